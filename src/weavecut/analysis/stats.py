"""Per-level statistics: counts, degree histograms, angles, convexity, boundary."""

from __future__ import annotations

import numpy as np

from ..mesh import Mesh, corner_angles, edge_lengths, outer_vertices, vertex_degrees

REFLEX_EPS = 1e-9


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


def level_stats(mesh: Mesh, level: int) -> dict:
    """The statistics of one level, in the shape ``weave-cut stats --json`` prints."""
    topo = mesh.topology
    degrees = vertex_degrees(mesh)
    outer = outer_vertices(mesh)
    angles = np.degrees(corner_angles(mesh))
    boundary = topo.boundary_edges
    return {
        "level": level,
        "vertices": mesh.n_vertices,
        "edges": topo.n_edges,
        "faces": mesh.n_faces,
        "inner_vertex_degrees": _histogram(degrees[~outer], lowest=3),
        "outer_vertex_degrees": _histogram(degrees[outer], lowest=2),
        "face_degrees": _histogram(mesh.face_sizes),
        "nonconvex_faces": int(nonconvex_faces(mesh).sum()),
        "min_angle_deg": round(float(angles.min()), 6),
        "max_angle_deg": round(float(angles.max()), 6),
        "boundary_edges": int(boundary.sum()),
        "boundary_length": round(float(edge_lengths(mesh)[boundary].sum()), 6),
    }
