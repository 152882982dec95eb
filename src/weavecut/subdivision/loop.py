"""Loop subdivision (Loop 1987): every triangle splits 1-to-4 at its edge points.

Stencils (C. Loop, "Smooth subdivision surfaces based on triangles", 1987):

- edge (odd) vertex on an inner edge (u, w) with opposite vertices c, d:
  3/8 (u + w) + 1/8 (c + d);
- old (even) inner vertex of valence n: (1 - n beta) v + beta * sum(neighbours),
  beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n  (Loop's original weights);
- boundary, following Hoppe et al. 1994 ("Piecewise smooth surface reconstruction"): an outer
  edge gets its midpoint, an outer vertex 3/4 v + 1/8 (its two outer neighbours), i.e. the
  boundary is a cubic B-spline. Simplified: no corner or crease tags, so a corner of the input
  boundary is smoothed like any other outer vertex.

Numbering (child of a triangle mesh with V, E, F, H = 3F), shared with butterfly:
vertices ``[old V | one per edge]`` (edge e -> ``V + e``); faces ``4f + i`` for the corner
triangle ``(a_i, m_i, m_{i-1})`` at corner i and ``4f + 3`` for the middle triangle
``(m_0, m_1, m_2)``, where ``m_i`` is the point of edge ``a_i -> a_{i+1}``; edges ``2e``
(u, m_e) and ``2e + 1`` (w, m_e) for the halves of edge e = (u, w), and ``2E + h`` for the
inner edge ``(m_i, m_{i-1})`` cut off by corner h. Counts: V' = V + E, E' = 2E + H, F' = 4F.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh, Topology
from ._common import is_outer, trusted_dense, neighbour_sums, require_degree
from .hierarchy import Level

FIRST_HALF, SECOND_HALF, INNER = 0, 1, 2
EDGE_PARTS = {"first half": FIRST_HALF, "second half": SECOND_HALF, "inner": INNER}


def counts(n_vertices: int, n_edges: int, n_faces: int, n_corners: int) -> tuple[int, ...]:
    """(V', E', F', H') after one 1-to-4 split of a triangle mesh.

    Examples
    --------
    >>> counts(3, 3, 1, 3)
    (6, 9, 4, 12)
    """
    return n_vertices + n_edges, 2 * n_edges + n_corners, 4 * n_faces, 4 * n_corners


def step(mesh: Mesh) -> Level:
    """One Loop step on a triangle mesh (see the module docstring for stencils and numbering)."""
    require_degree(mesh, 3, "Loop subdivision")
    topo = mesh.topology
    vertices = np.empty((mesh.n_vertices + topo.n_edges, 2))
    vertices[:mesh.n_vertices] = even_points(mesh)
    vertices[mesh.n_vertices:] = odd_points(mesh)
    return split_1_to_4(mesh, vertices)


def even_points(mesh: Mesh) -> NDArray[np.float64]:
    """(V, 2) new positions of the old vertices."""
    v = mesh.vertices
    topo = mesh.topology
    sums, n = neighbour_sums(mesh)
    n = np.maximum(n, 1)
    beta = (5 / 8 - (3 / 8 + np.cos(2 * np.pi / n) / 4) ** 2) / n
    out = (1 - n * beta)[:, None] * v + beta[:, None] * sums
    outer = is_outer(mesh)
    if outer.any():
        bsum, bn = neighbour_sums(mesh, topo.boundary_edges)
        on_curve = outer & (bn == 2)
        out[on_curve] = 0.75 * v[on_curve] + 0.125 * bsum[on_curve]
        out[outer & (bn != 2)] = v[outer & (bn != 2)]
    return out


def odd_points(mesh: Mesh) -> NDArray[np.float64]:
    """(E, 2) positions of the edge points."""
    topo = mesh.topology
    v = mesh.vertices
    e = topo.edges
    opposite = mesh.face_indices[mesh.prev_half_edge]
    he = topo.edge_half_edges
    inner = (he >= 0).all(axis=1)
    ends = np.take(v, e[:, 0], axis=0)
    ends += np.take(v, e[:, 1], axis=0)
    c = np.take(v, opposite[np.maximum(he[:, 0], 0)], axis=0)
    c += np.take(v, opposite[np.maximum(he[:, 1], 0)], axis=0)
    out = 0.375 * ends + 0.125 * c
    if not inner.all():
        out[~inner] = 0.5 * ends[~inner]
    return out


def split_1_to_4(mesh: Mesh, vertices: NDArray[np.float64]) -> Level:
    """The 1-to-4 triangle split with its provenance, given the child's vertex positions."""
    topo = mesh.topology
    n_v, n_e, n_f = mesh.n_vertices, topo.n_edges, mesh.n_faces
    tri = mesh.face_indices.reshape(-1, 3)
    he_edge = topo.half_edge_edge.reshape(-1, 3)
    side = topo.half_edge_side.reshape(-1, 3).astype(np.int32)
    m = he_edge + np.int32(n_v)
    m_prev = m[:, [2, 0, 1]]
    n_new = 2 * n_e + 3 * n_f
    faces = np.empty((n_f, 4, 3), dtype=np.int32)
    parts = np.empty((n_f, 4, 3), dtype=np.int32)
    sides = np.empty((n_f, 4, 3), dtype=np.int8)
    corner = np.arange(3 * n_f, dtype=np.int32).reshape(-1, 3) + np.int32(2 * n_e)
    flipped = m > m_prev                      # inner edge (m_i, m_{i-1}) stored the other way
    for i in range(3):
        p = (i - 1) % 3
        faces[:, i, 0], faces[:, i, 1], faces[:, i, 2] = tri[:, i], m[:, i], m[:, p]
        parts[:, i, 0] = 2 * he_edge[:, i] + side[:, i]
        parts[:, i, 1] = corner[:, i]
        parts[:, i, 2] = 2 * he_edge[:, p] + 1 - side[:, p]
        sides[:, i, 0], sides[:, i, 1], sides[:, i, 2] = 0, flipped[:, i], 1
        faces[:, 3, i] = m[:, i]
        parts[:, 3, i] = corner[:, (i + 1) % 3]
        sides[:, 3, i] = ~flipped[:, (i + 1) % 3]
    edges = np.empty((n_new, 2), dtype=np.int32)
    halves = edges[:2 * n_e].reshape(n_e, 2, 2)
    halves[:, :, 0] = topo.edges
    halves[:, :, 1] = np.arange(n_v, n_v + n_e, dtype=np.int32)[:, None]
    inner = edges[2 * n_e:]
    inner[:, 0] = np.minimum(m, m_prev).reshape(-1)
    inner[:, 1] = np.maximum(m, m_prev).reshape(-1)
    boundary = np.zeros(n_new, dtype=bool)
    boundary[:2 * n_e] = np.repeat(topo.boundary_edges, 2)
    child = trusted_dense(vertices, faces.reshape(-1, 3),
                          Topology(edges, parts.reshape(-1), sides.reshape(-1)), boundary)

    parent_edge = np.empty(2 * n_e + 3 * n_f, dtype=np.int32)
    parent_edge[:2 * n_e] = np.repeat(np.arange(n_e, dtype=np.int32), 2)
    parent_edge[2 * n_e:] = mesh.half_edge_face
    edge_part = np.full(2 * n_e + 3 * n_f, INNER, dtype=np.int8)
    edge_part[:2 * n_e] = np.tile(np.array([FIRST_HALF, SECOND_HALF], dtype=np.int8), n_e)
    parent_face = np.repeat(np.arange(n_f, dtype=np.int32), 4)
    parent_corner = np.tile(np.array([0, 1, 2, -1], dtype=np.int32), n_f)
    return Level(child, parent_face, parent_corner, parent_edge, edge_part)
