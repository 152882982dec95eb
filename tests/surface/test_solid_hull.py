"""inputs._convex_solid (a hull of its own) against the scipy ConvexHull version it replaces:
the same Mesh, bit for bit, for every solid and for random convex point sets."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial import ConvexHull

from weavecut import inputs
from weavecut.mesh import Mesh
from weavecut.numeric import dot


def _convex_solid_scipy(points) -> Mesh:
    points = np.asarray(points, dtype=np.float64)
    points /= np.linalg.norm(points, axis=1)[:, None]
    hull = ConvexHull(points)
    planes, face = np.unique(np.round(hull.equations, 9), axis=0, return_inverse=True)
    pairs = np.unique(np.column_stack([np.repeat(face.reshape(-1), 3),
                                       hull.simplices.reshape(-1)]), axis=0)
    f, v = pairs.T
    normal = planes[f, :3]
    starts = np.flatnonzero(np.r_[True, f[1:] != f[:-1]])
    centre = (np.add.reduceat(points[v], starts)[f] / np.bincount(f)[f][:, None])
    ref = points[v][starts][f] - centre
    angle = np.arctan2(dot(np.cross(ref, points[v] - centre), normal),
                       dot(ref, points[v] - centre))
    sizes = np.bincount(f)
    return Mesh(points, np.concatenate([[0], np.cumsum(sizes)]), v[np.lexsort((angle, f))])


def _same(a: Mesh, b: Mesh):
    assert a.vertices.tobytes() == b.vertices.tobytes()
    assert np.asarray(a.face_offsets).tolist() == np.asarray(b.face_offsets).tolist()
    assert np.asarray(a.face_indices).tolist() == np.asarray(b.face_indices).tolist()


@pytest.mark.parametrize("name", ["tetrahedron", "cube", "octahedron", "dodecahedron",
                                  "icosahedron"])
def test_every_solid_is_the_scipy_hulls_mesh(name, monkeypatch):
    corners = []
    build = inputs._convex_solid
    monkeypatch.setattr(inputs, "_convex_solid", lambda p: corners.append(p) or build(p))
    _same(inputs.get(name), _convex_solid_scipy(corners[0]))


@given(st.integers(0, 2 ** 32 - 1), st.integers(4, 30))
def test_random_convex_point_sets_give_the_scipy_hulls_mesh(seed, n):
    """Points in general position (every face a triangle), all corners once on the sphere."""
    points = np.random.default_rng(seed).normal(size=(n, 3))
    _same(inputs._convex_solid(points.copy()), _convex_solid_scipy(points))


@given(st.integers(0, 2 ** 32 - 1), st.sampled_from(["cube", "dodecahedron"]))
def test_turned_solids_merge_the_same_coplanar_faces(seed, name):
    """A cube or dodecahedron turned at random: faces of 4 and 5 corners, from many triples."""
    q = np.random.default_rng(seed).normal(size=4)
    w, x, y, z = q / np.sqrt(dot(q, q))
    turn = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    points = dot(inputs.get(name).vertices[:, None, :], turn[None])
    _same(inputs._convex_solid(points.copy()), _convex_solid_scipy(points))
