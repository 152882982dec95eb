"""Loop: counts and hand-derived stencils, boundary included."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings

from weavecut.subdivision import loop

from .classic_meshes import edge_id, fan, jittered_tri_grids


@settings(max_examples=30, deadline=None)
@given(mesh=jittered_tri_grids())
def test_counts_per_step(mesh):
    m = mesh
    for _ in range(2):
        child = loop.step(m).mesh
        assert (child.n_vertices, child.topology.n_edges, child.n_faces,
                child.n_corners) == loop.counts(m.n_vertices, m.topology.n_edges, m.n_faces,
                                                m.n_corners)
        m = child


def test_stencils_on_a_hexagonal_fan():
    m = fan(6, centre=(0.1, 0.2), radii=[1.0, 1.1, 0.9, 1.0, 1.2, 0.95])
    v = m.vertices
    child = loop.step(m).mesh
    c, rim = v[0], v[1:]
    # inner vertex of valence 6: beta = 1/16
    np.testing.assert_allclose(child.vertices[0], (1 - 6 / 16) * c + rim.sum(axis=0) / 16)
    # outer vertex: 3/4 v + 1/8 of its two rim neighbours
    np.testing.assert_allclose(child.vertices[1], 0.75 * rim[0] + 0.125 * (rim[1] + rim[5]))
    # inner edge (centre, rim 0): 3/8 ends + 1/8 opposite rim vertices
    e = edge_id(m, 0, 1)
    np.testing.assert_allclose(child.vertices[m.n_vertices + e],
                               0.375 * (c + rim[0]) + 0.125 * (rim[1] + rim[5]))
    # outer edge (rim 0, rim 1): its midpoint
    e = edge_id(m, 1, 2)
    np.testing.assert_allclose(child.vertices[m.n_vertices + e], 0.5 * (rim[0] + rim[1]))


def test_valence_three_uses_loops_beta():
    m = fan(3, centre=(0.05, 0.0))
    beta = (5 / 8 - (3 / 8 + np.cos(2 * np.pi / 3) / 4) ** 2) / 3
    expected = (1 - 3 * beta) * m.vertices[0] + beta * m.vertices[1:].sum(axis=0)
    np.testing.assert_allclose(loop.step(m).mesh.vertices[0], expected)
