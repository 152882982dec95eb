"""pieces._snap (shapely's STRtree) against the cKDTree + csgraph version it replaces."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from weavecut.puzzle.pieces import _snap


def _snap_scipy(points, tol):
    pairs = cKDTree(points).query_pairs(tol, output_type="ndarray")
    if not len(pairs):
        return points
    n = len(points)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    label = connected_components(graph, directed=False)[1]
    first = np.full(label.max() + 1, n, dtype=np.int64)
    np.minimum.at(first, label, np.arange(n))
    return points[first[label]]


@st.composite
def near_points(draw):
    """Points, and copies of earlier points moved by under 0.9 tol (merged, in chains) or
    over 1.1 tol (kept apart), shuffled; no distance near tol itself."""
    rng = np.random.default_rng(draw(st.integers(0, 2 ** 32 - 1)))
    tol = draw(st.sampled_from([1e-6, 1e-3, 0.5]))
    points = rng.uniform(-50, 50, (draw(st.integers(1, 40)), 2))
    for _ in range(draw(st.integers(0, 60))):
        step = rng.normal(size=2)
        reach = rng.choice([rng.uniform(0.0, 0.9), rng.uniform(1.1, 3.0)]) * tol
        points = np.vstack([points, points[rng.integers(len(points))]
                            + step / np.hypot(*step) * reach])
    return points[rng.permutation(len(points))], tol


@given(near_points())
def test_the_same_clusters_and_firsts_as_ckdtree(case):
    points, tol = case
    assert _snap(points, tol).tolist() == _snap_scipy(points, tol).tolist()


def test_pairs_at_exactly_tol_merge():
    points = np.array([[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [3.0, 0.0]])
    assert _snap(points, 0.5).tolist() == [[0.0, 0.0]] * 3 + [[3.0, 0.0]]
