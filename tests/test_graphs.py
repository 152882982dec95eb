"""graphs.components against scipy's connected_components (the oracle it replaces)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from weavecut.graphs import components


@st.composite
def graphs(draw):
    n = draw(st.integers(1, 60))
    edges = draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=90))
    a, b = (np.array([e[k] for e in edges], dtype=np.int64) for k in (0, 1))
    return n, a, b


@given(graphs())
def test_parts_and_their_numbers_are_scipys(graph):
    n, a, b = graph
    graph_matrix = coo_matrix((np.ones(len(a)), (a, b)), shape=(n, n))
    count, labels = connected_components(graph_matrix, directed=False)
    mine_count, mine = components(n, a, b)
    assert mine_count == count and mine.tolist() == labels.tolist()


def test_long_paths_and_stars_join_in_few_rounds():
    n = 100_000
    order = np.random.default_rng(1).permutation(n)  # one path through every node, shuffled
    count, labels = components(n, order[:-1], order[1:])
    assert count == 1 and not labels.any()
    count, labels = components(n + 5, np.zeros(n - 1, dtype=np.int64), np.arange(1, n))
    assert count == 6 and labels[:n].max() == 0 and labels[n:].tolist() == [1, 2, 3, 4, 5]
