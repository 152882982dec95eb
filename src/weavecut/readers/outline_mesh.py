"""Mesh the inside of an outline with convex, near-regular faces of a given size.

The faces start as the tessellation of the kind asked for (``tessellations``: Lloyd-relaxed
Voronoi cells for ``quad``, ``hex`` and ``voronoi``, clipped to the outline; a conforming
Delaunay triangulation for ``tri``); this module fits the cells to the outline.

A clipped cell is convex unless the outline has a reflex corner inside it; such a cell is cut
at that corner (``pieces.convex_pieces``) until every piece is convex, and pieces under 0.6
``cell`` are merged into a neighbour or cut anew with one, two or three of them
(``pieces.merged_small``). Every outline vertex stays a vertex, so the boundary is the
outline to the tolerance. The outline's edges are first cut to at most a cell's edge, where a
cell edge meets the outline it moves onto the nearer outline vertex beside it, inner cell
edges shorter than 0.15 ``cell`` collapse, and straight outline points of one face are
dropped: short edges and 180-degree corners make sliver pentagons, which turn over after a
few snub steps. None of these moves shrinks a face under half a cell (``SMALLEST``): a piece
too small to cut.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from scipy.spatial import cKDTree

from ..errors import MeshError
from ..mesh import Mesh
from ..text import counted
from ..mesh_geometry import corner_angles, signed_areas
from ..validation import validate
from . import KINDS
from .budgets import MAX_CELLS, MAX_GRID, amount
from .pieces import convex_pieces, merged_small
from .rings import close_groups, invalid_where, split_t_junctions, weld
from .tessellations import SPACING, _densified, _relaxed_cells, _triangles

DEFAULT_FACES = 60  # faces when no --cell is given
# outline edges are cut to at most a cell's edge (times cell), and cells meet them at vertices
EDGE = {"quad": 1.0, "hex": SPACING["hex"] / math.sqrt(3), "voronoi": 0.6}
SHORT = 0.15  # inner cell edges shorter than this (times cell) collapse
SMALLEST = 0.5  # tidying never shrinks a face under this (times cell): too small to cut
CORNER = 30.0  # degrees: where the outline turns by more, ``runs`` keeps a corner


def default_cell(region) -> float:
    """The cell size that gives about DEFAULT_FACES faces."""
    return math.sqrt(region.area / DEFAULT_FACES)


def mesh_outline(region, kind: str = "hex", cell: float | None = None,
                 tolerance: float = 0.2, runs: bool = False) -> Mesh:
    """Mesh the inside of ``region`` (a shapely Polygon or MultiPolygon, holes allowed).

    Parameters
    ----------
    region : the outline, in mm
    kind : one of KINDS
    cell : target face size in mm (faces of about cell**2 area); default: about 60 faces
    tolerance : how far (mm) the boundary may stray from ``region`` to keep faces convex
    runs : first redraw the outline as straight runs of one length (``_even_runs``), so the
        snub levels' boundary, and a puzzle's hexagon ring on it, keep one size all round

    Returns
    -------
    Mesh whose faces are convex and counter-clockwise and whose union is ``region``.
    """
    if kind not in KINDS:
        raise MeshError(f"unknown mesh kind {kind!r}; choose one of {', '.join(KINDS)}")
    if not region.area > 0:
        raise MeshError("the outline encloses no area")
    if not region.is_valid:
        what, (x, y) = invalid_where(region)
        raise MeshError(f"the outline is invalid ({what.lower()} near ({x:.4g}, {y:.4g}) mm, "
                        "y up): its rings must not cross themselves or one another")
    cell = default_cell(region) if cell is None else cell
    if not 0 < cell < math.inf:
        raise MeshError(f"--cell {cell:g} mm is not a positive length")
    if region.area < 0.5 * cell ** 2:
        raise MeshError(f"the outline ({region.area:.4g} mm²) is smaller than one cell "
                        f"({cell:.4g} mm across); give a smaller --cell")
    _check_budget(region, kind, cell, tolerance)
    if runs:
        region = _rings_mapped(region, lambda ring: _even_runs(ring, EDGE.get(kind, 0.6) * cell))
    if kind == "tri":
        return _triangles(shapely.simplify(region, tolerance / 2), cell)
    # no outline edge shorter than needed (Douglas-Peucker, half the tolerance), none longer
    # than a cell's edge
    region = _densified_region(region if runs else shapely.simplify(region, tolerance / 2),
                               EDGE[kind] * cell)
    _, cells = _relaxed_cells(region, kind, cell)
    pieces = merged_small([q for c in shapely.get_parts(cells)
                           for q in convex_pieces(c, tolerance)], cell)
    rings = [np.asarray(shapely.orient_polygons(p).exterior.coords)[:-1] for p in pieces]
    parts = shapely.get_parts(region)
    euler = len(parts) - sum(len(p.interiors) for p in parts)  # V - E + F of its meshes
    for snap, short in ((EDGE[kind], SHORT), (EDGE[kind], 0.0), (0.0, 0.0)):  # tidiest valid
        smallest = (SMALLEST * cell) ** 2
        tidy = _short_inner_edges_merged(_snapped(rings, region, snap * cell, smallest),
                                         region, short * cell, smallest)
        try:
            mesh = validate(_without_straight_corners(
                split_t_junctions(weld(tidy, 1e-9 * cell)[0], 1e-9 * cell)))
        except MeshError as exc:
            error = exc
            continue
        # merging short edges can move a corner off the neighbour's edge it lay on, which
        # opens a gap between the faces: a hole the outline does not have (Euler's formula)
        gaps = euler - (mesh.n_vertices - mesh.topology.n_edges + mesh.n_faces)
        if gaps == 0:
            return mesh
        error = MeshError(f"the faces leave {counted(gaps, 'gap')} between them")
    raise MeshError(f"meshing the outline failed ({error}); try another --cell")


def _check_budget(region, kind: str, cell: float, tolerance: float) -> None:
    """Refuse, before any cell is made, an outline whose faces and outline points (simplified
    to the tolerance, then cut to a cell's edge) would pass MAX_CELLS, or whose bounding box
    would hold more than MAX_GRID cells (lattice points or seeds are laid over all of it)."""
    faces = region.area / cell ** 2
    outline = (shapely.get_num_coordinates(shapely.simplify(region, tolerance / 2))
               + region.length / (EDGE.get(kind, 1.0) * cell))
    if faces + outline > MAX_CELLS:
        raise MeshError(f"--cell {cell:.4g} mm would give about {amount(faces)} faces "
                        f"({region.area:,.6g} mm²) and {amount(outline)} outline points; at "
                        f"most {MAX_CELLS:,} in all: give a larger --cell")
    x0, y0, x1, y1 = region.bounds
    grid = (x1 - x0 + 2 * cell) * (y1 - y0 + 2 * cell) / cell ** 2
    if grid > MAX_GRID:
        raise MeshError(f"--cell {cell:.4g} mm would lay {amount(grid)} cells over the "
                        f"outline's bounding box ({x1 - x0:.4g} x {y1 - y0:.4g} mm) for "
                        f"{amount(faces)} inside it; at most {MAX_GRID:,}: give a larger --cell")


def _without_straight_corners(mesh: Mesh) -> Mesh:
    """``mesh`` without the outline points that only one face uses where the outline runs
    straight (180 degree corners make degenerate pentagons in a snub step)."""
    p = mesh.vertices[mesh.face_indices]
    a = p - p[mesh.prev_half_edge]
    b = p[mesh.next_half_edge] - p
    sine = (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) / (np.hypot(*a.T) * np.hypot(*b.T))
    alone = np.bincount(mesh.face_indices, minlength=mesh.n_vertices)[mesh.face_indices] == 1
    keep = ~(alone & (np.abs(sine) < 1e-9) & ((a * b).sum(axis=1) > 0))
    used, corners = np.unique(mesh.face_indices[keep], return_inverse=True)
    sizes = np.bincount(mesh.half_edge_face[keep], minlength=mesh.n_faces)
    return Mesh(mesh.vertices[used], np.concatenate([[0], np.cumsum(sizes)]), corners)


def _short_inner_edges_merged(rings: list[np.ndarray], region, short: float,
                              smallest: float = 0.0) -> list[np.ndarray]:
    """Inner cell corners closer than ``short`` to one another meet at their mean (a short
    Voronoi edge would become a sliver pentagon after a snub step); outline points stay, and
    so do the corners of a cell that this would shrink under ``smallest`` (an area)."""
    if short == 0:
        return rings
    sizes = [len(r) for r in rings]
    points = np.concatenate(rings)
    inner = shapely.distance(region.boundary, shapely.points(points)) > 1e-9 * short
    _, same = np.unique(points, axis=0, return_inverse=True)  # one decision per point
    same = same.reshape(-1)
    ring = np.repeat(np.arange(len(sizes)), sizes)
    for _ in range(8):
        label = close_groups(points, short, movable=inner)
        count = np.bincount(label)
        mean = np.column_stack([np.bincount(label, weights=points[:, k]) for k in (0, 1)])
        moved = mean[label] / count[label, None]
        shrunk = _shrunk(points, moved, sizes, smallest)
        if not len(shrunk):
            return np.split(moved, np.cumsum(sizes)[:-1])
        inner &= ~np.isin(same, same[np.isin(ring, shrunk)])
    return rings


def _shrunk(points: np.ndarray, moved: np.ndarray, sizes: list[int],
            smallest: float) -> np.ndarray:
    """Rings (of ``sizes`` points each) that ``moved`` leaves smaller than ``points`` did and
    than ``smallest`` (an area), by more than rounding."""
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    corners = np.arange(len(points))
    before, after = (signed_areas(Mesh(p, offsets, corners)) for p in (points, moved))
    return np.flatnonzero(after < np.minimum(before, smallest) * (1 - 1e-9))


def _densified_region(region, side: float):
    """``region`` with every outline edge longer than ``side`` cut into equal parts."""
    return _rings_mapped(region, lambda ring: _densified(ring, side))


def _rings_mapped(region, change):
    """``region`` with ``change`` applied to every ring ((N, 2) corners, not closed)."""
    return shapely.union_all([
        shapely.Polygon(change(np.asarray(p.exterior.coords)[:-1]),
                        [change(np.asarray(r.coords)[:-1]) for r in p.interiors])
        for p in shapely.get_parts(region)])


def _even_runs(ring: np.ndarray, side: float, corner: float = CORNER) -> np.ndarray:
    """``ring`` redrawn as straight runs of one length between its corners.

    A corner is a point where the outline turns by more than ``corner`` degrees (a heart's
    tip and notch); between two corners (or once round a ring without any) the outline is cut
    into the fewest equal lengths, measured along it, no longer than ``side``, and the points
    there are joined by straight runs. A curve flattened into many short segments becomes
    runs of about one cell edge; a drawn polygon keeps its corners."""
    edge = np.roll(ring, -1, axis=0) - ring
    length = np.hypot(*edge.T)
    before = np.roll(edge, 1, axis=0)
    turn = np.degrees(np.abs(np.arctan2(before[:, 0] * edge[:, 1] - before[:, 1] * edge[:, 0],
                                        (before * edge).sum(axis=1))))
    corners = np.flatnonzero(turn > corner)
    if not len(corners):
        corners = np.array([0])
    along = np.concatenate([[0.0], np.cumsum(length)])  # arc length at every point, closed
    closed = np.concatenate([ring, ring[:1]])
    ends = np.append(along[corners], along[corners[0]] + along[-1])
    parts = np.maximum(1, np.ceil(np.diff(ends) / side)).astype(int)
    k = np.arange(parts.sum()) - np.repeat(np.cumsum(parts) - parts, parts)
    at = (np.repeat(ends[:-1], parts) + k * np.repeat(np.diff(ends) / parts, parts)) % along[-1]
    return np.column_stack([np.interp(at, along, closed[:, 0]),
                            np.interp(at, along, closed[:, 1])])


def _snapped(rings: list[np.ndarray], region, reach: float,
             smallest: float) -> list[np.ndarray]:
    """Move every point where a cell edge meets the outline onto the nearer of the outline
    vertices beside it when that is nearer than ``reach``: no sliver edge, no sliver pentagon
    after a few snub steps. No move bends a cell inward, pinches it, or shrinks it under
    ``smallest`` (an area)."""
    sizes = [len(r) for r in rings]
    points = np.concatenate(rings)
    outline = shapely.get_coordinates(shapely.get_rings(shapely.get_parts(region)))
    distance, nearest = cKDTree(outline).query(points)
    if reach == 0:
        return rings
    target = outline[nearest]
    start = np.repeat(np.cumsum(sizes) - sizes, sizes)
    k = np.arange(len(points)) - start
    before_index = start + (k - 1) % np.repeat(sizes, sizes)
    after_index = start + (k + 1) % np.repeat(sizes, sizes)
    before, after = points[before_index], points[after_index]
    beside = (before == target).all(axis=1) | (after == target).all(axis=1)
    _, same = np.unique(points, axis=0, return_inverse=True)  # one decision per point
    same = same.reshape(-1)
    beside = np.bincount(same, weights=beside)[same] > 0
    on_outline = shapely.distance(region.boundary, shapely.points(points)) < 1e-9 * reach
    snap = on_outline & beside & (distance < reach) & (distance > 0)
    ring = np.repeat(np.arange(len(sizes)), sizes)
    for _ in range(8):  # moves that bend a cell inward or pinch cells are taken back
        moved = np.where(snap[:, None], target, points)
        b, a = moved - moved[before_index], moved[after_index] - moved
        reflex = (b[:, 0] * a[:, 1] - b[:, 1] * a[:, 0]
                  < -1e-6 * np.hypot(*b.T) * np.hypot(*a.T))  # turning back > 1e-6 rad
        _, vertex = np.unique(moved, axis=0, return_inverse=True)
        vertex = vertex.reshape(-1)
        runs = np.bincount(ring, weights=vertex != vertex[before_index], minlength=len(sizes))
        distinct = np.bincount(np.unique(ring * len(moved) + vertex) // len(moved),
                               minlength=len(sizes))
        pinched = np.flatnonzero(distinct < runs)  # a ring through one point twice
        shrunk = _shrunk(points, moved, sizes, smallest)
        undo = np.isin(ring, np.concatenate([ring[reflex], pinched, shrunk])) & snap
        undo |= np.isin(vertex, _bow_ties(vertex, vertex[after_index])) & snap
        if not undo.any():
            return np.split(moved, np.cumsum(sizes)[:-1])
        snap &= ~np.isin(same, same[undo])
    return np.split(points, np.cumsum(sizes)[:-1])


def _bow_ties(tail: np.ndarray, head: np.ndarray) -> np.ndarray:
    """Vertices that two boundary half-edges leave (cells meeting at a point only)."""
    keep = tail != head
    tail, head = tail[keep], head[keep]
    n = max(tail.max(), head.max()) + 1
    boundary = ~np.isin(tail * n + head, head * n + tail)
    return np.flatnonzero(np.bincount(tail[boundary], minlength=n) > 1)


def quality(mesh: Mesh, cell: float) -> dict[str, float]:
    """Corner angles (degrees) and face sizes (square root of area, in units of ``cell``)."""
    angles = np.degrees(corner_angles(mesh))
    sizes = np.sqrt(signed_areas(mesh)) / cell
    return {"faces": mesh.n_faces, "min_angle": float(angles.min()),
            "max_angle": float(angles.max()), "min_size": float(sizes.min()),
            "median_size": float(np.median(sizes)), "max_size": float(sizes.max())}
