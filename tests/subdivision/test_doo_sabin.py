"""Doo-Sabin: counts, corner weights, kept non-quad faces."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings

from weavecut.subdivision import doo_sabin

from .classic_meshes import any_meshes, mixed, quad_grid


@settings(max_examples=30, deadline=None)
@given(mesh=any_meshes())
def test_counts(mesh):
    topo = mesh.topology
    inner_v = np.ones(mesh.n_vertices, bool)
    inner_v[topo.edges[topo.boundary_edges].ravel()] = False
    c = doo_sabin.step(mesh).mesh
    assert (c.n_vertices, c.topology.n_edges, c.n_faces) == doo_sabin.exact_counts(
        mesh.n_faces, mesh.n_corners, int((~topo.boundary_edges).sum()), int(inner_v.sum()))


def test_quad_and_triangle_weights():
    q = quad_grid(1, 1, jitter=0.1)
    v = q.vertices[q.face_indices]
    np.testing.assert_allclose(doo_sabin.step(q).mesh.vertices[0],
                               (9 * v[0] + 3 * v[1] + v[2] + 3 * v[3]) / 16)
    m = mixed()
    t = m.face_indices[8:11]                          # triangle (3, 4, 6), corner 8
    np.testing.assert_allclose(doo_sabin.step(m).mesh.vertices[8],
                               (4 * m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 6)


def test_non_quad_faces_are_kept():
    m = mixed()
    c = doo_sabin.step(doo_sabin.step(m).mesh).mesh
    np.testing.assert_array_equal(c.face_sizes[:m.n_faces], m.face_sizes)
