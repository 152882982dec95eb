"""Strands of a weave on a surface in space, unfolded into the plane pentagon by pentagon.

A strand on a closed surface is a loop of octagons; its strip is the chain of the pentagons it
covers, in walking order: in a tile it passes over, first the pentagon joined to the previous
tile, then the one whose tip pokes into the next tile's notch; in a tile it passes under, first
the pentagon round the same face centre as the tip before it. Consecutive pentagons of the chain
share an edge (the middle edge of an octagon, or the edge from a tip to its face centre), and
the strip is unfolded along these edges:

- every pentagon is flattened on its own: its corners are projected onto the plane that fits
  them best (least squares, oriented by the face's outward normal, so nothing is mirrored);
- each pentagon is turned and moved in the plane so that its edge shared with the previous
  pentagon lies on that pentagon's (midpoints together, directions along each other), and the
  two corners of that edge are then taken from the previous pentagon, so neighbours share
  their common edge exactly;
- the edges joining pentagons are folds: the surface bends there by the angle between the two
  best-fit planes. Round a notch the third edge (from the notch corner to an old vertex of the
  mesh) is left open: there the strip is slit, by the angle the surface curves at that corner.

What flattening costs is measured, not assumed: each pentagon's non-planarity (largest
distance of a corner from its plane, as a share of the pentagon's diameter) and every
unfolded edge's length against its length in space.

A loop closes with a glue band: the strip runs one tile past its start, and that last tile is
glued under the first. Where the unfolded strip would overlap itself or outgrow the page, it is
cut into pieces of whole tiles, each piece ending with a glue band that goes under the first
tile of the next piece; joint j (band "glue j") meets the tile marked "j".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from numpy.typing import NDArray

from ..errors import WeaveCutError
from ..numeric import dot, plane_normals
from ..surface import face_normals
from ..weave.model import Weave

OVERLAP = 1e-3  # share of a tile's area two tiles of one piece may overlap (rounding)
DASH, DASH_GAP = 2.0, 1.5  # mm, fold lines


class UnfoldError(WeaveCutError, ValueError):
    """A strand that cannot be unfolded (consecutive tiles share no edge, or a tile alone
    does not fit the page)."""


@dataclass(frozen=True, eq=False)
class Flat:
    """Every pentagon of a snub level flattened on its own best-fit plane.

    Parameters
    ----------
    coords : (F, 5) complex, the corners in the plane (x + iy), counter-clockwise seen from
        outside, centred on the corners' mean
    non_planarity : (F,) largest distance of a corner from the plane / the pentagon's diameter
    normals : (F, 3) unit normal of each plane, turned outwards
    centres : (F, 3) mean of each pentagon's corners
    """

    coords: NDArray[np.complex128]
    non_planarity: NDArray[np.float64]
    normals: NDArray[np.float64]
    centres: NDArray[np.float64]


def flatten(weave: Weave) -> Flat:
    """Every face of ``weave.mesh`` (pentagons, in space) projected onto its best-fit plane
    (least squares, through the corners' mean: :func:`~weavecut.numeric.plane_normals`, the same
    bits on every machine, where an SVD's are not), x towards corner 0."""
    mesh = weave.mesh
    faces = mesh.dense_faces()
    if faces is None or mesh.dim != 3:
        raise UnfoldError("unfolding needs a snub level of a surface in space (pentagons, x y z)")
    p = mesh.vertices[faces]  # (F, 5, 3)
    centres = p.mean(axis=1)
    x = p - centres[:, None]
    normal = plane_normals(x, face_normals(mesh))
    e1 = x[:, 0] - dot(x[:, 0], normal)[:, None] * normal  # towards corner 0, in the plane
    e1 /= np.linalg.norm(e1, axis=1)[:, None]
    e2 = np.cross(normal, e1)
    coords = dot(x, e1[:, None]) + 1j * dot(x, e2[:, None])
    height = np.abs(dot(x, normal[:, None])).max(axis=1)
    diameter = np.linalg.norm(p[:, :, None] - p[:, None], axis=-1).max(axis=(1, 2))
    return Flat(coords, height / diameter, normal, centres)


@dataclass(frozen=True, eq=False)
class Unfolding:
    """One strand's chain of pentagons laid out in the plane (mesh units).

    Parameters
    ----------
    strand : the strand
    visits : (m,) visit numbers along the strand (a loop repeats visit 0 at the end: the glue
        band that closes it)
    tiles : (m,) tile of every visit
    over : (m,) True where the strand is on top
    faces : (K,) faces of the chain, two per visit of an octagon
    face_visit : (K,) the visit (index into ``visits``) of every face
    corners : (K, 5) complex, every face's corners in the plane, in the mesh's corner order
    stretch : (K, 5) every unfolded edge's length / its length in space, minus 1 (edge i runs
        from corner i to corner i + 1)
    folds : (K - 1, 2) complex, the edge joining face k to face k + 1
    fold_angles : (K - 1,) radians the surface turns at each fold, positive where it is convex
        (a mountain fold seen from the printed side, which faces out)
    """

    strand: int
    visits: NDArray[np.int64]
    tiles: NDArray[np.int32]
    over: NDArray[np.bool_]
    faces: NDArray[np.int64]
    face_visit: NDArray[np.int64]
    corners: NDArray[np.complex128]
    stretch: NDArray[np.float64]
    folds: NDArray[np.complex128]
    fold_angles: NDArray[np.float64]

    def tile_polygons(self) -> NDArray[np.object_]:
        """(m,) every visit's tile as one shapely Polygon (its faces joined)."""
        faces = shapely.polygons(np.stack([self.corners.real, self.corners.imag], axis=-1))
        return shapely.union(faces[0::2], faces[1::2])  # two faces a visit


def chain_faces(weave: Weave, s: int) -> tuple[NDArray[np.int64], NDArray[np.int64],
                                                   NDArray[np.int64]]:
    """(visits, faces, face_visit): the pentagons strand ``s`` covers, in chain order (see the
    module docstring); a loop repeats its first visit at the end."""
    mesh = weave.mesh
    dense = mesh.dense_faces()
    start, end = int(weave.strand_offsets[s]), int(weave.strand_offsets[s + 1])
    tiles = weave.strand_visits[start:end]
    over = weave.visit_over[start:end]
    sizes = np.diff(weave.tile_offsets)[tiles]
    if (sizes != 2).any():
        raise UnfoldError(f"strand {s} crosses a boundary pentagon; only octagons unfold")
    pair = weave.tile_faces[weave.tile_offsets[tiles][:, None] + np.arange(2)]  # (n, 2)
    # over: the pentagon whose tip (corner 4) touches the next tile goes second
    nxt = np.roll(pair, -1, axis=0)
    tip_next = (dense[pair[:, 0], 4][:, None] == dense[nxt].reshape(len(pair), -1)).any(axis=1)
    over_pair = np.where(tip_next[:, None], pair[:, ::-1], pair)
    # under: the pentagon round the same face centre (corner 0) as the tip before it
    tip_before = np.roll(over_pair[:, 1], 1)
    same = (dense[pair[:, 0]] == dense[tip_before, 0][:, None]).any(axis=1)
    under_pair = np.where(same[:, None], pair, pair[:, ::-1])
    ordered = np.where(over[:, None], over_pair, under_pair)
    visits = np.arange(len(tiles))
    if weave.strand_closed[s]:
        visits = np.r_[visits, 0]
    faces = ordered[visits].ravel().astype(np.int64)
    return visits, faces, np.repeat(np.arange(len(visits)), 2)


def unfold(weave: Weave, s: int, flat: Flat | None = None) -> Unfolding:
    """Strand ``s`` of ``weave`` (a snub weave on a surface) unfolded into the plane."""
    flat = flatten(weave) if flat is None else flat
    mesh = weave.mesh
    dense = mesh.dense_faces()
    visits, faces, face_visit = chain_faces(weave, s)
    ids = dense[faces]  # (K, 5)
    k = len(faces)
    # the edge face j - 1 and face j share: two corners of each
    same = ids[:-1, :, None] == ids[1:, None, :]  # (K-1, 5 of the earlier, 5 of the later)
    count = same.sum(axis=(1, 2))
    if (count != 2).any():
        bad = int(np.argmax(count != 2))
        raise UnfoldError(f"strand {s}: pentagons {bad + 1} and {bad + 2} of its chain share "
                          f"{int(count[bad])} corners, not an edge")
    joint, earlier, later = np.nonzero(same)  # sorted by joint: two rows each
    earlier, later = earlier.reshape(-1, 2), later.reshape(-1, 2)
    rows = np.arange(k - 1)[:, None]
    w = flat.coords[faces]  # (K, 5) each face in its own plane
    a_end, b_end = w[rows, earlier], w[rows + 1, later]  # (K-1, 2) the edge in both frames
    turn = (a_end[:, 1] - a_end[:, 0]) / (b_end[:, 1] - b_end[:, 0])
    turn /= np.abs(turn)
    shift = a_end.mean(axis=1) - turn * b_end.mean(axis=1)
    # compose z -> turn z + shift along the chain: face j's map is A_j z + B_j
    big_a = np.cumprod(np.r_[1.0 + 0j, turn])
    big_b = np.cumsum(np.r_[0j, big_a[:-1] * shift])
    placed = (big_a[:, None] * w + big_b[:, None]).ravel()
    # a corner shared with the face before takes that face's position (exact shared edges)
    source = np.arange(5 * k)
    source[5 * (joint + 1) + later.ravel()] = 5 * joint + earlier.ravel()
    while True:  # a corner is shared by at most a few faces in a row
        deeper = source[source]
        if (deeper == source).all():
            break
        source = deeper
    corners = placed[source].reshape(k, 5)
    p = mesh.vertices[ids]
    length = np.linalg.norm(np.roll(p, -1, axis=1) - p, axis=-1)
    stretch = np.abs(np.roll(corners, -1, axis=1) - corners) / length - 1.0
    folds = corners[rows + 1, later]
    n0, n1 = flat.normals[faces[:-1]], flat.normals[faces[1:]]
    angle = np.arccos(np.clip(dot(n0, n1), -1.0, 1.0))
    convex = dot(flat.centres[faces[1:]] - flat.centres[faces[:-1]], n0) <= 0
    start = int(weave.strand_offsets[s])
    tiles = weave.strand_visits[start + visits]
    over = weave.visit_over[start + visits]
    return Unfolding(int(s), visits, tiles, over, faces, face_visit, corners, stretch, folds,
                     np.where(convex, angle, -angle))


def dashed(segments: NDArray[np.complex128], dash: float = DASH,
           gap: float = DASH_GAP) -> NDArray[np.object_]:
    """(L,) MultiLineStrings: every segment (L, 2) complex drawn as dashes, centred on it."""
    a, b = segments[:, 0], segments[:, 1]
    length = np.abs(b - a)
    n = np.maximum(np.floor((length + gap) / (dash + gap)), 1).astype(np.int64)
    used = np.minimum(n * (dash + gap) - gap, length)
    seg = np.repeat(np.arange(len(segments)), n)
    i = np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)
    unit = ((b - a) / np.maximum(length, 1e-12))[seg]
    t0 = (length[seg] - used[seg]) / 2 + i * (dash + gap)
    t1 = np.minimum(t0 + dash, length[seg])
    p0, p1 = a[seg] + unit * t0, a[seg] + unit * t1
    lines = shapely.linestrings(np.stack([np.column_stack([p0.real, p0.imag]),
                                          np.column_stack([p1.real, p1.imag])], axis=1))
    return shapely.multilinestrings(lines, indices=seg)
