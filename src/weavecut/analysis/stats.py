"""Per-level statistics: counts, degree histograms, angles, convexity, boundary."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh, outer_vertices, vertex_degrees
from ..mesh_geometry import corner_angles
from ..numeric import dot

REFLEX_EPS = 1e-9
BLOCK = 1 << 16  # faces per block of the angle pass: its scratch stays in the cache
TIE = 1e-9  # pseudo-angles this close to the extreme one get their exact angle


def _histogram(values, lowest: int | None = None) -> dict[str, int]:
    """Counts by value; with ``lowest``, every value from it to the largest is listed."""
    counts = np.bincount(np.asarray(values, dtype=np.int64))
    if lowest is None:
        keys = np.flatnonzero(counts)
    else:
        keys = range(lowest, max(lowest, len(counts) - 1) + 1)
    return {str(k): int(counts[k]) if k < len(counts) else 0 for k in keys}


def nonconvex_faces(mesh: Mesh) -> np.ndarray:
    """(F,) True for faces with an interior angle above 180 degrees."""
    reflex = corner_angles(mesh) > np.pi + REFLEX_EPS
    return np.bincount(mesh.half_edge_face[reflex], minlength=mesh.n_faces) > 0


def _dense_turns(x: NDArray[np.float64], y: NDArray[np.float64], faces: NDArray[np.int32]):
    """(k, f) cross and dot products of the two edges at every corner of faces of one degree
    (corner j of face i at [j, i]), bit for bit those of ``corner_angles``: with
    e_j = p_(j+1) - p_j, the edge to the previous corner is -e_(j-1) exactly. Corner-major,
    so that every operation runs over rows of f numbers."""
    k = faces.shape[1]
    edges = []
    for column in (x, y):
        p = np.take(column, faces.T, mode="clip")  # (k, f)
        e = np.empty_like(p)
        np.subtract(p[1:], p[:-1], out=e[:-1])
        np.subtract(p[0], p[-1], out=e[-1])
        edges.append(e)
    ex, ey = edges
    cross, dot, scratch = np.empty_like(ex), np.empty_like(ex), np.empty_like(ex)
    for j, i in ((slice(1, k), slice(0, k - 1)), (slice(0, 1), slice(k - 1, k))):
        # at corner j the edge before is e_i: cross = e_j x e_i, dot = -(e_j . e_i)
        np.multiply(ey[j], ex[i], out=cross[j])
        np.multiply(ex[j], ey[i], out=scratch[j])
        cross[j] -= scratch[j]
        np.multiply(ex[j], ex[i], out=dot[j])
        np.multiply(ey[j], ey[i], out=scratch[j])
        dot[j] += scratch[j]
    np.negative(dot, out=dot)
    return cross, dot


def _angles(cross, dot) -> NDArray[np.float64]:
    """Interior angles in [0, 2 pi) from the cross and dot products (``corner_angles``)."""
    return np.mod(np.arctan2(cross, dot), 2 * np.pi)


def _pseudo_angles(cross, dot) -> NDArray[np.float64]:
    """An increasing function of :func:`_angles`, in [0, 4], with no transcendental (NaN at a
    corner with an edge of length 0): 1 - dot / (|cross| + |dot|) up to pi, 3 + the ratio
    above."""
    ratio, turn = np.abs(cross), np.abs(dot)
    ratio += turn
    np.divide(dot, ratio, out=ratio)
    np.subtract(1, ratio, out=turn)
    np.add(3, ratio, out=turn, where=cross < 0)
    return turn


def surface_angles(mesh: Mesh) -> NDArray[np.float64]:
    """(H,) interior angle at every corner of a surface in space, in (0, 2 pi): measured in the
    plane of the corner's two edges, reflex where the corner turns against the face's normal."""
    from ..surface import face_normals

    p = mesh.vertices[mesh.face_indices]
    a = p[mesh.prev_half_edge] - p
    b = p[mesh.next_half_edge] - p
    cross = np.cross(b, a)
    side = dot(cross, face_normals(mesh)[mesh.half_edge_face])
    angle = np.arctan2(np.linalg.norm(cross, axis=1), dot(a, b))
    return np.where(side < 0, 2 * np.pi - angle, angle)


def angle_summary(mesh: Mesh) -> tuple[float, float, int]:
    """(smallest, largest interior angle in radians, number of non-convex faces) in one pass.

    Faces of one degree go in blocks of ``BLOCK`` rows, so the pass needs no per-corner
    index arrays and little memory, and the arc tangent is taken only where it can matter:
    at the corners whose pseudo-angle (:func:`_pseudo_angles`, increasing with the angle) is
    within ``TIE`` of the block's extremes, and at corners turning by more than pi; the
    numbers equal ``corner_angles`` and :func:`nonconvex_faces`.
    """
    if mesh.dim == 3:
        angles = surface_angles(mesh)
        reflex = np.bincount(mesh.half_edge_face[angles > np.pi + REFLEX_EPS],
                             minlength=mesh.n_faces) > 0
        return float(angles.min()), float(angles.max()), int(reflex.sum())
    dense = mesh.dense_faces()
    if dense is None:
        angles = corner_angles(mesh)
        return float(angles.min()), float(angles.max()), int(nonconvex_faces(mesh).sum())
    lo, hi, bad = np.inf, -np.inf, 0
    x, y = np.ascontiguousarray(mesh.vertices.T)
    for start in range(0, len(dense), BLOCK):
        cross, dot = _dense_turns(x, y, dense[start:start + BLOCK])
        turn = _pseudo_angles(cross, dot)
        undefined = np.isnan(turn)
        pick = (turn <= np.fmin.reduce(turn, axis=None) + TIE) | undefined
        pick |= turn >= np.fmax.reduce(turn, axis=None) - TIE  # the corners that may be extreme
        angles = _angles(cross[pick], dot[pick])
        if len(angles):
            lo, hi = min(lo, float(angles.min())), max(hi, float(angles.max()))
        turning = (cross < 0) | undefined  # above pi, or unknown: the reflex candidates
        if turning.any():
            reflex = np.zeros(cross.shape, dtype=bool)
            reflex[turning] = _angles(cross[turning], dot[turning]) > np.pi + REFLEX_EPS
            bad += int(reflex.any(axis=0).sum())
    return lo, hi, bad


def boundary_length(mesh: Mesh) -> float:
    """Total length of the outer edges."""
    topo = mesh.topology
    e = topo.edges[topo.boundary_edges]
    return float(np.hypot(*(mesh.vertices[e[:, 1]] - mesh.vertices[e[:, 0]]).T).sum())


def level_stats(mesh: Mesh, level: int) -> dict:
    """The statistics of one level, in the shape ``weave-cut stats --json`` prints."""
    topo = mesh.topology
    degrees = vertex_degrees(mesh)
    outer = outer_vertices(mesh)
    lo, hi, nonconvex = angle_summary(mesh)
    boundary = topo.boundary_edges
    return {
        "level": level,
        "vertices": mesh.n_vertices,
        "edges": topo.n_edges,
        "faces": mesh.n_faces,
        "inner_vertex_degrees": _histogram(degrees[~outer], lowest=3),
        "outer_vertex_degrees": _histogram(degrees[outer], lowest=2),
        "face_degrees": _histogram(mesh.face_sizes),
        "nonconvex_faces": nonconvex,
        "min_angle_deg": round(float(np.degrees(lo)), 6),
        "max_angle_deg": round(float(np.degrees(hi)), 6),
        "boundary_edges": int(boundary.sum()),
        "boundary_length": round(boundary_length(mesh), 6),
    }


def surface_stats(hierarchy) -> list[dict]:
    """What ``stats`` adds for a surface in space, per level: the Euler characteristic
    V - E + F, the counts paper eq. (2) predicts from the level before (|V'| = |V| + 2|E| + |F|,
    |E'| = 3|E| + sum n_f, |F'| = sum n_f) and whether they hold, and the snub weave's strands:
    how many, how many closed, and every loop's centre-line length (mesh units)."""
    from ..weave.snub_weave import snub_weaves

    weaves = snub_weaves(hierarchy) if len(hierarchy) > 1 else []
    rows = []
    for t, level in enumerate(hierarchy):  # levels
        mesh = level.mesh
        v, e, f = mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces
        row: dict = {"euler_characteristic": v - e + f}
        if t:
            before = hierarchy[t - 1].mesh
            corners = int(before.face_sizes.sum())
            eq2 = {"vertices": before.n_vertices + 2 * before.topology.n_edges + before.n_faces,
                   "edges": 3 * before.topology.n_edges + corners, "faces": corners}
            weave = weaves[t - 1]
            row.update(eq2=eq2, eq2_holds=eq2 == {"vertices": v, "edges": e, "faces": f},
                       strands=weave.n_strands, closed_strands=int(weave.strand_closed.sum()),
                       strand_lengths=[round(float(x), 6) for x in weave.strand_lengths()])
        rows.append(row)
    return rows
