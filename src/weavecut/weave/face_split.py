"""The general face-split weave for any mesh (paper 5.4; Mercat's Celtic links).

Every face gets its vertex mean c_f, joined to its corners; the original edges are removed, so
every inner edge (u, w) with faces f (left of u -> w) and g becomes the quad (u, c_g, w, c_f).
Old vertices are c1 and centres c2, a two-colouring of any mesh; the crossings lie on the
original edges. Outer edges give no quad.

Numbering: vertices ``[old V | centre of every face]``; quad i belongs to the i-th inner edge
(increasing edge id).
"""

from __future__ import annotations

import numpy as np

from ..mesh import Mesh
from ..mesh_geometry import face_centroids
from .model import Weave
from .quad import quad_weave, twins_by_key


def face_split_mesh(mesh: Mesh) -> Mesh:
    """The quad mesh (u, c_g, w, c_f) of the inner edges, over ``[old V | face centres]``."""
    topo = mesh.topology
    he = topo.edge_half_edges
    inner = (he >= 0).all(axis=1)
    f, g = mesh.half_edge_face[he[inner, 0]], mesh.half_edge_face[he[inner, 1]]
    u, w = topo.edges[inner, 0], topo.edges[inner, 1]
    n_v = mesh.n_vertices
    quads = np.column_stack([u, g + n_v, w, f + n_v]).astype(np.int32)
    return Mesh.trusted(np.concatenate([mesh.vertices, face_centroids(mesh)]),
                        np.arange(0, 4 * len(quads) + 1, 4, dtype=np.int64), quads.reshape(-1))


def face_split_weave(mesh: Mesh) -> Weave:
    """The face-split weave; its mesh is ``face_split_mesh(mesh)``, one tile per quad."""
    quads = face_split_mesh(mesh)
    c1 = np.arange(quads.n_vertices) < mesh.n_vertices
    return quad_weave(quads, c1, twins_by_key(quads))
