"""Cut path ordering: every path is cut once (maybe reversed), no reversal of a run of paths
shortens the travel any more (2-opt's local optimum), and the travel of one path is the way to
its start."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout.cutpaths import are_closed, is_closed, order_paths, travel_length


def test_travel_of_one_path_is_the_way_to_its_start():
    assert travel_length([np.array([[3.0, 4.0], [9.0, 9.0]])]) == 5.0


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 12), st.integers(0, 2**16))
def test_ordering_keeps_every_path_and_no_reversal_helps(n, seed):
    rng = np.random.default_rng(seed)
    paths = [rng.uniform(0, 100, size=(int(rng.integers(2, 5)), 2)) for _ in range(n)]
    ordered, end = order_paths(paths)
    key = sorted(tuple(np.round(p, 9).ravel()) for p in paths)
    seen = sorted(min(tuple(np.round(p, 9).ravel()), tuple(np.round(p[::-1], 9).ravel()))
                  for p in ordered)
    assert seen == sorted(min(k, tuple(np.asarray(k).reshape(-1, 2)[::-1].ravel()))
                          for k in key)
    travel = travel_length(ordered)
    for i in range(len(ordered)):  # reverse the run i..j, each path turned round too
        for j in range(i + 1, len(ordered)):
            turned = ordered[:i] + [p[::-1] for p in ordered[i:j + 1][::-1]] + ordered[j + 1:]
            assert travel_length(turned) >= travel - 1e-9
    assert np.allclose(end, ordered[-1][-1])


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(st.integers(1, 5), st.sampled_from([0.0, 1e-9, 1e-6, 1e-3, 1.0]),
                          st.floats(-1e6, 1e6)), max_size=8))
def test_paths_closed_at_once_as_one_by_one(specs):
    # loops that end where they start, a hair away, or not at all, near and far from 0
    paths = []
    for n, gap, at in specs:
        p = np.full((n, 2), at) + np.arange(n)[:, None] * [1.0, 2.0]
        p[-1] = p[0] + gap
        paths.append(p)
    assert are_closed(paths).tolist() == [is_closed(p) for p in paths]
