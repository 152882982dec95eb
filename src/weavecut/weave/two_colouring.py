"""Vertex two-colourings (c1 / c2) that turn quad and triangle meshes into weaves (paper 5.3).

A colouring is a (V,) bool array, True for c1.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.sparse.csgraph import connected_components, dijkstra

from ..errors import MeshError
from ..mesh import Mesh
from ..subdivision.catmull_clark import SPOKE as CC_SPOKE
from ..subdivision.hierarchy import Level


def disc_two_colouring(mesh: Mesh) -> NDArray[np.bool_]:
    """(V,) disc growing: the lowest vertex of every component is c1, BFS layers alternate.

    Raises MeshError when the edge graph has an odd cycle (e.g. a triangle), naming an edge
    whose ends got the same colour.
    """
    e = mesh.topology.edges
    n = mesh.n_vertices
    graph = sp.coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n)).tocsr()
    _, label = connected_components(graph, directed=False)
    roots = np.unique(label, return_index=True)[1]
    dist = dijkstra(graph, directed=False, unweighted=True, indices=roots, min_only=True)
    c1 = (np.nan_to_num(dist, posinf=0).astype(np.int64) % 2) == 0
    check_two_colouring(mesh, c1)
    return c1


def check_two_colouring(mesh: Mesh, c1: NDArray[np.bool_]) -> None:
    """Raise MeshError unless every edge joins a c1 and a c2 vertex."""
    e = mesh.topology.edges
    bad = np.flatnonzero(c1[e[:, 0]] == c1[e[:, 1]])
    if len(bad):
        u, w = e[bad[0]]
        raise MeshError(f"not two-colourable: edge ({u}, {w}) joins two vertices of one colour "
                        f"({len(bad)} such edges)")


def catmull_clark_colouring(level: Level) -> NDArray[np.bool_]:
    """(V',) after a Catmull-Clark step: edge points c1; old vertices and face points c2."""
    c1 = np.zeros(level.mesh.n_vertices, dtype=bool)
    spokes = level.mesh.topology.edges[level.edge_part == CC_SPOKE]
    c1[spokes[:, 0]] = True
    return c1


def check_triangle_colouring(mesh: Mesh, c1: NDArray[np.bool_]) -> None:
    """Raise MeshError unless every triangle has exactly one c1 corner."""
    per_face = np.add.reduceat(c1[mesh.face_indices].astype(np.int64), mesh.face_offsets[:-1])
    bad = np.flatnonzero((per_face != 1) | (mesh.face_sizes != 3))
    if len(bad):
        raise MeshError(f"face {bad[0]} is not a triangle with exactly one c1 corner "
                        f"({len(bad)} such faces)")


def triangle_colouring_step(parent: Mesh, c1: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """(V + E,) the colouring after a Loop or butterfly step (the paper's propagation rule).

    Old vertices keep their colour; the point of a c1-c2 edge is c2, of a c2-c2 edge c1.
    """
    e = parent.topology.edges
    return np.concatenate([c1, ~c1[e[:, 0]] & ~c1[e[:, 1]]])
