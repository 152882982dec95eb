"""Kobbelt's sqrt(3) subdivision: a centre in every face, then every old inner edge flipped.

Stencils (L. Kobbelt, "sqrt(3)-subdivision", SIGGRAPH 2000): the new vertex of a face is its
vertex mean; an old inner vertex of valence n moves to (1 - a_n) p + a_n / n * sum(neighbours),
a_n = (4 - 2 cos(2 pi / n)) / 9. Faces of any degree are accepted (a face of degree n gets one
centre joined to its n corners), which is the natural generalisation.

Boundary, simplified: Kobbelt trisects the outer edges every second step with the univariate
masks 1/27 (4, 19, 4) and 1/27 (10, 16, 1). Here an outer edge is never flipped (the triangle
(a, b, c_f) on it stays) and outer vertices keep their positions, so the boundary polygon is
interpolated and never refined.

Numbering (child of a mesh with V, E, F, H): vertices ``[old V | one centre per face]``; faces:
one triangle per parent half-edge h = a -> b of face f, ``(a, c_g, c_f)`` when h has a twin in
face g, ``(a, b, c_f)`` on the boundary; edges ``e`` for the flipped edge ``(c_f, c_g)`` of an
inner edge e (or edge e itself when outer, kept) and ``E + h`` for the spoke ``(a, c_f)`` of
corner h. Counts: V' = V + F, E' = E + H, F' = H (= 3F on triangles).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh, Topology
from ..mesh_geometry import face_centroids
from ._common import is_outer, neighbour_sums, trusted_dense
from .hierarchy import Level

FLIPPED, KEPT, SPOKE = 0, 1, 2
EDGE_PARTS = {"flipped": FLIPPED, "kept": KEPT, "spoke": SPOKE}


def counts(n_vertices: int, n_edges: int, n_faces: int, n_corners: int) -> tuple[int, ...]:
    """(V', E', F', H') after one step.

    Examples
    --------
    >>> counts(4, 5, 2, 6)  # two triangles sharing an edge
    (6, 11, 6, 18)
    """
    return n_vertices + n_faces, n_edges + n_corners, n_corners, 3 * n_corners


def vertex_points(mesh: Mesh) -> NDArray[np.float64]:
    """(V, 2) relaxed positions of the old vertices (outer ones stay)."""
    sums, n = neighbour_sums(mesh)
    nn = np.maximum(n, 1)
    a = (4 - 2 * np.cos(2 * np.pi / nn)) / 9
    out = (1 - a)[:, None] * mesh.vertices + (a / nn)[:, None] * sums
    outer = is_outer(mesh)
    out[outer] = mesh.vertices[outer]
    return out


def step(mesh: Mesh) -> Level:
    """One sqrt(3) step (see the module docstring for the numbering)."""
    topo = mesh.topology
    n_v, n_e, n_f, n_h = mesh.n_vertices, topo.n_edges, mesh.n_faces, mesh.n_corners
    vertices = np.empty((n_v + n_f, 2))
    vertices[:n_v] = vertex_points(mesh)
    vertices[n_v:] = face_centroids(mesh)

    fi = mesh.face_indices
    nxt = mesh.next_half_edge
    twin = topo.twin
    he_edge = topo.half_edge_edge
    inner = twin >= 0
    c_own = mesh.half_edge_face + np.int32(n_v)
    c_other = np.where(inner, mesh.half_edge_face[twin] + np.int32(n_v), fi[nxt])
    spoke = np.arange(n_e, n_e + n_h, dtype=np.int32)
    faces = np.empty((n_h, 3), dtype=np.int32)
    faces[:, 0], faces[:, 1], faces[:, 2] = fi, c_other, c_own
    parts = np.empty((n_h, 3), dtype=np.int32)
    parts[:, 0] = np.where(inner, spoke[nxt[twin]], he_edge)
    parts[:, 1] = np.where(inner, he_edge, spoke[nxt])
    parts[:, 2] = spoke
    sides = np.empty((n_h, 3), dtype=np.int8)
    sides[:, 0] = np.where(inner, 0, topo.half_edge_side)
    sides[:, 1] = np.where(inner, c_other > c_own, 0)
    sides[:, 2] = 1

    edges = np.empty((n_e + n_h, 2), dtype=np.int32)
    he = topo.edge_half_edges
    ef = np.where(he >= 0, mesh.half_edge_face[np.maximum(he, 0)] + n_v, -1)
    flip = (he >= 0).all(axis=1)
    edges[:n_e, 0] = np.where(flip, ef.min(axis=1), topo.edges[:, 0])
    edges[:n_e, 1] = np.where(flip, ef.max(axis=1), topo.edges[:, 1])
    edges[n_e:, 0], edges[n_e:, 1] = fi, c_own
    boundary = np.zeros(n_e + n_h, dtype=bool)
    boundary[:n_e] = ~flip
    child = trusted_dense(vertices, faces, Topology(edges, parts.reshape(-1), sides.reshape(-1)),
                          boundary)

    parent_edge = np.empty(n_e + n_h, dtype=np.int32)
    parent_edge[:n_e] = np.arange(n_e, dtype=np.int32)
    parent_edge[n_e:] = mesh.half_edge_face
    edge_part = np.full(n_e + n_h, SPOKE, dtype=np.int8)
    edge_part[:n_e] = np.where(flip, FLIPPED, KEPT)
    corner = (np.arange(n_h) - np.repeat(mesh.face_offsets[:-1], mesh.face_sizes)).astype(np.int32)
    return Level(child, mesh.half_edge_face.copy(), corner, parent_edge, edge_part)
