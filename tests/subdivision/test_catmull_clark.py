"""Catmull-Clark: counts, face/edge/vertex points, boundary, mixed input."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings

from weavecut.mesh import vertex_degrees
from weavecut.subdivision import catmull_clark as cc

from .classic_meshes import any_meshes, edge_id, mixed, quad_grid


@settings(max_examples=30, deadline=None)
@given(mesh=any_meshes())
def test_counts_and_all_quads(mesh):
    c = cc.step(mesh).mesh
    assert (c.n_vertices, c.topology.n_edges, c.n_faces, c.n_corners) == cc.counts(
        mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces, mesh.n_corners)
    assert c.face_degree == 4


def test_points_on_a_two_by_two_grid():
    m = quad_grid(2, 2, jitter=0.1, seed=1)
    v = m.vertices
    child = cc.step(m).mesh
    n_v, n_e = m.n_vertices, m.topology.n_edges
    faces = m.faces()
    fp = np.array([v[f].mean(axis=0) for f in faces])
    np.testing.assert_allclose(child.vertices[n_v + n_e:], fp)
    # inner edge (centre 4, vertex 5) between faces 1 (right bottom) and 3 (right top)
    e = edge_id(m, 4, 5)
    np.testing.assert_allclose(child.vertices[n_v + e], (v[4] + v[5] + fp[1] + fp[3]) / 4)
    # outer edge: midpoint
    e = edge_id(m, 0, 1)
    np.testing.assert_allclose(child.vertices[n_v + e], (v[0] + v[1]) / 2)
    # inner vertex 4, valence 4: (Q + 2R + S) / 4
    q = fp.mean(axis=0)
    r = np.mean([(v[4] + v[j]) / 2 for j in (1, 3, 5, 7)], axis=0)
    np.testing.assert_allclose(child.vertices[4], (q + 2 * r + v[4]) / 4)
    # outer vertex 1: 3/4 v + 1/8 (outer neighbours 0, 2)
    np.testing.assert_allclose(child.vertices[1], 0.75 * v[1] + 0.125 * (v[0] + v[2]))


def test_non_quad_faces_leave_irregular_vertices():
    m = mixed()
    level = cc.step(m)
    deg = vertex_degrees(level.mesh)
    face_points = m.n_vertices + m.topology.n_edges + np.arange(m.n_faces)
    np.testing.assert_array_equal(deg[face_points], m.face_sizes)
    level2 = cc.step(level.mesh)     # still there one level down (a face point's child)
    assert sorted(vertex_degrees(level2.mesh)[face_points].tolist()) == [3, 3, 4, 4]
