"""Validation of input meshes: orientation, zero area, convexity, overlaps."""

from __future__ import annotations

import numpy as np
import pytest

from tests import meshes
from weavecut.errors import MeshError
from weavecut.mesh import Mesh, signed_areas
from weavecut.validation import validate


def test_clockwise_mesh_is_reoriented():
    mesh = meshes.two_squares().reversed()
    assert (signed_areas(mesh) < 0).all()
    fixed = validate(mesh)
    assert (signed_areas(fixed) > 0).all()


def test_mixed_orientation_is_an_error():
    v = [(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (0, 1)]
    mesh = Mesh.from_faces(v, [[0, 1, 4, 5], [1, 4, 3, 2]])
    with pytest.raises(MeshError, match="face 1 is clockwise"):
        validate(mesh)


def test_zero_area_face():
    mesh = Mesh.from_faces([(0, 0), (1, 0), (2, 0)], [[0, 1, 2]])
    with pytest.raises(MeshError, match="face 0 has zero area"):
        validate(mesh)


def test_nonconvex_face_is_an_error_unless_allowed():
    v = [(0, 0), (2, 0), (2, 2), (1, 0.5), (0, 2)]
    mesh = Mesh.from_faces(v, [[0, 1, 2, 3, 4]])
    with pytest.raises(MeshError, match="face 0 is not convex at vertex 3"):
        validate(mesh)
    assert validate(mesh, allow_nonconvex=True).n_faces == 1


def test_overlapping_faces():
    v = [(0, 0), (2, 0), (2, 2), (0, 2), (1, 1), (3, 1), (3, 3), (1, 3)]
    mesh = Mesh.from_faces(v, [[0, 1, 2, 3], [4, 5, 6, 7]])
    with pytest.raises(MeshError, match="overlap"):
        validate(mesh)


def test_self_intersecting_face():
    v = [(0, 0), (2, 2), (2, 0), (0, 3)]
    mesh = Mesh.from_faces(v, [[0, 1, 2, 3]])  # a bow-tie quad with positive area
    with pytest.raises(MeshError, match="face 0 intersects itself"):
        validate(mesh, allow_nonconvex=True)


def test_empty_mesh():
    with pytest.raises(MeshError, match="no faces"):
        validate(Mesh(np.zeros((0, 2)), [0], []))


def test_valid_meshes_pass_unchanged():
    mesh = meshes.mixed()
    assert validate(mesh) is mesh


def test_face_nested_inside_another_and_folded_fans():
    outer = [(0, 0), (4, 0), (4, 4), (0, 4)]
    inner = [(1, 1), (2, 1), (2, 2), (1, 2)]
    mesh = Mesh.from_faces(outer + inner, [[0, 1, 2, 3], [4, 5, 6, 7]])
    with pytest.raises(MeshError, match="lies inside face 0"):
        validate(mesh)
    # six triangles around a vertex that turn around it twice (each CCW, no edge shared twice)
    t = np.linspace(0, 4 * np.pi, 7)[:-1] + 0.1
    ring = [(float(np.cos(a)), float(np.sin(a))) for a in t]
    fan = Mesh.from_faces([(0.0, 0.0)] + ring, [[0, 1 + i, 1 + (i + 1) % 6] for i in range(6)])
    with pytest.raises(MeshError, match="overlap"):
        validate(fan)


def test_huge_coordinates_are_refused():
    mesh = Mesh.from_faces([(0, 0), (1e300, 0), (0, 1)], [[0, 1, 2]])
    with pytest.raises(MeshError, match="beyond"):
        validate(mesh)
