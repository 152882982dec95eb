"""The weave of a two-coloured quad mesh (paper 5.3.1): every quad is a crossing of two strands.

A strand runs through opposite edges of each quad. Entering through an edge with the c1 vertex
on its left and the c2 vertex on its right it goes on top, otherwise below. A strand entering
a counter-clockwise quad through its half-edge h = a -> b has a on its left, so it is on top
exactly when a is c1; both strands of a quad agree on who is on top since opposite corners
share a colour.

Strands are ordered with arrays only: the map "enter through h -> enter the next quad through
twin(next(next(h)))" is ranked by pointer jumping (log of the longest strand rounds).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..errors import MeshError
from ..mesh import Mesh
from .model import Weave
from .paths import rank_paths
from .two_colouring import check_two_colouring


def quad_weave(mesh: Mesh, c1: NDArray[np.bool_], twin: NDArray[np.int64] | None = None) -> Weave:
    """The weave of a quad mesh with a vertex two-colouring; tile t is quad t.

    ``twin`` (H,) may give the opposite half-edges when the caller knows them (glued quads may
    touch at a vertex, which ``Mesh.topology`` refuses as a bow-tie).
    """
    if mesh.n_faces and mesh.face_degree != 4:
        raise MeshError("the quad weave needs a mesh of quads only")
    c1 = np.asarray(c1, dtype=bool)
    if twin is None:
        check_two_colouring(mesh, c1)
        twin = mesh.topology.twin
    else:
        fi = mesh.face_indices
        if (c1[fi] == c1[fi[mesh.next_half_edge]]).any():
            raise MeshError("not two-colourable: a quad has two neighbouring corners of one colour")
    n_f = mesh.n_faces
    offsets, visits, closed = strand_order(mesh, twin)
    over = c1[mesh.face_indices[visits]]
    return Weave(mesh, np.arange(n_f + 1, dtype=np.int64), np.arange(n_f, dtype=np.int32),
                 offsets, mesh.half_edge_face[visits], over, closed)


def strand_order(mesh: Mesh, twin: NDArray) -> tuple[NDArray[np.int64], NDArray[np.int32], NDArray[np.bool_]]:
    """Strands of a quad mesh as (offsets, entry half-edge of every visit, closed flags).

    Each strand is listed once, in the direction whose first entry half-edge id is smaller.
    """
    n = mesh.n_corners
    h = np.arange(n, dtype=np.int64)
    opposite = mesh.next_half_edge[mesh.next_half_edge].astype(np.int64)
    twin = np.asarray(twin, dtype=np.int64)
    succ = np.where(twin[opposite] >= 0, twin[opposite], -1)
    root, rank, on_cycle = rank_paths(succ)
    return _select(mesh, h, opposite, root, rank, on_cycle)


def _select(mesh, h, opposite, root, rank, on_cycle):
    """Keep one direction per strand and lay the strands out in CSR form."""
    if len(h) == 0:
        return np.zeros(1, dtype=np.int64), np.zeros(0, dtype=np.int32), np.zeros(0, dtype=bool)
    keep = root < root[opposite[root]]
    order = np.lexsort((rank[keep], root[keep]))
    states = h[keep][order]
    starts = root[keep][order]
    first = np.flatnonzero(np.r_[True, starts[1:] != starts[:-1]])
    offsets = np.r_[first, len(states)].astype(np.int64)
    return offsets, states.astype(np.int32), on_cycle[states[first]]


def twins_by_key(mesh: Mesh) -> NDArray[np.int64]:
    """(H,) opposite half-edges found by sorting edge keys, with no manifold check (-1: none).

    For quads that may touch at single vertices (bow-ties), which ``Mesh.topology`` refuses.
    """
    u = mesh.face_indices.astype(np.int64)
    w = u[mesh.next_half_edge]
    key = np.minimum(u, w) * max(mesh.n_vertices, 1) + np.maximum(u, w)
    order = np.argsort(key, kind="stable")
    same = np.flatnonzero(key[order][1:] == key[order][:-1])
    twin = np.full(len(u), -1, dtype=np.int64)
    twin[order[same]], twin[order[same + 1]] = order[same + 1], order[same]
    return twin
