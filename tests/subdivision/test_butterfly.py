"""Modified butterfly: interpolation, the 8-point stencil, extraordinary and boundary rules."""

from __future__ import annotations

import numpy as np
import pytest

from weavecut.subdivision import butterfly

from .classic_meshes import edge_id, fan, tri_grid


def test_old_vertices_stay_and_counts():
    m = tri_grid(3, 2, jitter=0.1)
    child = butterfly.step(m).mesh
    np.testing.assert_array_equal(child.vertices[:m.n_vertices], m.vertices)
    assert child.n_faces == 4 * m.n_faces


def test_regular_eight_point_stencil():
    m = tri_grid(4, 4, jitter=0.15, seed=3)
    p = lambda i, j: m.vertices[j * 5 + i]  # noqa: E731
    e = edge_id(m, 2 * 5 + 2, 2 * 5 + 3)     # (2, 2) - (3, 2), both ends inner, valence 6
    expected = (0.5 * (p(2, 2) + p(3, 2)) + 0.125 * (p(3, 3) + p(2, 1))
                - 0.0625 * (p(4, 3) + p(2, 3) + p(1, 1) + p(3, 1)))
    np.testing.assert_allclose(butterfly.step(m).mesh.vertices[m.n_vertices + e], expected)


@pytest.mark.parametrize("k", [3, 4, 5, 7])
def test_extraordinary_ring_stencil(k):
    m = fan(k, centre=(0.1, -0.05), radii=1 + 0.1 * np.arange(k))
    s = butterfly.ring_weights(k)
    rim = m.vertices[1:]
    e = edge_id(m, 0, 1)
    expected = 0.75 * m.vertices[0] + (s[:, None] * rim).sum(axis=0)
    np.testing.assert_allclose(butterfly.step(m).mesh.vertices[m.n_vertices + e], expected)


def test_boundary_four_point_rule():
    m = fan(5, radii=[1.0, 1.2, 0.9, 1.1, 1.0])
    rim = m.vertices[1:]
    e = edge_id(m, 2, 3)                     # rim 1 - rim 2, boundary runs rim 0, 1, 2, 3
    expected = (9 * (rim[1] + rim[2]) - rim[0] - rim[3]) / 16
    np.testing.assert_allclose(butterfly.step(m).mesh.vertices[m.n_vertices + e], expected)


def test_weights_sum_to_one():
    for k in range(3, 12):
        assert butterfly.ring_weights(k).sum() == pytest.approx(0.25)
