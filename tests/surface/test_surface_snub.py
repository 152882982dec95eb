"""The snub step on surfaces in space: the planar scheme on z = 0 under any rotation, the
paper's counts and Euler's formula on closed solids, the projection onto the sphere."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from tests.strategies import jittered_grids
from weavecut import inputs
from weavecut.errors import MeshError
from weavecut.mesh import Mesh
from weavecut.subdivision import snub, subdivide
from weavecut.surface import edge_normals

SOLIDS = ["tetrahedron", "cube", "octahedron", "dodecahedron", "icosahedron", "icosphere:1"]


def placed_in_space(mesh: Mesh, rotation: np.ndarray, shift) -> Mesh:
    return Mesh(np.column_stack([mesh.vertices, np.zeros(mesh.n_vertices)]) @ rotation.T + shift,
                mesh.face_offsets, mesh.face_indices)


@settings(max_examples=25, deadline=None)
@given(mesh=st.one_of(jittered_grids(3), st.sampled_from(
           [inputs.get(n) for n in ("pentagon", "pentagon-flower", "tiling-8-4:2x2")])),
       seed=st.integers(0, 2**32 - 1), chirality=st.sampled_from(snub.CHIRALITIES),
       smooth=st.booleans())
def test_planar_mesh_in_space_gives_the_planar_result_rotated(mesh, seed, chirality, smooth):
    rotation = Rotation.random(random_state=seed).as_matrix()
    shift = np.random.default_rng(seed).uniform(-1, 1, 3)
    flat = subdivide(mesh, 3, chirality=chirality, smooth=smooth)
    space = subdivide(placed_in_space(mesh, rotation, shift), 3, chirality=chirality,
                      smooth=smooth)
    for a, b in zip(flat, space):
        assert b.mesh.dim == 3
        np.testing.assert_array_equal(a.mesh.face_indices, b.mesh.face_indices)
        want = placed_in_space(a.mesh, rotation, shift).vertices
        np.testing.assert_allclose(b.mesh.vertices, want, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", SOLIDS)
def test_counts_follow_eq2_and_euler_on_closed_solids(name):
    hierarchy = subdivide(inputs.get(name), 3)
    for parent, child in zip(hierarchy, hierarchy[1:]):
        p, c = parent.mesh, child.mesh
        want = snub.counts(p.n_vertices, p.topology.n_edges, p.n_faces, p.n_corners)
        assert (c.n_vertices, c.topology.n_edges, c.n_faces, c.n_corners) == want
    for level in hierarchy:
        m = level.mesh
        assert m.n_vertices - m.topology.n_edges + m.n_faces == 2
        assert not m.topology.boundary_edges.any()
        # the step's own topology has the edges a fresh build finds
        rebuilt = Mesh(m.vertices, m.face_offsets, m.face_indices).topology
        np.testing.assert_array_equal(rebuilt.edges, np.unique(m.topology.edges, axis=0))


@pytest.mark.parametrize("name", SOLIDS)
def test_z_triplets_are_the_paper_shape_in_the_bisecting_plane(name):
    mesh = inputs.get(name)
    child = snub.step(mesh, smooth=False).mesh
    e = mesh.topology.edges
    u, w = mesh.vertices[e[:, 0]], mesh.vertices[e[:, 1]]
    z = child.vertices[mesh.n_vertices:mesh.n_vertices + 2 * len(e)].reshape(-1, 2, 3)
    path = np.stack([u, z[:, 0], z[:, 1], w], axis=1)
    steps = np.diff(path, axis=1)
    length = np.linalg.norm(w - u, axis=1)
    np.testing.assert_allclose(np.linalg.norm(steps, axis=2), (length / np.sqrt(7))[:, None] *
                               np.ones(3), rtol=1e-12)  # three edges of |e| / sqrt(7)
    cos = (steps[:, :-1] * steps[:, 1:]).sum(axis=2) / (length[:, None] ** 2 / 7)
    np.testing.assert_allclose(cos, 0.5 * np.ones_like(cos), atol=1e-12)  # 60 deg turns
    # the triplet is planar, in a plane that makes equal angles with the two faces' planes
    plane = np.cross(w - u, z[:, 0] - u)
    plane /= np.linalg.norm(plane, axis=1)[:, None]
    np.testing.assert_allclose((steps * plane[:, None]).sum(axis=2), 0, atol=1e-12)
    p = mesh.vertices[mesh.dense_faces()[:, :3]]  # face normals from three corners (flat faces)
    face_normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    face_normal /= np.linalg.norm(face_normal, axis=1)[:, None]
    he = mesh.topology.edge_half_edges
    left, right = (face_normal[mesh.half_edge_face[he[:, c]]] for c in (0, 1))
    np.testing.assert_allclose(np.einsum("ij,ij->i", plane, left),
                               np.einsum("ij,ij->i", plane, right), atol=1e-12)
    # left chirality: the first Z edge turns towards the face on the left of u -> w
    assert (np.einsum("ij,ij->i", plane, left + right) > 0).all()
    np.testing.assert_allclose(edge_normals(mesh), (left + right) / np.linalg.norm(
        left + right, axis=1)[:, None], atol=1e-12)


@pytest.mark.parametrize("name", ["dodecahedron", "cube", "icosphere:1"])
def test_project_sphere_puts_every_vertex_on_the_circumsphere(name):
    mesh = inputs.get(name)
    mesh = mesh.moved(mesh.vertices * 2.5 + (1, -2, 3))
    levels = subdivide(mesh, 2, project="sphere")
    for level in levels:
        r = np.linalg.norm(level.mesh.vertices - (1, -2, 3), axis=1)
        np.testing.assert_allclose(r, 2.5, rtol=1e-12)
    plain = subdivide(mesh, 2)[-1].mesh
    assert np.linalg.norm(plain.vertices - (1, -2, 3), axis=1).min() < 2.4  # it did move


def test_project_sphere_refuses_a_mesh_off_the_sphere():
    mesh = inputs.get("cube")
    vertices = mesh.vertices.copy()
    vertices[5] *= 1.1  # (a box's corners would still lie on a sphere)
    with pytest.raises(MeshError, match="vertices on a sphere; vertex 5 "):
        snub.step(mesh.moved(vertices), project="sphere")
    with pytest.raises(MeshError, match="needs a surface in space"):
        snub.step(inputs.get("pentagon"), project="sphere")


def test_area_centres_are_planar_only():
    with pytest.raises(MeshError, match="--centre area needs a planar mesh"):
        snub.step(inputs.get("cube"), centre="area")
