"""The pentagon snub step as it was written before the in-place rewrite (frozen, do not
optimise): the oracle that ``test_snub_identity.py`` holds the engine to, array for array.

It builds the child's faces by stacking columns, computes the child face centres with
``face_centroids``/``area_centroids`` of the whole child, and smooths from those: the direct
reading of the paper's operations, with the same numbering as ``weavecut.subdivision.snub``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from weavecut.mesh import Mesh, Topology, outer_vertices
from weavecut.mesh_geometry import area_centroids, face_centroids
from weavecut.subdivision.hierarchy import Level
from weavecut.subdivision.snub import FIRST, LAST, MIDDLE, SPOKE


def step(mesh: Mesh, *, smooth: bool = True, centre: str = "vertex",
         chirality: str = "left") -> Level:
    """``weavecut.subdivision.snub.step`` as it was written directly (module docstring)."""
    right = chirality == "right"
    topo = mesh.topology
    n_v, n_e, n_f, n_h = mesh.n_vertices, topo.n_edges, mesh.n_faces, mesh.n_corners
    centre_of = area_centroids if centre == "area" else face_centroids

    # operations 1 and 2: Z vertices and face centres
    vertices = np.empty((n_v + 2 * n_e + n_f, 2))
    vertices[:n_v] = mesh.vertices
    u = np.take(mesh.vertices, topo.edges[:, 0], axis=0)
    d = np.take(mesh.vertices, topo.edges[:, 1], axis=0) - u
    s = (-1.0 if right else 1.0) * np.sqrt(3.0)
    z = vertices[n_v:n_v + 2 * n_e].reshape(n_e, 2, 2)
    z[:, 0, 0] = u[:, 0] + (5 * d[:, 0] - s * d[:, 1]) / 14
    z[:, 0, 1] = u[:, 1] + (5 * d[:, 1] + s * d[:, 0]) / 14
    z[:, 1, 0] = u[:, 0] + (9 * d[:, 0] + s * d[:, 1]) / 14
    z[:, 1, 1] = u[:, 1] + (9 * d[:, 1] - s * d[:, 0]) / 14
    vertices[n_v + 2 * n_e:] = centre_of(mesh)

    # operation 3: one pentagon per half-edge, with its topology read off the parent's
    he_edge = topo.half_edge_edge.astype(np.int32)
    side = topo.half_edge_side
    face_side = side if not right else 1 - side  # which of z0, z1 is x_h
    x = n_v + 2 * he_edge + face_side
    y = n_v + 2 * he_edge + (1 - face_side)
    c = n_v + 2 * n_e + mesh.half_edge_face
    a = mesh.face_indices
    nb = mesh.prev_half_edge if right else mesh.next_half_edge
    spoke = 3 * n_e + np.arange(n_h, dtype=np.int32)
    middle = 3 * he_edge + MIDDLE
    near_end = 3 * he_edge + 2 * (1 - side)       # the Z part at b, the end of h
    near_start = 3 * he_edge + 2 * side           # the Z part at a, the start of h
    sidecol = side.astype(np.int8)
    if right:
        corners = (a, y, x, c, x[nb])
        parts = (near_start, middle, spoke, spoke[nb], near_end[nb])
        sides = (0, sidecol, 0, 1, 1)
    else:
        corners = (c, x, y, a[mesh.next_half_edge], x[nb])
        parts = (spoke, middle, near_end, near_start[nb], spoke[nb])
        sides = (1, sidecol, 1, 0, 0)
    faces = _stack(corners, np.int32, n_h)
    child_he_edge = _stack(parts, np.int32, n_h)
    child_side = _stack(sides, np.int8, n_h)

    edges = np.empty((3 * n_e + n_h, 2), dtype=np.int32)
    zids = n_v + 2 * np.arange(n_e, dtype=np.int32)
    ez = edges[:3 * n_e].reshape(n_e, 3, 2)
    ez[:, FIRST, 0], ez[:, FIRST, 1] = topo.edges[:, 0], zids
    ez[:, MIDDLE, 0], ez[:, MIDDLE, 1] = zids, zids + 1
    ez[:, LAST, 0], ez[:, LAST, 1] = topo.edges[:, 1], zids + 1
    edges[3 * n_e:, 0], edges[3 * n_e:, 1] = x, c

    child_topo = Topology(edges, child_he_edge, child_side)
    boundary = np.zeros(len(edges), dtype=bool)
    boundary[:3 * n_e] = np.repeat(topo.boundary_edges, 3)
    child_topo.__dict__["boundary_edges"] = boundary
    offsets = np.arange(0, 5 * n_h + 1, 5, dtype=np.int64)
    child = Mesh.trusted(vertices, offsets, faces, child_topo)
    if smooth:
        around = mesh.next_half_edge if right else mesh.prev_half_edge  # P_h's neighbour at x_h
        child = Mesh.trusted(_smoothed(mesh, child, x, around, right, centre_of), offsets,
                             faces, child_topo)

    parent_edge = np.empty(len(edges), dtype=np.int32)
    parent_edge[:3 * n_e] = np.repeat(np.arange(n_e, dtype=np.int32), 3)
    parent_edge[3 * n_e:] = mesh.half_edge_face
    edge_part = np.full(len(edges), SPOKE, dtype=np.int8)
    edge_part[:3 * n_e] = np.tile(np.array([FIRST, MIDDLE, LAST], dtype=np.int8), n_e)
    corner = np.arange(n_h, dtype=np.int32) - mesh.face_offsets[:-1].astype(np.int32)[
        mesh.half_edge_face]
    return Level(child, mesh.half_edge_face, corner, parent_edge, edge_part)


def _stack(columns, dtype, n: int) -> NDArray:
    """(n * 5,) row-major interleave of five columns (arrays or scalars)."""
    out = np.empty((n, len(columns)), dtype=dtype)
    for k, col in enumerate(columns):
        out[:, k] = col
    return out.reshape(-1)


def _smoothed(parent: Mesh, child: Mesh, x, around, right: bool,
              centre_of) -> NDArray[np.float64]:
    """Operation 4: every inner vertex moves, all at once, to the mean centre of its faces.

    The faces around each kind of child vertex are known from the parent, so the sums run
    over parent corners (H) instead of child corners (5H):
    a Z vertex x_h lies in P_h, P_around(h) and (inner edges) P_twin(h); a centre in the faces of
    its parent face; an old vertex in one face per parent corner at it.
    """
    topo = parent.topology
    n_v, n_e = parent.n_vertices, topo.n_edges
    centres = centre_of(child).view(np.complex128).ravel()  # (H,) one per child face
    out = child.vertices.copy()
    flat = out.view(np.complex128).ravel()
    twin = topo.twin
    inner = twin >= 0
    z_sum = centres + centres[around] + np.where(inner, centres[np.maximum(twin, 0)], 0)
    z_new = z_sum / np.where(inner, 3.0, 2.0)
    z_ids = x[inner]  # the x of an inner half-edge is an inner Z vertex
    flat[z_ids] = z_new[inner]
    k = parent.face_degree
    if k:
        face_sum = centres.reshape(-1, k).sum(axis=1)
    else:
        face_sum = np.add.reduceat(centres, parent.face_offsets[:-1])
    flat[n_v + 2 * n_e:] = face_sum / parent.face_sizes
    corner_vertex = parent.face_indices if right else parent.face_indices[parent.next_half_edge]
    count = np.bincount(corner_vertex, minlength=n_v)
    mean = (np.bincount(corner_vertex, weights=centres.real, minlength=n_v)
            + 1j * np.bincount(corner_vertex, weights=centres.imag, minlength=n_v))
    old_inner = ~outer_vertices(parent)
    flat[:n_v][old_inner] = mean[old_inner] / count[old_inner]
    return out
