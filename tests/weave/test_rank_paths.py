"""Pointer jumping (``weave.paths.rank_paths``) against a walk state by state: every state's
path start (a cycle starts at its smallest state), its distance from there, and whether it lies
on a cycle, on random successor maps made of paths and cycles of any length."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from weavecut.weave.paths import rank_paths


@st.composite
def successor_maps(draw):
    """An injective successor map: a random order of n states cut into runs, each run a
    path (last state -> -1) or a cycle (last state -> first)."""
    n = draw(st.integers(0, 70))
    order = draw(st.permutations(range(n)))
    succ = np.full(n, -1, dtype=np.int64)
    start = 0
    while start < n:
        size = draw(st.integers(1, n - start))
        run = order[start:start + size]
        succ[run[:-1]] = run[1:]
        if draw(st.booleans()):
            succ[run[-1]] = run[0]
        start += size
    return succ


def walked(succ):
    n = len(succ)
    pred = {int(s): h for h, s in enumerate(succ.tolist()) if s >= 0}
    root, rank, cycle = [0] * n, [0] * n, [False] * n
    for h in range(n):
        seen, x = [h], h
        while x in pred and pred[x] != h:  # walk back to the path's start or round the cycle
            x = pred[x]
            seen.append(x)
        if x in pred:  # back at h: a cycle, which starts at its smallest state
            cycle[h] = True
            start = min(seen)
            root[h], rank[h] = start, seen.index(start)  # seen runs back from h to start
        else:
            root[h], rank[h] = x, len(seen) - 1
    return root, rank, cycle


@given(successor_maps())
def test_ranks_equal_a_walk(succ):
    root, rank, cycle = rank_paths(succ)
    assert rank.dtype == np.int64 and root.dtype == np.int64
    assert (root.tolist(), rank.tolist(), cycle.tolist()) == walked(succ)


def test_one_long_path_and_one_long_cycle():
    """1000 states on one path in reverse order, 1000 on a cycle: log2 rounds must reach."""
    path = np.r_[-1, np.arange(999)]          # 999 -> 998 -> ... -> 0
    cycle = np.r_[np.arange(1001, 2000), 1000]
    root, rank, on = rank_paths(np.r_[path, cycle])
    assert (root[:1000] == 999).all() and rank[:1000].tolist() == list(range(999, -1, -1))
    assert (root[1000:] == 1000).all() and rank[1000:].tolist() == list(range(1000))
    assert not on[:1000].any() and on[1000:].all()


def test_a_map_that_is_not_injective_is_refused():
    with pytest.raises(ValueError, match="^successor map is not injective$"):
        rank_paths(np.array([2, 2, -1]))
