"""The laser-cut jigsaw puzzle of the paper's section 6: pieces, hexagon ring, frame.

Pieces are the tiles of the level-t snub weave: octagons (two pentagons glued along a Z middle
edge) and, for every boundary pentagon (its middle edge on the boundary), an *enneagon*: the
pentagon glued to the regular hexagon built outward on that middle edge. The boundary of a snub
level turns by +-60 degrees between equal edges along each input edge, so the hexagons on its
outer side are cells of one honeycomb per input edge: an almost complete ring.

Decisions (documented here and in the README):

- **Unclaimed ring hexagons are part of the frame.** Only hexagons across a boundary middle edge
  become (parts of) pieces; every other ring cell stays in the frame board, whose inner outline
  therefore follows the hexagons of the enneagons, so each enneagon sits in a hexagonal notch
  that fixes its orientation. The unclaimed cells' free edges are offered as a *score* layer so
  the hexagon pattern (the paper's nod to the Koch curve) shows on the frame without cutting it.
- **The corners of the input polygon, where the two honeycombs of neighbouring sides do not
  meet, are part of the frame** (the wedge between the last cell of one side and the first of
  the next). Cells that would overlap the mesh or an earlier cell are dropped (claimed cells
  first); on the pentagon none overlap.
- **The frame** grows from the input's outline (the paper's pentagon) or from the ring's outer
  boundary (any other shape) to the asked ``size``: see ``frame_size``.
- **Straight runs.** The ring follows every edge of the input's outline: its snub levels turn
  by +-60 degrees along each edge, so each edge carries one row of hexagons, and the corners
  between edges are left to the frame. A drawn curve is therefore first redrawn as runs of
  one length (``readers``' ``runs``, what the puzzle command asks for), so the ring keeps one
  size all round; where a shallow corner makes the cells of neighbouring runs overlap, the
  later cell stays in the frame.
- **Pieces must be cuttable.** A level whose pentagons turn over (self-intersect, as at a
  star's sharp tips after a few steps) is refused with where it happens.

The frame's outer outline and size are in ``frame_size``, colours in ``colouring``, cut files
in ``files``, painting guides in ``guides``.
"""

from __future__ import annotations

import math

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
import shapely
from numpy.typing import NDArray

from ..errors import MeshError, TurnedOverError, WeaveCutError
from ..graphs import components
from ..mesh import Mesh
from ..numeric import offsets_of
from ..subdivision.hierarchy import Level
from ..weave.model import Weave
from ..weave.snub_weave import snub_weaves
from ..layout.weave_figure import tile_rings
from .frame_size import MEASURES, frame_outline, frame_scale, ring_offset

OCTAGON, ENNEAGON = 0, 1
KIND_NAMES = ("octagon", "enneagon")
_SIN60, _COS60 = np.sqrt(3.0) / 2.0, 0.5


@dataclass(frozen=True, eq=False)
class Puzzle:
    """All geometry in millimetres, centred on the input's vertex mean.

    Parameters
    ----------
    pieces : (P,) shapely Polygons, counter-clockwise; octagons first, then enneagons
    kinds : (P,) int8, OCTAGON or ENNEAGON
    piece_tiles : (P,) int32, the level-t weave tile of every piece
    hexagons : (P,) shapely Polygons, the ring hexagon of an enneagon (None for octagons)
    ring : (K,) shapely Polygons, unclaimed ring hexagons (part of the frame)
    outer : shapely Polygon, the frame's outer outline
    hierarchy, weaves : levels 0..t and the weaves of levels 1..t (with lineage)
    scale : mm per model unit
    centre : the input's vertex mean (model units), at the origin in mm
    frame_width : mm of frame beyond the ring
    measure : what ``size`` measured, "diagonal" or "width" (see ``extent``)
    """

    pieces: NDArray[np.object_]
    kinds: NDArray[np.int8]
    piece_tiles: NDArray[np.int32]
    hexagons: NDArray[np.object_]
    ring: NDArray[np.object_]
    outer: shapely.Polygon
    hierarchy: tuple[Level, ...]
    weaves: list[Weave]
    scale: float
    centre: tuple[float, float]
    frame_width: float
    measure: str = "diagonal"

    @property
    def levels(self) -> int:
        return len(self.hierarchy) - 1

    @property
    def n_pieces(self) -> int:
        return len(self.pieces)

    @cached_property
    def hole(self) -> shapely.Polygon:
        """The frame's hole: the union of all pieces."""
        return shapely.union_all(self.pieces, grid_size=None)

    @cached_property
    def frame(self) -> shapely.Polygon:
        """The frame board: the outer outline minus the hole."""
        return shapely.Polygon(self.outer.exterior, [self.hole.exterior])

    def counts(self) -> dict[str, int]:
        """Pieces by type, plus the unclaimed ring hexagons."""
        out = {name: int((self.kinds == k).sum()) for k, name in enumerate(KIND_NAMES)}
        out["ring hexagons in the frame"] = len(self.ring)
        return out

    def to_mm(self, xy: NDArray[np.float64]) -> NDArray[np.float64]:
        return (np.asarray(xy, dtype=float) - self.centre) * self.scale


def build_puzzle(hierarchy: tuple[Level, ...], size: float = 500.0,
                 frame_width: float = 20.0, measure: str = "diagonal") -> Puzzle:
    """Cut the last level of a snub ``hierarchy`` into puzzle pieces inside a frame.

    Parameters
    ----------
    hierarchy : snub levels 0..t, t >= 2 (the front shows level t-1, whose colours need the
        level t-2 strands); the command builds it (``subdivide(mesh, t)``)
    size : mm, the diagonal of the frame's outer outline (its largest vertex distance): 50 cm
        in the paper, where the surrounding pentagon is the frame; or its width (``measure``)
    frame_width : mm of frame beyond the ring's outermost point
    measure : "diagonal" (the paper's pentagon) or "width" (any other shape)
    """
    levels = len(hierarchy) - 1
    if levels < 2:
        raise WeaveCutError(f"a puzzle needs --levels >= 2 (front shows level t-1), got {levels}")
    if not (size > 0 and frame_width > 0):
        raise WeaveCutError("size and frame width must be positive")
    if measure not in MEASURES:
        raise WeaveCutError(f"unknown size measure {measure!r}; choose one of "
                            f"{', '.join(MEASURES)}")
    _check_cuttable(hierarchy[-1].mesh, fewer=levels > 2)
    weaves = snub_weaves(hierarchy)
    mesh = hierarchy[0].mesh
    v0 = mesh.vertices
    centre = tuple(float(c) for c in v0.mean(axis=0))
    diagonal = float(np.max(np.linalg.norm(v0[:, None] - v0[None], axis=2)))
    weave = weaves[-1]
    level_mesh = weave.mesh

    def to_model(xy):  # centred model units; scaled to mm once the frame's size is solved
        return np.asarray(xy, dtype=float) - centre

    coords, offsets = tile_rings(weave)
    lone = np.diff(weave.tile_offsets) == 1
    ring_id = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
    octagon_xy = to_model(coords[~lone[ring_id]])
    octagon_sizes = np.diff(offsets)[~lone]
    octagon_tiles = np.flatnonzero(~lone).astype(np.int32)

    # the ring: a hexagon outward on every boundary half-edge (interior on its left)
    bhe = np.flatnonzero(level_mesh.topology.twin < 0)
    a = to_model(level_mesh.vertices[level_mesh.face_indices[bhe]])
    b = to_model(level_mesh.vertices[level_mesh.face_indices[level_mesh.next_half_edge[bhe]]])
    face = level_mesh.half_edge_face[bhe]
    claimed = (bhe - level_mesh.face_offsets[face]) == 1  # local edge 1: the Z middle edge
    cells = _outer_hexagons(a, b)  # (B, 6, 2): b, a, then four new corners
    keep = _non_overlapping(cells, claimed, level_mesh, to_model)
    lone_tiles = weave.face_tile[face[claimed & keep]]
    mesh_faces = level_mesh.dense_faces()
    pent = to_model(level_mesh.vertices[mesh_faces[face[claimed & keep]]])  # (N, 5, 2)
    hexes = cells[claimed & keep]
    # enneagon, counter-clockwise: p1, four hexagon corners, p2, p3, p4, p0
    ennea = np.concatenate([hexes[:, 1:], pent[:, 2:], pent[:, :1]], axis=1)
    # boundary pentagons whose hexagon was dropped stay plain pentagons (never on the pentagon)
    dropped = np.flatnonzero(lone & ~np.isin(np.arange(len(lone)), lone_tiles))
    plain = to_model(level_mesh.vertices[mesh_faces[weave.tile_faces[weave.tile_offsets[
        dropped]]]])
    ring_cells = _unique_cells(cells[~claimed & keep], hexes)

    # one coordinate per corner: computed hexagon corners snap onto mesh vertices and each other
    parts = [octagon_xy, ennea.reshape(-1, 2), plain.reshape(-1, 2), hexes.reshape(-1, 2),
             ring_cells.reshape(-1, 2)]
    snapped = _snap(np.concatenate(parts), tol=1e-6 * diagonal)
    outline = _outline(mesh, to_model)
    if measure == "diagonal":
        depth = float(np.max(shapely.distance(shapely.points(snapped), outline)))
        base, grow = outline, lambda s: frame_outline(outline, depth, frame_width, s)
    else:
        base = _one_region(np.concatenate(_shapes(snapped, parts, octagon_sizes)[::2]))
        grow = lambda s: ring_offset(base, frame_width, s)  # noqa: E731
    grow = lru_cache(maxsize=2)(grow)  # the root search ends where the outline is wanted
    scale = frame_scale(base, grow, size, measure, frame_width)
    pieces, hexes, ring = _shapes(snapped * scale, parts, octagon_sizes)
    hole = _checked_union(pieces)
    kinds = np.repeat(np.array([OCTAGON, ENNEAGON, ENNEAGON], dtype=np.int8),
                      [len(octagon_sizes), len(ennea), len(plain)])
    tiles = np.concatenate([octagon_tiles, lone_tiles, dropped]).astype(np.int32)
    hex_polys = np.concatenate([np.full(len(octagon_sizes), None, dtype=object), hexes,
                                np.full(len(plain), None, object)])
    outer = grow(scale)
    puzzle = Puzzle(pieces, kinds, tiles, hex_polys, ring, outer, tuple(hierarchy), weaves,
                    scale, centre, frame_width, measure)
    puzzle.__dict__["hole"] = hole  # its cached ``hole``: the union just checked, not made twice
    return puzzle


SLIVER = 1e-8  # of the puzzle's area: a gap or overlap smaller than this is rounding


def _one_region(pieces: np.ndarray) -> shapely.Polygon:
    """The outline of the pieces' union (:func:`_checked_union`)."""
    return shapely.Polygon(_checked_union(pieces).exterior)


def _checked_union(pieces: np.ndarray) -> shapely.Polygon:
    """The pieces' union (``shapely.union_all``); MeshError unless each piece is a valid polygon and
    together they cover one region without overlaps or gaps between them (a ring hexagon
    dropped where two runs of the boundary meet can leave one). Slivers far below any cutter's
    resolution (ring corners computed a few micrometres off a mesh vertex) are not gaps."""
    flat = ~shapely.is_valid(pieces)
    if flat.any():
        x, y = shapely.get_coordinates(pieces[flat][0])[0]
        raise MeshError(f"{flat.sum()} of the puzzle's pieces collapse to a line or a point "
                        f"(the first at ({x:.1f}, {y:.1f})): the mesh has faces too thin "
                        "there; mesh the outline with another --cell")
    union = shapely.union_all(pieces)
    tiny = SLIVER * union.area
    overlap = float(shapely.area(pieces).sum() - union.area)
    if overlap > tiny:
        a, b = shapely.STRtree(pieces).query(pieces, predicate="intersects")
        shared = shapely.intersection(pieces[a[a < b]], pieces[b[a < b]])  # also one inside
        largest = shared[np.argmax(shapely.area(shared))]
        x, y = shapely.get_coordinates(shapely.centroid(largest))[0]
        raise MeshError(f"the puzzle's pieces overlap ({overlap:.3g} square units in all, the "
                        f"first near ({x:.1f}, {y:.1f})): the mesh has faces too thin for the "
                        "hexagon ring there; mesh the outline with another --cell")
    parts = getattr(union, "geoms", [union])
    gaps = [r for p in parts for r in p.interiors if shapely.Polygon(r).area > tiny]
    if len(parts) == 1 and not gaps:
        return union
    where = (f", one {np.hypot(gaps[0].centroid.x, gaps[0].centroid.y):.0f} mm from the centre"
             if gaps else "")
    what = (f"{len(gaps)} gap{'s' * (len(gaps) > 1)} between them{where}" if gaps
            else "separate parts")
    raise MeshError(f"the puzzle's pieces leave {what}: the hexagon ring does not close "
                    "around this mesh; mesh the outline with another --cell")


def _check_cuttable(mesh: Mesh, fewer: bool = True) -> None:
    """Refuse a level with faces that turn over (a pentagon crossing itself cannot be cut);
    the message suggests fewer levels where there can be fewer."""
    rings = shapely.linearrings(mesh.vertices[mesh.face_indices], indices=mesh.half_edge_face)
    simple = shapely.is_simple(rings)
    if simple.all():
        return
    where = mesh.vertices[mesh.dense_faces()[np.flatnonzero(~simple)[0]]].mean(axis=0)
    raise TurnedOverError(f"{int((~simple).sum())} pentagons of the last level turn over (the "
                        f"first near ({where[0]:.4g}, {where[1]:.4g}) in input units), so they "
                        "cannot be cut (sharp corners and slim faces do this); "
                        f"{'use fewer --levels, or ' if fewer else ''}mesh a drawing with "
                        "another --cell or --mesh tri")


def _shapes(points: NDArray[np.float64], parts: list, octagon_sizes) -> tuple:
    """Pieces (octagons, enneagons, plain pentagons), claimed hexagons and ring cells as
    polygons, from the snapped corners of ``parts`` (as ``build_puzzle`` lists them)."""
    bounds = np.cumsum([0] + [len(p) for p in parts])
    octagon_xy, ennea, plain, hexes, ring_cells = (
        points[bounds[k]:bounds[k + 1]].reshape(parts[k].shape if k == 0 else (-1,) + shape)
        for k, shape in enumerate([None, (9, 2), (5, 2), (6, 2), (6, 2)]))
    octagons = _polygons(octagon_xy, offsets_of(octagon_sizes))
    pieces = np.concatenate([octagons, shapely.polygons(ennea), shapely.polygons(plain)])
    ring = shapely.polygons(ring_cells) if len(ring_cells) else np.empty(0, dtype=object)
    return pieces, shapely.polygons(hexes), ring


def _polygons(coords: NDArray[np.float64], offsets: NDArray[np.int64]) -> NDArray[np.object_]:
    ring_id = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
    return shapely.polygons(shapely.linearrings(coords, indices=ring_id))


def _outer_hexagons(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    """(B, 6, 2) regular hexagons on the right of every a -> b, counter-clockwise from b.

    Walking b -> a keeps the hexagon on the left; each next side turns 60 degrees left."""
    out = np.empty((len(a), 6, 2))
    out[:, 0], out[:, 1] = b, a
    step = a - b
    for k in range(2, 6):  # four corners, each one column of the batch
        step = np.column_stack([_COS60 * step[:, 0] - _SIN60 * step[:, 1],
                                _SIN60 * step[:, 0] + _COS60 * step[:, 1]])
        out[:, k] = out[:, k - 1] + step
    return out


def _non_overlapping(cells, claimed, level_mesh: Mesh, to_mm) -> NDArray[np.bool_]:
    """(B,) True for ring cells kept: no overlap with the mesh or an earlier kept cell.

    A cell on several boundary edges appears once per edge; copies are not conflicts. Claimed
    cells win over unclaimed ones, then the earlier edge."""
    polys = shapely.polygons(cells)
    scale = np.linalg.norm(cells[:, 0] - cells[:, 1], axis=1)
    centres = cells.mean(axis=1)
    tol = 1e-6 * float(scale.mean()) ** 2
    keep = _overlap(polys, shapely.polygons(to_mm(level_mesh.vertices[
        level_mesh.dense_faces()]))) <= tol
    tree = shapely.STRtree(polys)
    i, j = tree.query(polys, predicate="intersects")
    pair = i < j
    i, j = i[pair], j[pair]
    same = np.linalg.norm(centres[i] - centres[j], axis=1) < 1e-3 * scale[i]
    keep[j[same & claimed[i] & claimed[j]]] = False  # one hexagon, two middle edges: first wins
    i, j = i[~same], j[~same]
    if len(i):
        area = shapely.area(shapely.intersection(polys[i], polys[j]))
        i, j = i[area > tol], j[area > tol]
    if len(i):  # rare (not on the pentagon): resolve conflicts greedily, claimed first
        order = np.lexsort((np.arange(len(cells)), ~claimed))
        rank = np.empty(len(cells), dtype=np.int64)
        rank[order] = np.arange(len(cells))
        first, second = np.where(rank[i] < rank[j], i, j), np.where(rank[i] < rank[j], j, i)
        for k in np.argsort(rank[first], kind="stable").tolist():  # conflicts only
            if keep[first[k]]:
                keep[second[k]] = False
    return keep  # copies of an unclaimed cell that is claimed elsewhere: see _unique_cells


def _overlap(polys: NDArray[np.object_], faces: NDArray[np.object_]) -> NDArray[np.float64]:
    """(N,) the area every polygon shares with the faces of a mesh (which do not overlap one
    another): summed over the faces it meets, without their union (a ring cell meets a few)."""
    i, j = shapely.STRtree(faces).query(polys, predicate="intersects")
    area = shapely.area(shapely.intersection(polys[i], faces[j]))
    return np.bincount(i, weights=area, minlength=len(polys))


def _snap(points: NDArray[np.float64], tol: float) -> NDArray[np.float64]:
    """Points within ``tol`` (inclusive) merged onto the first of their cluster."""
    geoms = shapely.points(points)
    i, j = shapely.STRtree(geoms).query(geoms, predicate="dwithin", distance=tol)
    pair = i < j
    if not pair.any():
        return points
    n = len(points)
    label = components(n, i[pair], j[pair])[1]
    first = np.full(label.max() + 1, n, dtype=np.int64)
    np.minimum.at(first, label, np.arange(n))
    return points[first[label]]


def _unique_cells(cells: NDArray[np.float64], claimed_cells: NDArray[np.float64]):
    """Unclaimed cells (K, 6, 2), each once, without those also claimed by another edge."""
    if not len(cells):
        return cells
    side = math.hypot(*(cells[0, 0] - cells[0, 1]))
    key = np.round(cells.mean(axis=1) / (side * 1e-3)).astype(np.int64)
    taken = np.round(claimed_cells.mean(axis=1) / (side * 1e-3)).astype(np.int64)
    _, first = np.unique(key, axis=0, return_index=True)
    first = np.sort(first)
    if len(taken):
        both = np.concatenate([key[first], taken])
        _, inverse, counts = np.unique(both, axis=0, return_inverse=True, return_counts=True)
        first = first[counts[inverse.reshape(-1)[:len(first)]] == 1]
    return cells[first]


def _outline(mesh: Mesh, to_model) -> shapely.Polygon:
    """The input mesh's outer outline (holes filled), in centred model units."""
    outline = shapely.union_all(shapely.polygons(shapely.linearrings(
        to_model(mesh.vertices[mesh.face_indices]), indices=mesh.half_edge_face)))
    return shapely.Polygon(outline.exterior)
