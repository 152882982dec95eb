"""Geometric checks on input meshes: orientation, degenerate, non-convex and overlapping faces.

The Mesh constructor already refuses bad indices, short faces, repeated corners and
non-finite coordinates; ``Topology.build`` refuses non-manifold edges and bow-tie vertices.
"""

from __future__ import annotations

import numpy as np
import shapely

from .errors import MeshError
from .mesh import Mesh, corner_angles, corner_turns, outer_vertices, signed_areas

AREA_EPS = 1e-12
MAX_COORDINATE = 1e9


def validate(mesh: Mesh, *, allow_nonconvex: bool = False) -> Mesh:
    """Return ``mesh`` (re-oriented if consistently clockwise) or raise MeshError."""
    if mesh.n_faces == 0:
        raise MeshError("the mesh has no faces")
    huge = np.abs(mesh.vertices).max(axis=1) > MAX_COORDINATE
    if huge.any():
        v = int(np.flatnonzero(huge)[0])
        raise MeshError(f"vertex {v} has a coordinate beyond {MAX_COORDINATE:g}; scale the "
                        "mesh down")
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
            raise MeshError(f"face {f} is not convex at vertex {mesh.face_indices[h]}: the "
                            "snub scheme assumes convex faces (deep levels of some inputs have "
                            "a few non-convex faces, see weave-cut convexity); pass "
                            "--allow-nonconvex to use the mesh anyway")
    _check_overlaps(mesh, areas)
    return mesh


def _check_overlaps(mesh: Mesh, areas) -> None:
    """Faces may touch along edges and at corners, never share interior points.

    A manifold mesh of counter-clockwise faces is embedded (no two faces overlap) when every
    face is simple, the corner angles around every inner vertex add up to one full turn (at
    most one at a boundary vertex), the boundary edges cross nowhere, and no boundary vertex
    lies inside a face. These are local checks plus a search over the boundary only, so a
    million faces take seconds, not minutes.
    """
    rings = shapely.linearrings(np.take(mesh.vertices, mesh.face_indices, axis=0),
                                indices=mesh.half_edge_face)
    polys = shapely.polygons(rings)
    invalid = ~shapely.is_valid(polys)
    if invalid.any():
        f = int(np.flatnonzero(invalid)[0])
        raise MeshError(f"face {f} intersects itself")
    topo = mesh.topology
    outer = outer_vertices(mesh)
    turn = np.bincount(mesh.face_indices, weights=corner_angles(mesh),
                       minlength=mesh.n_vertices) / (2 * np.pi)
    bad = np.flatnonzero(np.where(outer, turn > 1 + 1e-9, np.abs(turn - 1) > 1e-9))
    if len(bad):
        v = int(bad[0])
        raise MeshError(f"faces around vertex {v} overlap (their angles add up to "
                        f"{360 * turn[v]:.1f} degrees)")
    edges = topo.edges[topo.boundary_edges]
    segments = shapely.linestrings(mesh.vertices[edges.ravel()],
                                   indices=np.repeat(np.arange(len(edges)), 2))
    a, b = shapely.STRtree(segments).query(segments, predicate="intersects")
    apart = (a < b) & (edges[a][:, :, None] != edges[b][:, None, :]).all(axis=(1, 2))
    if apart.any():
        i, j = edges[a[apart][0]], edges[b[apart][0]]
        raise MeshError(f"faces overlap: boundary edges ({i[0]}, {i[1]}) and "
                        f"({j[0]}, {j[1]}) cross")
    corners = np.unique(edges)
    points = shapely.points(mesh.vertices[corners])
    p, f = shapely.STRtree(polys).query(points, predicate="within")
    if len(p):
        raise MeshError(f"vertex {corners[p[0]]} lies inside face {f[0]} (faces overlap)")
