"""Doo-Sabin subdivision: one new vertex per corner; faces for faces, edges and vertices.

Weights (D. Doo, M. Sabin, "Behaviour of recursive division surfaces near extraordinary
points", 1978): the new point of corner i of a face of degree n is
sum_j a_ij v_j with a_ij = [i = j] / 4 + (3 + 2 cos(2 pi (i - j) / n)) / (4 n), so a quad
gives the bi-quadratic B-spline weights 9/16, 3/16, 3/16, 1/16. A face of degree n stays a face
of degree n (the paper's point), an inner edge becomes a quad and an inner vertex of valence k
a k-gon. Boundary, simplified: outer edges and outer vertices give no face, so the boundary
recedes each step (no boundary curve rule, e.g. Nasri 1987, is applied).

Numbering (child of a mesh with V, E, F, H, E_in inner edges, V_in inner vertices): vertices:
one per parent corner (corner h -> h); faces ``[F face polygons | E_in edge quads | V_in vertex
polygons]`` in increasing parent id; edge quad of inner edge (h0 = u -> w, h1 = w -> u) is
``(h0, next h1, h1, next h0)``; edges ``h`` = (h, next h) inside the face of h, then
``H + 2k`` and ``H + 2k + 1`` joining the two corners of u, resp. w, across the k-th inner edge.
Counts: V' = H, E' = H + 2 E_in, F' = F + E_in + V_in.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ._common import corner_index, ragged_mesh, vertex_rings
from .hierarchy import Level
from .midedge import inner_vertices

IN_FACE, ACROSS_EDGE = 0, 1
EDGE_PARTS = {"in face": IN_FACE, "across edge": ACROSS_EDGE}


def counts(n_vertices: int, n_edges: int, n_faces: int, n_corners: int) -> tuple[int, ...]:
    """Upper bounds of (V', E', F', H') from V, E, F, H alone (for memory checks)."""
    e = n_corners + 2 * n_edges
    return n_corners, e, n_faces + n_edges + n_vertices, 2 * e


def exact_counts(n_faces: int, n_corners: int, n_inner_edges: int, n_inner_vertices: int):
    """(V', E', F') after one step.

    Examples
    --------
    >>> exact_counts(4, 16, 4, 1)  # a 2 x 2 quad grid
    (16, 24, 9)
    """
    return n_corners, n_corners + 2 * n_inner_edges, n_faces + n_inner_edges + n_inner_vertices


def corner_points(mesh: Mesh) -> NDArray[np.float64]:
    """(H, 2) the Doo-Sabin point of every corner."""
    n = mesh.face_sizes[mesh.half_edge_face]
    i = corner_index(mesh)
    start = mesh.face_offsets[:-1][mesh.half_edge_face]
    out = np.zeros((mesh.n_corners, 2))
    for d in range(int(mesh.face_sizes.max(initial=0))):
        sel = np.flatnonzero(n > d)
        nn = n[sel]
        w = (3 + 2 * np.cos(2 * np.pi * d / nn)) / (4 * nn) + (0.25 if d == 0 else 0.0)
        j = start[sel] + (i[sel] + d) % nn
        out[sel] += w[:, None] * mesh.vertices[mesh.face_indices[j]]
    return out


def step(mesh: Mesh) -> Level:
    """One Doo-Sabin step (see the module docstring for the numbering)."""
    topo = mesh.topology
    n_f, n_h = mesh.n_faces, mesh.n_corners
    nxt, prv = mesh.next_half_edge, mesh.prev_half_edge
    inner_edge = ~topo.boundary_edges
    compact = np.cumsum(inner_edge) - 1
    n_ei = int(inner_edge.sum())
    h0, h1 = topo.edge_half_edges[inner_edge].T
    cross = n_h + 2 * np.arange(n_ei, dtype=np.int32)
    quads = np.column_stack([h0, nxt[h1], h1, nxt[h0]]).reshape(-1)
    quad_edges = np.column_stack([cross, h1, cross + 1, h0]).reshape(-1)
    ring_offsets, ring = vertex_rings(mesh, inner_vertices(mesh))
    p = prv[ring]
    ring_edges = n_h + 2 * compact[topo.half_edge_edge[p]] + 1 - topo.half_edge_side[p]
    n_vi = len(ring_offsets) - 1
    offsets = np.concatenate([mesh.face_offsets, n_h + 4 * np.arange(1, n_ei + 1),
                              n_h + 4 * n_ei + ring_offsets[1:]])
    face_indices = np.concatenate([np.arange(n_h), quads, ring])
    child_edges = np.concatenate([np.arange(n_h), quad_edges, ring_edges])
    child = ragged_mesh(corner_points(mesh), offsets, face_indices, child_edges, n_h + 2 * n_ei)

    parent_face = np.full(n_f + n_ei + n_vi, -1, dtype=np.int32)
    parent_face[:n_f] = np.arange(n_f)
    parent_corner = np.full(n_f + n_ei + n_vi, -1, dtype=np.int32)
    parent_edge = np.concatenate([mesh.half_edge_face,
                                  np.repeat(np.flatnonzero(inner_edge), 2)]).astype(np.int32)
    edge_part = np.repeat(np.array([IN_FACE, ACROSS_EDGE], dtype=np.int8), [n_h, 2 * n_ei])
    return Level(child, parent_face, parent_corner, parent_edge, edge_part)
