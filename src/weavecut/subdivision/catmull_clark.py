"""Catmull-Clark subdivision: one quad per corner of every face, for faces of any degree.

Stencils (E. Catmull, J. Clark, "Recursively generated B-spline surfaces on arbitrary
topological meshes", 1978): face point = vertex mean of the face; inner edge point =
(u + w + c_f + c_g) / 4; inner vertex of valence n: (Q + 2R + (n - 3) S) / n with Q the mean
of the adjacent face points, R the mean of the incident edge midpoints and S the old position.
Boundary (the crease rules of DeRose, Kass, Truong, "Subdivision surfaces in character
animation", 1998, and Hoppe et al. 1994): an outer edge point is the midpoint, an outer vertex
moves to 3/4 S + 1/8 (its two outer neighbours), a cubic B-spline. Simplified: no corner tags,
so corners of the input boundary are smoothed too.

A face of degree n != 4 becomes a face point of valence n, the irregular vertex the paper
describes; every child face is a quad.

Numbering (child of a mesh with V, E, F, H): vertices ``[old V | one per edge | one per
face]`` (edge e -> ``V + e``, face f -> ``V + E + f``); faces: quad ``h`` = ``(a_h, m_e(h),
c_f, m_e(prev h))`` for every parent corner h; edges ``2e`` (u, m_e) and ``2e + 1`` (w, m_e)
for the halves of edge e and ``2E + h`` for the spoke ``(m_e(h), c_f)``.
Counts: V' = V + E + F, E' = 2E + H, F' = H.
"""

from __future__ import annotations

import numpy as np

from ..mesh import Mesh, Topology
from ..mesh_geometry import face_centroids
from ._common import is_outer, neighbour_sums, trusted_dense, vertex_sums
from .hierarchy import Level

FIRST_HALF, SECOND_HALF, SPOKE = 0, 1, 2
EDGE_PARTS = {"first half": FIRST_HALF, "second half": SECOND_HALF, "spoke": SPOKE}


def counts(n_vertices: int, n_edges: int, n_faces: int, n_corners: int) -> tuple[int, ...]:
    """(V', E', F', H') after one step.

    Examples
    --------
    >>> counts(4, 4, 1, 4)  # one quad -> four
    (9, 12, 4, 16)
    """
    return n_vertices + n_edges + n_faces, 2 * n_edges + n_corners, n_corners, 4 * n_corners


def step(mesh: Mesh) -> Level:
    """One Catmull-Clark step (see the module docstring for stencils and numbering)."""
    topo = mesh.topology
    n_v, n_e, n_f, n_h = mesh.n_vertices, topo.n_edges, mesh.n_faces, mesh.n_corners
    v = mesh.vertices
    centres = face_centroids(mesh)
    he = topo.edge_half_edges
    inner = (he >= 0).all(axis=1)
    e = topo.edges

    vertices = np.empty((n_v + n_e + n_f, 2))
    mids = vertices[n_v:n_v + n_e]
    np.add(np.take(v, e[:, 0], axis=0), np.take(v, e[:, 1], axis=0), out=mids)
    ef = mesh.half_edge_face[np.maximum(he, 0)]
    cf = np.take(centres, ef[:, 0], axis=0)
    cf += np.take(centres, ef[:, 1], axis=0)
    edge_sum = mids.copy()                       # u + w, used by the vertex rule
    mids += cf
    mids *= 0.25
    if not inner.all():
        mids[~inner] = 0.5 * edge_sum[~inner]
    vertices[n_v + n_e:] = centres

    nb_sum, n = neighbour_sums(mesh)
    face_sum = vertex_sums(n_v, mesh.face_indices, np.take(centres, mesh.half_edge_face, axis=0))
    nn = np.maximum(n, 1)[:, None].astype(float)
    vertices[:n_v] = ((nn - 2) * v + (nb_sum + face_sum) / nn) / nn
    outer = is_outer(mesh)
    if outer.any():
        bsum, bn = neighbour_sums(mesh, topo.boundary_edges)
        curve = outer & (bn == 2)
        vertices[:n_v][curve] = 0.75 * v[curve] + 0.125 * bsum[curve]
        vertices[:n_v][outer & ~curve] = v[outer & ~curve]

    # topology: quad h = (a, m_e(h), c_f, m_e(prev h))
    fi = mesh.face_indices
    prv = mesh.prev_half_edge
    he_edge = topo.half_edge_edge
    side = topo.half_edge_side
    faces = np.empty((n_h, 4), dtype=np.int32)
    faces[:, 0] = fi
    faces[:, 1] = he_edge + np.int32(n_v)
    faces[:, 2] = mesh.half_edge_face + np.int32(n_v + n_e)
    faces[:, 3] = faces[prv, 1]
    parts = np.empty((n_h, 4), dtype=np.int32)
    parts[:, 0] = 2 * he_edge + side
    parts[:, 1] = np.arange(2 * n_e, 2 * n_e + n_h, dtype=np.int32)
    parts[:, 2] = parts[prv, 1]
    parts[:, 3] = 2 * he_edge[prv] + 1 - side[prv]
    sides = np.tile(np.array([0, 0, 1, 1], dtype=np.int8), n_h)
    edges = np.empty((2 * n_e + n_h, 2), dtype=np.int32)
    halves = edges[:2 * n_e].reshape(n_e, 2, 2)
    halves[:, :, 0] = e
    halves[:, :, 1] = np.arange(n_v, n_v + n_e, dtype=np.int32)[:, None]
    edges[2 * n_e:, 0], edges[2 * n_e:, 1] = faces[:, 1], faces[:, 2]
    boundary = np.zeros(2 * n_e + n_h, dtype=bool)
    boundary[:2 * n_e] = np.repeat(~inner, 2)
    child = trusted_dense(vertices, faces, Topology(edges, parts.reshape(-1), sides), boundary)

    parent_edge = np.empty(2 * n_e + n_h, dtype=np.int32)
    parent_edge[:2 * n_e] = np.repeat(np.arange(n_e, dtype=np.int32), 2)
    parent_edge[2 * n_e:] = mesh.half_edge_face
    edge_part = np.full(2 * n_e + n_h, SPOKE, dtype=np.int8)
    edge_part[:2 * n_e] = np.tile(np.array([FIRST_HALF, SECOND_HALF], dtype=np.int8), n_e)
    corner = (np.arange(n_h) - np.repeat(mesh.face_offsets[:-1], mesh.face_sizes)).astype(np.int32)
    return Level(child, mesh.half_edge_face.copy(), corner, parent_edge, edge_part)
