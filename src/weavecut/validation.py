"""Geometric checks on input meshes: orientation, degenerate, non-convex and overlapping faces.

The Mesh constructor already refuses bad indices, short faces, repeated corners and
non-finite coordinates; ``Topology.build`` refuses non-manifold edges and bow-tie vertices.
"""

from __future__ import annotations

import numpy as np
import shapely

from .errors import MeshError
from .mesh import Mesh, corner_turns, signed_areas

AREA_EPS = 1e-12


def validate(mesh: Mesh, *, allow_nonconvex: bool = False) -> Mesh:
    """Return ``mesh`` (re-oriented if consistently clockwise) or raise MeshError."""
    if mesh.n_faces == 0:
        raise MeshError("the mesh has no faces")
    areas = signed_areas(mesh)
    scale = max(float(np.ptp(mesh.vertices, axis=0).max()), 1e-300) ** 2
    flat = np.abs(areas) <= AREA_EPS * scale
    if flat.any():
        f = int(np.flatnonzero(flat)[0])
        raise MeshError(f"face {f} has zero area")
    if (areas < 0).all():
        mesh = mesh.reversed()
        areas = -areas
    elif (areas < 0).any():
        f = int(np.flatnonzero(areas < 0)[0])
        raise MeshError(f"face {f} is clockwise while others are counter-clockwise "
                        f"({int((areas < 0).sum())} of {mesh.n_faces} faces are clockwise)")
    mesh.topology  # non-manifold edges and vertices raise here
    if not allow_nonconvex:
        turns = corner_turns(mesh)
        reflex = turns < -AREA_EPS * scale
        if reflex.any():
            h = int(np.flatnonzero(reflex)[0])
            f = int(mesh.half_edge_face[h])
            raise MeshError(f"face {f} is not convex at vertex {mesh.face_indices[h]} "
                            f"(the scheme assumes convex faces; --allow-nonconvex to go on)")
    _check_overlaps(mesh, areas)
    return mesh


def _check_overlaps(mesh: Mesh, areas) -> None:
    """Faces may touch along edges and at corners, never share interior points."""
    rings = shapely.linearrings(np.take(mesh.vertices, mesh.face_indices, axis=0),
                                indices=mesh.half_edge_face)
    polys = shapely.polygons(rings)
    invalid = ~shapely.is_valid(polys)
    if invalid.any():
        f = int(np.flatnonzero(invalid)[0])
        raise MeshError(f"face {f} intersects itself")
    tree = shapely.STRtree(polys)
    a, b = tree.query(polys, predicate="intersects")
    keep = a < b
    a, b = a[keep], b[keep]
    if len(a):
        shared = shapely.area(shapely.intersection(polys[a], polys[b]))
        tol = 1e-9 * np.minimum(areas[a], areas[b])
        bad = np.flatnonzero(shared > tol)
        if len(bad):
            i = bad[0]
            raise MeshError(f"faces {a[i]} and {b[i]} overlap (shared area {shared[i]:.3g})")
