"""sqrt(3): counts, centres, relaxation, flipped edges."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings

from weavecut.mesh_geometry import face_centroids
from weavecut.subdivision import sqrt3

from .classic_meshes import fan, jittered_tri_grids


@settings(max_examples=30, deadline=None)
@given(mesh=jittered_tri_grids())
def test_counts_and_nine_triangles_after_two_steps(mesh):
    level = sqrt3.step(mesh)
    c = level.mesh
    assert (c.n_vertices, c.topology.n_edges, c.n_faces, c.n_corners) == sqrt3.counts(
        mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces, mesh.n_corners)
    assert sqrt3.step(c).mesh.n_faces == 9 * mesh.n_faces
    np.testing.assert_allclose(c.vertices[mesh.n_vertices:], face_centroids(mesh))
    # a flipped edge joins the centres of the two faces of its parent edge
    flipped = c.topology.edges[level.edge_part == sqrt3.FLIPPED]
    assert (flipped >= mesh.n_vertices).all()
    assert (level.edge_part == sqrt3.FLIPPED).sum() == (~mesh.topology.boundary_edges).sum()


def test_relaxation_of_an_inner_vertex():
    m = fan(6, centre=(0.2, 0.1), radii=[1.0, 1.1, 0.9, 1.0, 1.2, 0.95])
    child = sqrt3.step(m).mesh
    alpha = (4 - 2 * np.cos(2 * np.pi / 6)) / 9          # = 1/3
    expected = (1 - alpha) * m.vertices[0] + alpha * m.vertices[1:].mean(axis=0)
    np.testing.assert_allclose(child.vertices[0], expected)
    np.testing.assert_array_equal(child.vertices[1:7], m.vertices[1:])  # outer vertices stay
