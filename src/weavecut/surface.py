"""Geometry of surfaces in space (meshes with (V, 3) vertices): normals, the plane of every
edge's Z-triplet, the circumsphere.

The Z-triplet of an edge lies in the plane through the edge whose normal bisects the normals
of the faces beside it (:func:`edge_normals`): the mean of the two unit face normals, the only
face's normal on the boundary. On a planar mesh every face normal is the plane's normal, so
the triplet lies in the plane, as the paper draws it; on a convex polyhedron the plane leans
neither way, so the triplet stays as close to both faces as it can (its bend is split evenly).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .errors import MeshError
from .mesh import Mesh
from .numeric import solve

SPHERE_TOLERANCE = 1e-6  # relative spread of the distances from the centre of a spherical mesh


def vector_areas(mesh: Mesh) -> NDArray[np.float64]:
    """(F, 3) Newell's vector area of every face: its normal times its area for a planar
    face, the mean normal's direction for a bent one (a planar mesh: (0, 0, signed area))."""
    p = np.take(mesh.vertices, mesh.face_indices, axis=0)
    if mesh.dim == 2:
        p = np.column_stack([p, np.zeros(len(p))])
    cross = np.cross(p, p[mesh.next_half_edge])
    return 0.5 * np.add.reduceat(cross, mesh.face_offsets[:-1]) if mesh.n_faces else cross[:0]


def face_normals(mesh: Mesh) -> NDArray[np.float64]:
    """(F, 3) unit normal of every face (counter-clockwise seen from the tip)."""
    areas = vector_areas(mesh)
    return areas / np.linalg.norm(areas, axis=1)[:, None]


def edge_normals(mesh: Mesh) -> NDArray[np.float64]:
    """(E, 3) unit normal of the plane every edge's Z-triplet lies in: the mean of the unit
    normals of the faces beside the edge (see the module docstring)."""
    normals = face_normals(mesh)
    he = mesh.topology.edge_half_edges
    faces = mesh.half_edge_face[np.maximum(he, 0)]
    total = np.where((he >= 0)[:, :, None], normals[faces], 0.0).sum(axis=1)
    return total / np.linalg.norm(total, axis=1)[:, None]


def signed_volume(mesh: Mesh) -> float:
    """Volume enclosed by a closed surface, positive when the faces turn outwards."""
    centres = np.add.reduceat(np.take(mesh.vertices, mesh.face_indices, axis=0),
                              mesh.face_offsets[:-1]) / mesh.face_sizes[:, None]
    return float((vector_areas(mesh) * centres).sum() / 3.0)


def circumsphere(points: NDArray[np.float64]) -> tuple[NDArray[np.float64], float]:
    """Centre and radius of the sphere through ``points`` (least squares); MeshError when
    the points do not lie on one sphere (distances from the centre spread by more than
    ``SPHERE_TOLERANCE`` of the radius)."""
    if points.shape[1] != 3:
        raise MeshError("--project sphere needs a surface in space (x, y, z vertices)")
    # |q|^2 = 2 c . q + (r^2 - |c|^2), q = p - mean: linear in c and the constant; the normal
    # equations summed and solved without BLAS or LAPACK (numeric), the same bits everywhere
    mean = points.mean(axis=0)
    q = points - mean
    a = np.column_stack([2 * q, np.ones(len(q))])
    b = (q * q).sum(axis=1)
    try:
        solution = solve((a[:, :, None] * a[:, None, :]).sum(axis=0), (a * b[:, None]).sum(axis=0))
    except ValueError:
        raise MeshError("--project sphere needs a surface in space whose vertices span a "
                        "sphere; these lie in one plane") from None
    centre = mean + solution[:3]
    distance = np.linalg.norm(points - centre, axis=1)
    radius = float(distance.mean())
    worst = int(np.argmax(np.abs(distance - radius)))
    if abs(distance[worst] - radius) > SPHERE_TOLERANCE * radius:
        raise MeshError(f"--project sphere needs vertices on a sphere; vertex {worst} is "
                        f"{distance[worst]:.6g} from the centre, the mean is {radius:.6g}")
    return centre, radius


def onto_sphere(points: NDArray[np.float64], centre, radius: float) -> None:
    """Move every point, in place, along its ray from ``centre`` onto the sphere."""
    points -= centre
    points *= radius / np.linalg.norm(points, axis=1)[:, None]
    points += centre
