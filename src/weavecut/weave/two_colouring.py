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


def triangle_three_colouring(mesh: Mesh) -> NDArray[np.bool_]:
    """(V,) a c1 set with exactly one c1 corner per triangle, from a proper 3-colouring of the
    vertices grown triangle by triangle (breadth-first over the faces, one depth at a time).

    Raises MeshError when the mesh is not made of triangles or has no such colouring (an inner
    vertex of odd degree)."""
    if mesh.face_degree != 3:
        raise MeshError("a triangle weave needs a mesh of triangles only")
    faces = mesh.dense_faces().astype(np.int64)
    topo = mesh.topology
    twin = topo.twin
    has = twin >= 0
    n_f = mesh.n_faces
    adj = sp.coo_matrix((np.ones(int(has.sum())), (mesh.half_edge_face[has],
                                                   mesh.half_edge_face[twin[has]])),
                        shape=(n_f, n_f)).tocsr()
    _, label = connected_components(adj, directed=False)
    roots = np.unique(label, return_index=True)[1]
    depth = dijkstra(adj, directed=False, unweighted=True, indices=roots, min_only=True)
    depth = np.nan_to_num(depth, posinf=0).astype(np.int64)
    colour = np.full(mesh.n_vertices, -1, dtype=np.int64)
    colour[faces[roots]] = np.arange(3)
    for d in range(1, int(depth.max(initial=0)) + 1):  # one BFS layer of faces at a time
        layer = faces[depth == d]
        known = colour[layer]
        missing = known < 0
        fill = 3 - np.where(missing, 0, known).sum(axis=1)
        rows = np.flatnonzero(missing.sum(axis=1) == 1)
        colour[layer[rows, missing[rows].argmax(axis=1)]] = fill[rows]
    c = colour[faces]
    if (c < 0).any() or (np.sort(c, axis=1) != [0, 1, 2]).any():
        raise MeshError("the triangles have no colouring with one c1 corner each "
                        "(an inner vertex of odd degree)")
    return colour == 0
