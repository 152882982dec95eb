"""The dual mesh: a vertex at every face's vertex mean, a face around every inner vertex.

The dual of a planar mesh with boundary, simplified to its inner part: outer vertices give no
face and outer edges no dual edge (the classic dual; e.g. Botsch et al., "Polygon Mesh
Processing", 2010, sec. 1.3). The dual of a triangle mesh after Loop, butterfly or sqrt(3) is
hexagon-dominant, as the paper's section 2.2 says. Dual edges cross the inner edges
with at least one inner end (E_in below counts those).

Numbering (mesh with F faces, V_in inner vertices, E_in inner edges): vertices: face f -> f;
faces: one per inner vertex in increasing id (face i around ``inner_vertices(mesh)[i]``), its
corners the faces around the vertex counter-clockwise; edges: the i-th inner edge (increasing
edge id) -> dual edge i. Counts: V' = F, E' = E_in, F' = V_in. Faces have no parent face (-1).
"""

from __future__ import annotations

import numpy as np

from ..mesh import Mesh
from ..mesh_geometry import face_centroids
from ._common import ragged_mesh, vertex_rings
from .hierarchy import Level
from .midedge import inner_vertices

CROSSING = 0
EDGE_PARTS = {"crossing": CROSSING}


def counts(n_vertices: int, n_edges: int, n_faces: int, n_corners: int) -> tuple[int, ...]:
    """Upper bounds of (V', E', F', H') from V, E, F, H alone (for memory checks)."""
    return n_faces, n_edges, n_vertices, 2 * n_edges


def step(mesh: Mesh) -> Level:
    """The dual mesh as a Level (see the module docstring for the numbering)."""
    topo = mesh.topology
    ring_offsets, ring = vertex_rings(mesh, inner_vertices(mesh))
    inner_v = np.zeros(mesh.n_vertices, dtype=bool)
    inner_v[inner_vertices(mesh)] = True
    inner_edge = inner_v[topo.edges].any(axis=1)   # the edges a dual face crosses
    compact = np.cumsum(inner_edge) - 1
    crossed = topo.half_edge_edge[mesh.prev_half_edge[ring]]
    child = ragged_mesh(face_centroids(mesh), ring_offsets, mesh.half_edge_face[ring],
                        compact[crossed], int(inner_edge.sum()))
    n_in = len(ring_offsets) - 1
    minus = np.full(n_in, -1, dtype=np.int32)
    parent_edge = np.flatnonzero(inner_edge).astype(np.int32)
    return Level(child, minus, minus.copy(), parent_edge,
                 np.full(len(parent_edge), CROSSING, dtype=np.int8))
