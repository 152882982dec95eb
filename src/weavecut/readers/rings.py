"""From closed rings to a mesh: checks, nesting (holes), welding near vertices, T-junctions.

A drawing's faces rarely meet exactly: a vertex drawn by hand lands a hair beside its
neighbour's, or on the middle of a neighbour's edge. ``weld`` merges points closer than a
tolerance into one vertex and then splits every boundary edge that passes within the
tolerance of another boundary vertex, so that edges drawn twice become one shared edge.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import shapely
from scipy.sparse import coo_array
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from ..errors import MeshFileError
from ..mesh import Mesh


class Ring(NamedTuple):
    """One closed outline of a drawing: a label naming its element and (k, 2) points in mm."""

    label: str
    points: np.ndarray


def checked(rings: list[Ring], tolerance: float) -> list[Ring]:
    """Rings without repeated points, counter-clockwise, each simple and of non-zero area.

    Raises MeshFileError naming the first ring that crosses itself (a bow tie or a figure
    eight too, whose signed area can be 0) or encloses nothing (an area, or for a ring that
    crosses itself the area of its convex hull, of at most ``tolerance`` squared).
    """
    out = []
    for ring in rings:
        p = ring.points
        step = np.hypot(*(p - np.roll(p, 1, axis=0)).T)
        p = p[step > tolerance * 1e-6] if (step > tolerance * 1e-6).sum() >= 3 else p
        polygon = shapely.Polygon(p) if len(p) >= 3 else None
        if polygon is None or polygon.convex_hull.area <= tolerance ** 2:
            raise MeshFileError(f"{ring.label} encloses no area")
        if not polygon.is_valid:
            _, (x, y) = invalid_where(polygon)
            raise MeshFileError(f"{ring.label} crosses itself near ({x:.4g}, {y:.4g}) mm (y up); "
                                "a face must be a simple closed outline")
        if polygon.area <= tolerance ** 2:
            raise MeshFileError(f"{ring.label} encloses no area")
        ccw = shapely.is_ccw(polygon.exterior)
        out.append(Ring(ring.label, p if ccw else p[::-1]))
    return out


def invalid_where(polygon) -> tuple[str, tuple[float, float]]:
    """Why GEOS finds ``polygon`` invalid (its words, such as "Self-intersection") and the
    point it names."""
    what, _, where = shapely.is_valid_reason(polygon).partition("[")
    x, y = map(float, where.rstrip("]").split()[:2])
    return what, (x, y)


def nesting(rings: list[Ring], tolerance: float) -> np.ndarray:
    """(R,) index of the ring each ring is a hole of, or -1 for an outer ring.

    A ring inside an odd number of others is a hole of the smallest ring around it; two rings
    whose insides overlap (by more than ``tolerance`` times the smaller one's perimeter) and
    neither holds the other are an error naming both.
    """
    polygons = np.array([shapely.Polygon(r.points) for r in rings])
    left, right = shapely.STRtree(polygons).query(polygons, predicate="intersects")
    keep = left != right
    left, right = left[keep], right[keep]
    shared = shapely.area(shapely.intersection(polygons[left], polygons[right]))
    areas = shapely.area(polygons)
    slack = tolerance * shapely.length(polygons)
    inside = shared >= areas[left] - slack[left]  # ring `left` lies inside ring `right`
    overlap = (shared > np.minimum(slack[left], slack[right])) & ~inside
    overlap &= ~(shared >= areas[right] - slack[right])
    if overlap.any():
        k = int(np.flatnonzero(overlap)[0])
        a, b = sorted((int(left[k]), int(right[k])))
        raise MeshFileError(f"{rings[a].label} and {rings[b].label} overlap; faces may share "
                            "edges but not insides")
    left, right = left[inside], right[inside]
    depth = np.bincount(left, minlength=len(rings))
    # the ring around `left` one level up is its hole parent
    parent_pair = depth[right] == depth[left] - 1
    parent = np.full(len(rings), -1)
    parent[left[parent_pair]] = right[parent_pair]
    parent[depth % 2 == 0] = -1
    return parent


def close_groups(points: np.ndarray, tolerance: float,
                 movable: np.ndarray | None = None) -> np.ndarray:
    """(N,) group of every point: points closer than ``tolerance`` (in a chain) share one.

    Only ``movable`` points (a mask; default all) join groups; the others stay alone.
    """
    idx = np.arange(len(points)) if movable is None else np.flatnonzero(movable)
    pairs = idx[cKDTree(points[idx]).query_pairs(tolerance, output_type="ndarray")]
    n = len(points)
    graph = coo_array((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    return connected_components(graph, directed=False)[1]


def weld(polygons: list[np.ndarray], tolerance: float) -> tuple[Mesh, int]:
    """One mesh from counter-clockwise polygons; points closer than ``tolerance`` become one.

    Parameters
    ----------
    polygons : list of (k, 2) float64, each a face, counter-clockwise
    tolerance : points closer than this (mm) are merged; a merged vertex sits where the first
        of them (in face order) lies

    Returns
    -------
    mesh : the welded mesh (``split_t_junctions`` then shares edges drawn split on one side)
    n_merged : how many points moved (by more than 1e-6 mm) to merge with another
    """
    sizes = np.fromiter(map(len, polygons), dtype=np.int64, count=len(polygons))
    points = np.concatenate(polygons)
    label = close_groups(points, tolerance)
    target = np.unique(label, return_index=True)[1][label]  # the first point of its group
    n_merged = int((np.hypot(*(points - points[target]).T) > 1e-6).sum())  # beyond 1 nm
    used, vertex = np.unique(target, return_inverse=True)
    corners = vertex.reshape(-1)
    face = np.repeat(np.arange(len(polygons)), sizes)
    keep = corners != np.roll(corners, 1)  # drop a corner merged into the one before it
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    keep[starts] = corners[starts] != corners[starts + sizes - 1]
    corners, face = corners[keep], face[keep]
    counts = np.bincount(face, minlength=len(polygons))
    offsets = np.concatenate([[0], np.cumsum(counts)])
    mesh = Mesh(points[used], offsets, corners) if (counts >= 3).all() else None
    if mesh is None:
        bad = int(np.flatnonzero(counts < 3)[0])
        raise MeshFileError(f"face {bad} collapses to fewer than 3 corners when points closer "
                            f"than {tolerance:g} mm are merged")
    return mesh, n_merged


def split_t_junctions(mesh: Mesh, tolerance: float) -> Mesh:
    """Split every boundary edge at the boundary vertices within ``tolerance`` of its inside.

    An edge drawn once along a face and twice (split by a vertex) along its neighbours becomes
    two shared edges; the split points keep their order along the edge.
    """
    u = mesh.face_indices
    w = u[mesh.next_half_edge]
    key = np.minimum(u, w).astype(np.int64) * mesh.n_vertices + np.maximum(u, w)
    _, inverse, count = np.unique(key, return_inverse=True, return_counts=True)
    boundary = np.flatnonzero(count[inverse] == 1)
    if len(boundary) == 0:
        return mesh
    vertices = mesh.vertices
    segments = shapely.linestrings(np.stack([vertices[u[boundary]], vertices[w[boundary]]], 1))
    candidates = np.unique(u[boundary])
    hit_point, hit_segment = shapely.STRtree(segments).query(
        shapely.points(vertices[candidates]), predicate="dwithin", distance=tolerance)
    v, h = candidates[hit_point], boundary[hit_segment]
    a, b = vertices[u[h]], vertices[w[h]]
    t = ((vertices[v] - a) * (b - a)).sum(axis=1) / ((b - a) ** 2).sum(axis=1)
    inner = (v != u[h]) & (v != w[h]) & (t > 0) & (t < 1)
    if not inner.any():
        return mesh
    v, h, t = v[inner], h[inner], t[inner]
    order = np.lexsort((np.concatenate([np.zeros(len(u)), t]),
                        np.concatenate([np.arange(len(u)), h])))
    corners = np.concatenate([u, v])[order]
    faces = np.concatenate([mesh.half_edge_face, mesh.half_edge_face[h]])[order]
    offsets = np.concatenate([[0], np.cumsum(np.bincount(faces, minlength=mesh.n_faces))])
    return Mesh(vertices, offsets, corners)


def enclosed_faces(rings: list[Ring], pieces: list[Ring], tolerance: float) -> list[Ring]:
    """The faces that closed ``rings`` and open ``pieces`` (lines, arcs) enclose together, as
    a CAD user draws a mesh: loops of lines, a grid drawn with every edge once, or an outline
    with lines across it.

    A piece's end within ``tolerance`` of a ring's corner or of another end joins it; a piece
    with an end that joins nothing is an error naming it.

    Every face runs counter-clockwise from its leftmost corner (the lowest of them), and the
    faces come in the order of those corners (by x, then y), faces that share one
    counter-clockwise around it: the numbering depends on the faces' geometry only, not on
    how the lines were drawn or how GEOS walks them.
    """
    corners = np.concatenate([r.points for r in rings]) if rings else np.empty((0, 2))
    ends = np.array([[p.points[0], p.points[-1]] for p in pieces]).reshape(-1, 2)
    points = np.concatenate([corners, ends])
    label = close_groups(points, tolerance)
    moved = points[np.unique(label, return_index=True)[1][label]][len(corners):]
    lines = [np.vstack([moved[2 * k], p.points[1:-1], moved[2 * k + 1]])
             for k, p in enumerate(pieces)]
    lines += [np.vstack([r.points, r.points[:1]]) for r in rings]
    lines = np.array([shapely.LineString(line) for line in lines])
    faces, _, dangles, invalid = shapely.polygonize_full(
        shapely.get_parts(shapely.union_all(lines)))
    loose = shapely.get_parts(shapely.union(dangles, invalid))
    if len(loose):
        # the piece the loose part runs along, and the loose part's end that fewest lines reach
        k = int(np.argmax(shapely.length(shapely.intersection(lines[:len(pieces)], loose[0]))))
        ends = shapely.get_coordinates(loose[0])[[0, -1]]
        reach = shapely.dwithin(lines[:, None], shapely.points(ends)[None], 1e-9).sum(axis=0)
        x, y = ends[np.argmin(reach)]
        raise MeshFileError(f"{pieces[k].label} near ({x + 0:.4g}, {y + 0:.4g}) mm has an open "
                            "end; lines and arcs must enclose faces")
    # GEOS's normalize starts a ring at its smallest corner (x, then y), clockwise: reversed,
    # counter-clockwise from the same corner
    rings = [np.roll(np.asarray(f.exterior.coords)[-2::-1], 1, axis=0)
             for f in shapely.normalize(shapely.get_parts(faces))]
    first = np.array([r[0] for r in rings]).reshape(-1, 2)
    step = np.array([r[1] - r[0] for r in rings]).reshape(-1, 2)
    order = np.lexsort((np.arctan2(step[:, 1], step[:, 0]), first[:, 1], first[:, 0]))
    return [Ring(f"face {k + 1} enclosed by lines", rings[i]) for k, i in enumerate(order)]
