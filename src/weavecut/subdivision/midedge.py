"""Mid-edge subdivision (Peters and Reif 1997; Habib and Warren 1999): join edge midpoints.

J. Peters, U. Reif, "The simplest subdivision scheme for smoothing polyhedra" (ACM TOG 1997):
every edge gets its midpoint, and the midpoints of two edges that share a vertex and a face are
joined. A face of degree n keeps a face of degree n (the midpoint polygon), an inner vertex of
valence k becomes a face of degree k, and two steps match one Doo-Sabin step combinatorially
(child vertex h of the second step, the midpoint of corner edge h, is Doo-Sabin's corner h).

Boundary (our rule; Peters and Reif treat closed meshes): an outer vertex v in two or more
faces stays a vertex and gives the face (v, m_first, ..., m_last) with the midpoints of its
edges in counter-clockwise order, so the mesh stays manifold; an outer vertex in a single face
is cut off (its face would be a sliver, flat on a straight boundary).

Numbering (child of a mesh with V, E, F, H): vertices ``[one per
edge (edge e -> e, its midpoint) | the kept outer vertices in increasing id]``; faces ``[F face
polygons | vertex polygons in increasing vertex id]`` (inner vertices and kept outer
vertices, see ``polygon_vertices``); edges ``h`` = (m_e(prev h), m_e(h)) inside the
face of corner h, then ``H + 2i`` = (v, m_first) and ``H + 2i + 1`` = (m_last, v) for the i-th
kept outer vertex. With V_in inner and V_out kept outer vertices:
V' = E + V_out, E' = H + 2 V_out, F' = F + V_in + V_out.
Vertex polygons have parent_face = parent_corner = -1.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ._common import is_outer, ragged_mesh, vertex_rings
from .hierarchy import Level

CORNER, OUTER_SPOKE = 0, 1
EDGE_PARTS = {"corner": CORNER, "outer spoke": OUTER_SPOKE}


def inner_vertices(mesh: Mesh) -> NDArray[np.int64]:
    """Ids of the inner vertices (those with a closed fan of faces), increasing."""
    return np.flatnonzero(~is_outer(mesh))


def counts(n_vertices: int, n_edges: int, n_faces: int, n_corners: int) -> tuple[int, ...]:
    """Upper bounds of (V', E', F', H') from V, E, F, H alone (for memory checks)."""
    e = n_corners + 2 * n_vertices
    return n_edges + n_vertices, e, n_faces + n_vertices, 2 * e


def exact_counts(n_edges: int, n_faces: int, n_corners: int, n_inner: int, n_outer: int):
    """(V', E', F') after one step; ``n_outer`` counts outer vertices in two or more faces.

    Examples
    --------
    >>> exact_counts(12, 4, 16, 1, 4)  # a 2 x 2 quad grid: 4 corners cut off
    (16, 24, 9)
    """
    return n_edges + n_outer, n_corners + 2 * n_outer, n_faces + n_inner + n_outer


def step(mesh: Mesh) -> Level:
    """One mid-edge step (see the module docstring for the numbering)."""
    topo = mesh.topology
    n_e, n_f, n_h = topo.n_edges, mesh.n_faces, mesh.n_corners
    n_faces_at = np.bincount(mesh.face_indices, minlength=mesh.n_vertices)
    outer_all = is_outer(mesh)
    used = np.flatnonzero((n_faces_at > 0) & ~(outer_all & (n_faces_at < 2)))
    outer = outer_all[used]
    ring_offsets, ring = vertex_rings(mesh, used)
    he_edge = topo.half_edge_edge
    n_out = int(outer.sum())
    out_id = np.cumsum(outer) - 1                      # index among the outer vertices

    # every vertex polygon: midpoints of its ring; an outer one adds (v) first and
    # the last edge m_e(prev h_last) at the end
    sizes = np.diff(ring_offsets) + 2 * outer
    offsets = np.zeros(len(used) + 1, dtype=np.int64)
    np.cumsum(sizes, out=offsets[1:])
    slot = np.repeat(offsets[:-1] + outer, np.diff(ring_offsets)) + (
        np.arange(len(ring)) - np.repeat(ring_offsets[:-1], np.diff(ring_offsets)))
    poly = np.empty(offsets[-1], dtype=np.int64)
    poly_edges = np.empty(offsets[-1], dtype=np.int64)
    poly[slot], poly_edges[slot] = he_edge[ring], ring
    o = np.flatnonzero(outer)
    last = ring[ring_offsets[o + 1] - 1]
    poly[offsets[o]] = n_e + out_id[o]
    poly_edges[offsets[o]] = n_h + 2 * out_id[o]
    poly[offsets[o + 1] - 1] = he_edge[mesh.prev_half_edge[last]]
    poly_edges[offsets[o + 1] - 1] = n_h + 2 * out_id[o] + 1
    # the half-edge leaving slot k is the corner edge of ring entry k (set above); for an
    # outer polygon the last ring entry leads to m_last, and m_last leads back to v

    e = topo.edges
    mids = 0.5 * (np.take(mesh.vertices, e[:, 0], axis=0) + np.take(mesh.vertices, e[:, 1], axis=0))
    vertices = np.concatenate([mids, mesh.vertices[used[outer]]])
    child = ragged_mesh(vertices, np.concatenate([mesh.face_offsets, n_h + offsets[1:]]),
                        np.concatenate([he_edge, poly]),
                        np.concatenate([mesh.next_half_edge, poly_edges]), n_h + 2 * n_out)
    n_p = len(used)
    parent_face = np.concatenate([np.arange(n_f), np.full(n_p, -1)]).astype(np.int32)
    parent_corner = np.full(n_f + n_p, -1, dtype=np.int32)
    outer_v = used[o]
    parent_edge = np.concatenate([mesh.half_edge_face, np.repeat(outer_v, 2)]).astype(np.int32)
    edge_part = np.repeat(np.array([CORNER, OUTER_SPOKE], dtype=np.int8), [n_h, 2 * n_out])
    return Level(child, parent_face, parent_corner, parent_edge, edge_part)
