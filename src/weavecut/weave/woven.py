"""The woven model in 3-D: every strand of a snub weave as the strip of paper it is, raised
where it passes over and lowered where it passes under, flat or on a surface in space.

A strand's strip is the union of the tiles it visits (as :mod:`weavecut.papermodel` prints it),
so the strips together cover the surface. At every visit the strip lies ``lift`` above the
surface where the strand is on top and ``lift`` below where it passes under; it comes back to
the surface only on the edges it shares with the tile it comes from or goes to. Each tile is
triangulated once (a ring of its outline, an inner ring at ``INNER`` of the way to its centre,
the centre), and both strands that cross there use that triangulation, so the height between
them is linear on every triangle: at least ``lift`` wherever at most one of them is on the
surface. At a corner where both cross an edge (three tiles meet and each pair crosses the other
way round, which no heights can satisfy) the corner is cut off every strip by ``CUT`` of its
shortest edge, a small hole the coverage figure counts.

Lengths are in mesh units; heights go along the surface's normal (+z for a flat weave), and on
a surface whose vertices lie on a sphere every point is first put on the sphere.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import MeshError
from ..numeric import among, distinct, snap, unique_rows
from ..surface import circumsphere, face_normals, onto_sphere
from .model import Weave, tile_ring_ids

INNER = 0.75  # the inner ring, from the centre: the strip ramps to the surface outside it
CUT = 0.06  # of the shortest edge at a corner both strands of a tile cross at


@dataclass(frozen=True, eq=False)
class Model:
    """Coloured triangles in space, in named parts (a strand, a puzzle piece's face, ...).

    Parameters
    ----------
    vertices : (N, 3) float64
    normals : (N, 3) float64, unit, for smooth shading
    triangles : (M, 3) int64, counter-clockwise seen from the side the normals point to
    part : (M,) int64, the part of every triangle
    colours : (P,) "#rrggbb" of every part
    names : (P,) name of every part
    """

    vertices: NDArray[np.float64]
    normals: NDArray[np.float64]
    triangles: NDArray[np.int64]
    part: NDArray[np.int64]
    colours: tuple[str, ...]
    names: tuple[str, ...]

    def scaled(self, factor: float, origin=(0.0, 0.0, 0.0)) -> Model:
        """The model moved by ``-origin`` and scaled by ``factor``."""
        return Model((self.vertices - np.asarray(origin, dtype=float)) * factor, self.normals,
                     self.triangles, self.part, self.colours, self.names)


def smooth_normals(vertices: NDArray[np.float64], triangles: NDArray[np.int64]
                   ) -> NDArray[np.float64]:
    """(N, 3) unit normal of every vertex: its triangles' normals weighted by their areas
    (a vertex in no triangle gets +z)."""
    c = vertices[triangles]
    cross = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    total = np.column_stack([np.bincount(triangles.ravel(), weights=np.repeat(cross[:, k], 3),
                                         minlength=len(vertices)) for k in range(3)])
    length = np.sqrt((total * total).sum(axis=1))
    return np.where(length[:, None] > 0, total / np.maximum(length, 1e-300)[:, None], [0, 0, 1])


def merged(points: NDArray[np.float64], group: NDArray[np.int64], triangles: NDArray[np.int64]
           ) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.bool_]]:
    """Points of one ``group`` at the same place (to ``numeric.GRID``) made one vertex:
    (vertices, triangles, which triangles are kept: those with three distinct corners)."""
    first, inverse = unique_rows(np.column_stack([group, snap(points)]))
    tri = inverse[triangles]
    keep = (tri[:, 0] != tri[:, 1]) & (tri[:, 1] != tri[:, 2]) & (tri[:, 0] != tri[:, 2])
    return points[first], tri, keep


def _sphere(weave: Weave):
    """(centre, radius) when the surface's vertices lie on a sphere, else None."""
    v = weave.mesh.vertices
    if weave.mesh.dim != 3:
        return None
    try:
        return circumsphere(v)
    except MeshError:
        return None


def _vertex_normals(weave: Weave) -> NDArray[np.float64]:
    """(V, 3) unit normal of every mesh vertex: the mean of its faces' unit normals."""
    mesh = weave.mesh
    if mesh.dim == 2:
        return np.tile([0.0, 0.0, 1.0], (mesh.n_vertices, 1))
    corner = face_normals(mesh)[mesh.half_edge_face]
    total = np.column_stack([np.bincount(mesh.face_indices, weights=corner[:, k],
                                         minlength=mesh.n_vertices) for k in range(3)])
    return total / np.sqrt((total * total).sum(axis=1))[:, None]


def _corner_cut(weave: Weave) -> NDArray[np.float64]:
    """(V,) how far a cut corner is cut back along its edges: ``CUT`` of its shortest edge."""
    mesh = weave.mesh
    edges = mesh.topology.edges
    d = mesh.vertices[edges[:, 0]] - mesh.vertices[edges[:, 1]]
    length = np.sqrt((d * d).sum(axis=1))
    shortest = np.full(mesh.n_vertices, np.inf)
    np.minimum.at(shortest, edges[:, 0], length)
    np.minimum.at(shortest, edges[:, 1], length)
    return CUT * shortest


def woven_model(weave: Weave, colours, lift: float, names=None) -> Model:
    """The strips of every strand of ``weave`` (a snub weave, flat or in space), one part per
    strand in ``colours[strand]``, ``lift`` (mesh units) over and under each other."""
    mesh = weave.mesh
    faces = mesh.dense_faces()
    if faces is None or faces.shape[1] != 5 or weave.n_tiles == 0:
        raise MeshError("a woven 3-D model needs a snub weave (pentagons glued into octagons)")
    v3 = mesh.vertices if mesh.dim == 3 else np.column_stack([mesh.vertices,
                                                              np.zeros(mesh.n_vertices)])
    ring_ids, ring_offsets = tile_ring_ids(weave)
    ring_size = np.diff(ring_offsets)
    tiles, over, strand = weave.strand_visits, weave.visit_over, weave.visit_strand
    n = len(tiles)
    start = np.repeat(weave.strand_offsets[:-1], np.diff(weave.strand_offsets))
    end = np.repeat(weave.strand_offsets[1:], np.diff(weave.strand_offsets))
    closed = weave.strand_closed[strand]
    k = np.arange(n)
    prev_tile = np.where(k > start, tiles[np.maximum(k - 1, 0)], np.where(closed, tiles[end - 1],
                                                                          -1))
    next_tile = np.where(k + 1 < end, tiles[np.minimum(k + 1, n - 1)],
                         np.where(closed, tiles[start], -1))
    prev_tile = np.where(prev_tile == tiles, -1, prev_tile)  # a loop of one tile
    next_tile = np.where(next_tile == tiles, -1, next_tile)
    # one row per ring corner of every visit
    size = ring_size[tiles]
    row_visit = np.repeat(k, size)
    row_first = np.repeat(np.cumsum(size) - size, size)
    local = np.arange(len(row_visit)) - row_first
    vid = ring_ids[ring_offsets[tiles[row_visit]] + local].astype(np.int64)
    n_v = mesh.n_vertices
    tile_keys = distinct(np.repeat(np.arange(weave.n_tiles), ring_size) * n_v + ring_ids)
    in_prev = (prev_tile[row_visit] >= 0) & among(prev_tile[row_visit] * n_v + vid, tile_keys)
    in_next = (next_tile[row_visit] >= 0) & among(next_tile[row_visit] * n_v + vid, tile_keys)
    on = in_prev | in_next  # the corner is on an edge the strand crosses
    after = row_first + (local + 1) % size[row_visit]  # the next corner of the ring
    before = row_first + (local - 1) % size[row_visit]
    edge_on = (in_prev & in_prev[after]) | (in_next & in_next[after])  # corner -> next corner
    # corners two strands of the tile cross at: cut off
    here = tiles[row_visit] * n_v + vid
    keys, counts = np.unique(here[on], return_counts=True)
    cut = among(here, keys[counts >= 2])
    rho = _corner_cut(weave)[vid]

    def towards(other):
        d = v3[vid[other]] - v3[vid]
        return v3[vid] + np.where(cut, rho, 0.0)[:, None] * d / np.sqrt((d * d).sum(
            axis=1))[:, None]

    # the outline: every corner twice (a, b), apart where the corner is cut
    outer = np.stack([towards(before), towards(after)], axis=1).reshape(-1, 3)
    on_outer = np.stack([np.where(cut, edge_on[before], on), np.where(cut, edge_on, on)],
                        axis=1).reshape(-1)
    ring_n = np.repeat(2 * size, 2 * size)
    ids = ring_ids[ring_offsets[tiles]]
    mids = ring_ids[ring_offsets[tiles] + 4]
    lone = size == 5
    centre = np.where(lone[:, None], 0.0, 0.5 * (v3[ids] + v3[mids]))
    if lone.any():
        centre[lone] = np.add.reduceat(v3[vid], np.cumsum(size) - size)[lone] / 5
    outer_visit = np.repeat(k, 2 * size)
    inner = centre[outer_visit] + INNER * (outer - centre[outer_visit])
    normal_outer = _vertex_normals(weave)[np.repeat(vid, 2)]
    normal_inner = _tile_normals(weave, v3)[tiles]
    sphere = _sphere(weave)
    if sphere is not None:
        for points in (outer, inner, centre):
            onto_sphere(points, *sphere)
        normal_outer = (outer - sphere[0]) / sphere[1]
        normal_inner = (inner - sphere[0]) / sphere[1]
        tile_n = (centre - sphere[0]) / sphere[1]
    else:
        tile_n = normal_inner
        normal_inner = normal_inner[outer_visit]
    # points of a visit: its outer ring (R), its inner ring (R), its centre
    block = 4 * size + 1
    block_first = np.cumsum(block) - block
    j = np.arange(len(outer)) - np.repeat(np.cumsum(2 * size) - 2 * size, 2 * size)
    r = ring_n
    base = block_first[outer_visit]
    o, o1 = base + j, base + (j + 1) % r
    i, i1 = o + r, o1 + r
    c = base + 2 * r
    triangles = np.concatenate([np.column_stack([o, o1, i1]), np.column_stack([o, i1, i]),
                                np.column_stack([i, i1, c])])
    points = np.empty((int(block.sum()), 3))
    up = np.empty_like(points)  # where every point goes per unit of height
    sign = np.where(over, 1.0, -1.0)
    points[o], up[o] = outer, np.where(on_outer, 0.0, sign[outer_visit])[:, None] * normal_outer
    points[i], up[i] = inner, sign[outer_visit][:, None] * normal_inner
    points[block_first + block - 1], up[block_first + block - 1] = centre, sign[:, None] * tile_n
    if sphere is not None:  # flat triangles between points of a sphere sag towards its centre
        lift = lift / _least_cos(points[triangles] - sphere[0])
    points += lift * up
    group = np.repeat(strand.astype(np.int64), block)
    vertices, triangles, keep = merged(points, group, triangles)
    triangles = triangles[keep]
    part = np.tile(strand[outer_visit], 3)[keep].astype(np.int64)
    names = tuple(names) if names is not None else tuple(f"strand {s + 1}"
                                                         for s in range(weave.n_strands))
    return Model(vertices, smooth_normals(vertices, triangles), triangles, part,
                 tuple(colours), names)


def _least_cos(corners: NDArray[np.float64]) -> float:
    """The least cosine between a triangle's centroid and its corners, seen from the origin,
    over ``corners`` (M, 3, 3): a plane through three points at radius r passes at r times it
    or more from the origin, so lifts divided by it clear as much along every ray."""
    unit = corners / np.sqrt((corners * corners).sum(axis=2))[:, :, None]
    mid = unit.sum(axis=1)
    mid /= np.sqrt((mid * mid).sum(axis=1))[:, None]
    return float((unit * mid[:, None]).sum(axis=2).min())


def _tile_normals(weave: Weave, v3: NDArray[np.float64]) -> NDArray[np.float64]:
    """(T, 3) unit normal of every tile: the mean of its faces' unit normals."""
    if weave.mesh.dim == 2:
        return np.tile([0.0, 0.0, 1.0], (weave.n_tiles, 1))
    total = np.add.reduceat(face_normals(weave.mesh)[weave.tile_faces], weave.tile_offsets[:-1])
    return total / np.sqrt((total * total).sum(axis=1))[:, None]


def woven_mm(weave: Weave, colours, mm_per_unit: float, thickness: float) -> Model:
    """The woven model in mm, centred on its box, strips ``thickness`` mm over and under each
    other (the over strip clears the under one by at least ``thickness``)."""
    model = woven_model(weave, colours, thickness / mm_per_unit)
    centre = (model.vertices.max(axis=0) + model.vertices.min(axis=0)) / 2
    return model.scaled(mm_per_unit, centre)
