"""Geometry of a mesh: the measures its coordinates give (face centroids, areas and perimeters,
corner turns and angles, edge lengths) and its mirror image; the topology in ``mesh`` never
looks at coordinates.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .mesh import Mesh


def face_centroids(mesh: Mesh) -> NDArray[np.float64]:
    """(F, D) vertex mean of every face (the paper's "barycentre")."""
    dense = mesh.dense_faces()
    if dense is not None and mesh.dim == 2:  # summing complex columns: far faster than mean
        points = np.take(mesh.vertices.view(np.complex128).ravel(), dense)
        total = points[:, 0].copy()
        for k in range(1, dense.shape[1]):
            total += points[:, k]
        return (total / dense.shape[1]).view(np.float64).reshape(-1, 2)
    sums = np.add.reduceat(np.take(mesh.vertices, mesh.face_indices, axis=0),
                           mesh.face_offsets[:-1], axis=0)
    return sums / mesh.face_sizes[:, None]


def signed_areas(mesh: Mesh) -> NDArray[np.float64]:
    """(F,) shoelace area of every face, positive when counter-clockwise."""
    p = np.take(mesh.vertices, mesh.face_indices, axis=0)
    q = p[mesh.next_half_edge]
    cross = p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]
    return 0.5 * np.add.reduceat(cross, mesh.face_offsets[:-1]) if mesh.n_faces else cross[:0]


def area_centroids(mesh: Mesh) -> NDArray[np.float64]:
    """(F, 2) area centroid of every face."""
    p = np.take(mesh.vertices, mesh.face_indices, axis=0)
    q = p[mesh.next_half_edge]
    cross = p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]
    starts = mesh.face_offsets[:-1]
    a = 0.5 * np.add.reduceat(cross, starts)
    cx = np.add.reduceat((p[:, 0] + q[:, 0]) * cross, starts)
    cy = np.add.reduceat((p[:, 1] + q[:, 1]) * cross, starts)
    return np.column_stack([cx, cy]) / (6.0 * a[:, None])


def corner_turns(mesh: Mesh) -> NDArray[np.float64]:
    """(H,) cross product of the two edges at every corner; negative at a reflex corner."""
    p = mesh.vertices[mesh.face_indices]
    a = p - p[mesh.prev_half_edge]
    b = p[mesh.next_half_edge] - p
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def corner_angles(mesh: Mesh) -> NDArray[np.float64]:
    """(H,) interior angle at every corner in radians (in (0, 2*pi) for CCW faces)."""
    p = mesh.vertices[mesh.face_indices]
    a = p[mesh.prev_half_edge] - p
    b = p[mesh.next_half_edge] - p
    cross = b[:, 0] * a[:, 1] - b[:, 1] * a[:, 0]
    dot = (a * b).sum(axis=1)
    return np.mod(np.arctan2(cross, dot), 2 * np.pi)


def face_perimeters(mesh: Mesh) -> NDArray[np.float64]:
    """(F,) perimeter of every face."""
    p = mesh.vertices[mesh.face_indices]
    step = np.linalg.norm(p[mesh.next_half_edge] - p, axis=1)
    return np.add.reduceat(step, mesh.face_offsets[:-1])


def edge_lengths(mesh: Mesh) -> NDArray[np.float64]:
    """(E,) length of every edge."""
    e = mesh.topology.edges
    d = mesh.vertices[e[:, 1]] - mesh.vertices[e[:, 0]]
    return np.hypot(*d.T) if mesh.dim == 2 else np.linalg.norm(d, axis=1)


def mirrored(mesh: Mesh) -> Mesh:
    """Reflect in the y axis (x -> -x), keeping faces counter-clockwise."""
    flipped = mesh.reversed()
    return Mesh(mesh.vertices * np.array([-1.0, 1.0]), flipped.face_offsets, flipped.face_indices)
