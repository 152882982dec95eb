"""Weaves of triangle meshes by gluing pairs of triangles into quads (paper 5.3.2).

- ``triangle_weave``: a triangle mesh whose colouring gives every triangle one c1 and two c2
  corners; the c2-c2 edges are removed, so the triangles on both sides form a two-coloured
  quad. Loop and butterfly keep this property with ``triangle_colouring_step``.
- ``sqrt3_weave``: after a sqrt(3) step, the just-flipped edges are removed; each quad has two
  old vertices (c1) and two face centres (c2), diagonally.

A triangle whose glue edge is on the boundary has no partner and lies in no tile; strands end
there. Tiles are the glued pairs (two faces each); the crossing logic is the quad weave's.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..subdivision import sqrt3
from ..subdivision.hierarchy import Level
from .model import Weave
from .quad import quad_weave
from .two_colouring import check_triangle_colouring


def glued_weave(mesh: Mesh, glue: NDArray[np.bool_], c1: NDArray[np.bool_]) -> Weave:
    """Weave of the quads made by removing the ``glue`` edges (E,) of a triangle mesh.

    Every triangle may have at most one glue edge; quad (p, a, q, b) joins triangle (p, a, b)
    with the triangle (b, a, q) across its glue half-edge a -> b.
    """
    topo = mesh.topology
    fi, nxt, prv = mesh.face_indices, mesh.next_half_edge, mesh.prev_half_edge
    twin = topo.twin
    h = np.flatnonzero(glue[topo.half_edge_edge] & (topo.half_edge_side == 0) & (twin >= 0))
    t = twin[h]
    quads = np.column_stack([fi[prv[h]], fi[h], fi[prv[t]], fi[t]]).astype(np.int32)
    quad_mesh = Mesh.trusted(mesh.vertices, np.arange(0, 4 * len(h) + 1, 4, dtype=np.int64),
                             quads.reshape(-1))
    # quad half-edges are triangle half-edges: (p->a, a->q, q->b, b->p)
    tri_he = np.column_stack([prv[h], nxt[t], prv[t], nxt[h]]).reshape(-1)
    quad_he = np.full(mesh.n_corners, -1, dtype=np.int64)
    quad_he[tri_he] = np.arange(len(tri_he))
    across = twin[tri_he]
    quad_twin = np.where(across >= 0, quad_he[np.maximum(across, 0)], -1)
    w = quad_weave(quad_mesh, c1, quad_twin)
    pairs = np.column_stack([mesh.half_edge_face[h], mesh.half_edge_face[t]]).astype(np.int32)
    return Weave(mesh, np.arange(0, 2 * len(h) + 1, 2, dtype=np.int64), pairs.reshape(-1),
                 w.strand_offsets, w.strand_visits, w.visit_over, w.strand_closed)


def triangle_weave(mesh: Mesh, c1: NDArray[np.bool_]) -> Weave:
    """Weave of a triangle mesh with one c1 and two c2 corners per triangle."""
    c1 = np.asarray(c1, dtype=bool)
    check_triangle_colouring(mesh, c1)
    e = mesh.topology.edges
    return glued_weave(mesh, ~c1[e[:, 0]] & ~c1[e[:, 1]], c1)


def sqrt3_weave(level: Level, n_parent_vertices: int) -> Weave:
    """Weave of a sqrt(3) level: glue across the flipped edges; old vertices are c1."""
    c1 = np.zeros(level.mesh.n_vertices, dtype=bool)
    c1[:n_parent_vertices] = True
    return glued_weave(level.mesh, level.edge_part == sqrt3.FLIPPED, c1)
