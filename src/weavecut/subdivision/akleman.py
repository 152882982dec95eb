"""Akleman et al.'s "pentagon preserving" construction (the paper's section 3, their sec. 5.2).

E. Akleman, V. Srinivasan, Z. Melek, P. Edmundson, "Semi-regular pentagonal subdivisions"
(2004), as the paper describes it: split every edge at its midpoint m_e, and move a copy of the
midpoint towards the centre of each face that has the edge, p_h = m_e + t (c_f - m_e) for
the half-edge h of e in f. The copies form a smaller n-gon inside every n-gon, and every corner
a_h of the face becomes the pentagon (a_h, m_e(h), p_h, p_prev(h), m_e(prev h)). So a pentagon
mesh stays a pentagon mesh; other faces keep their degree in the inner copy. ``t`` = 1/2 by
default (the paper gives no value); no smoothing. The construction needs no boundary rule.

Numbering (child of a mesh with V, E, F, H): vertices ``[old V | midpoint per edge | copy per
corner]`` (edge e -> V + e, corner h -> V + E + h); faces ``[F inner copies | H corner
pentagons]``; edges ``2e`` (u, m_e), ``2e + 1`` (w, m_e), ``2E + h`` the spoke (m_e(h), p_h),
``2E + H + h`` the inner ring edge (p_h, p_next(h)).
Counts: V' = V + E + H, E' = 2E + 2H, F' = F + H.
"""

from __future__ import annotations

import numpy as np

from ..mesh import Mesh
from ..mesh_geometry import face_centroids
from ._common import corner_index, ragged_mesh
from .hierarchy import Level

FIRST_HALF, SECOND_HALF, SPOKE, RING = 0, 1, 2, 3
EDGE_PARTS = {"first half": FIRST_HALF, "second half": SECOND_HALF, "spoke": SPOKE,
              "ring": RING}


def counts(n_vertices: int, n_edges: int, n_faces: int, n_corners: int):
    """(V', E', F', H') after one step.

    Examples
    --------
    >>> counts(5, 5, 1, 5)  # a pentagon -> a pentagon and five pentagons around it
    (15, 20, 6, 30)
    """
    return (n_vertices + n_edges + n_corners, 2 * n_edges + 2 * n_corners, n_faces + n_corners,
            6 * n_corners)


def step(mesh: Mesh, *, t: float = 0.5) -> Level:
    """One pentagon-preserving step; ``t`` in (0, 1) is how far the copies move inwards."""
    if not 0.0 < t < 1.0:
        raise ValueError(f"t must lie strictly between 0 and 1, got {t}")
    topo = mesh.topology
    n_v, n_e, n_f, n_h = mesh.n_vertices, topo.n_edges, mesh.n_faces, mesh.n_corners
    e = topo.edges
    mids = 0.5 * (np.take(mesh.vertices, e[:, 0], axis=0) + np.take(mesh.vertices, e[:, 1], axis=0))
    he_edge, side = topo.half_edge_edge, topo.half_edge_side.astype(np.int32)
    copies = (1 - t) * mids[he_edge] + t * face_centroids(mesh)[mesh.half_edge_face]
    vertices = np.concatenate([mesh.vertices, mids, copies])

    prv = mesh.prev_half_edge
    h = np.arange(n_h, dtype=np.int32)
    m, p = he_edge + n_v, h + n_v + n_e
    pentagons = np.column_stack([mesh.face_indices, m, p, p[prv], m[prv]]).reshape(-1)
    spoke, ring = 2 * n_e + h, 2 * n_e + n_h + h
    pent_edges = np.column_stack([2 * he_edge + side, spoke, ring[prv], spoke[prv],
                                  2 * he_edge[prv] + 1 - side[prv]]).reshape(-1)
    offsets = np.concatenate([mesh.face_offsets, n_h + 5 * np.arange(1, n_h + 1)])
    child = ragged_mesh(vertices, offsets, np.concatenate([p, pentagons]),
                        np.concatenate([ring, pent_edges]), 2 * n_e + 2 * n_h)

    parent_face = np.concatenate([np.arange(n_f), mesh.half_edge_face]).astype(np.int32)
    parent_corner = np.concatenate([np.full(n_f, -1), corner_index(mesh)]).astype(np.int32)
    parent_edge = np.concatenate([np.repeat(np.arange(n_e), 2), mesh.half_edge_face,
                                  mesh.half_edge_face]).astype(np.int32)
    edge_part = np.repeat(np.array([FIRST_HALF, SPOKE, RING], dtype=np.int8), [2 * n_e, n_h, n_h])
    edge_part[1:2 * n_e:2] = SECOND_HALF
    return Level(child, parent_face, parent_corner, parent_edge, edge_part)
