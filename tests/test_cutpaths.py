"""Cut path ordering: every path is cut once (maybe reversed), no reversal of a run of paths
shortens the travel any more (2-opt's local optimum), and the travel of one path is the way to
its start."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout.cutpaths import (_two_opt, are_closed, is_closed, order_paths,
                                      travel_length)
from weavecut.layout.cutpaths import FAR, EdgeGraph, trails
from weavecut.numeric import snap


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
@given(st.lists(st.tuples(st.integers(0, 5), st.sampled_from([0.0, 1e-9, 1e-6, 1e-3, 1.0]),
                          st.floats(-1e6, 1e6)), max_size=8))
def test_paths_closed_at_once_as_one_by_one(specs):
    # loops that end where they start, a hair away, or not at all, near and far from 0
    paths = []
    for n, gap, at in specs:  # (n = 0: a path without points)
        p = np.full((n, 2), at) + np.arange(n)[:, None] * [1.0, 2.0]
        if n:
            p[-1] = p[0] + gap
        paths.append(p)
    assert are_closed(paths).tolist() == [is_closed(p) for p in paths]
    assert are_closed(paths, 2).tolist() == [len(p) > 1 and bool(np.allclose(p[0], p[-1]))
                                             for p in paths]


def two_opt_by_the_book(paths, start, passes, window):
    """2-opt as first written: every run's gain measured anew from the paths' ends."""
    n = len(paths)
    if n < 3:
        return paths
    s, e = np.array([p[0] for p in paths]), np.array([p[-1] for p in paths])
    order, flipped = np.arange(n), np.zeros(n, dtype=bool)
    for _ in range(passes):
        improved = False
        for i in range(n - 1):
            prev = start if i == 0 else e[i - 1]
            j = np.arange(i + 1, min(n, i + 1 + window))
            nxt = np.vstack([s[i + 1:], [np.nan, np.nan]])[1:len(j) + 1]
            old = np.hypot(*(prev - s[i])) + np.where(j < n - 1, np.hypot(*(e[j] - nxt).T), 0.0)
            new = np.hypot(*(prev - e[j]).T) + np.where(j < n - 1, np.hypot(*(s[i] - nxt).T), 0.0)
            gain = snap(old - new)
            k = int(np.argmax(gain))
            if gain[k] > 0:
                run = slice(i, int(j[k]) + 1)
                order[run] = order[run][::-1].copy()
                flipped[run] = ~flipped[run][::-1]
                s[run], e[run] = e[run][::-1].copy(), s[run][::-1].copy()
                improved = True
        if not improved:
            break
    return [paths[o][::-1] if f else paths[o] for o, f in zip(order.tolist(), flipped.tolist())]


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 60), st.integers(1, 70), st.integers(0, 2**16), st.booleans())
def test_two_opt_takes_the_runs_the_book_takes(n, window, seed, grid):
    # the same runs reversed in the same order, to the last bit (grid: ties and equal gains)
    rng = np.random.default_rng(seed)
    size = (lambda: rng.integers(0, 6, size=(int(rng.integers(1, 4)), 2)).astype(float)) if grid \
        else (lambda: rng.uniform(0, 100, size=(int(rng.integers(1, 4)), 2)))
    paths = [size() for _ in range(n)]
    start = rng.uniform(0, 100, 2)
    got = _two_opt(paths, start, 30, window)
    want = two_opt_by_the_book(paths, start, 30, window)
    assert len(got) == len(want) and all(np.array_equal(a, b) for a, b in zip(got, want))


def order_by_the_book(paths, start=(0.0, 0.0)):
    """order_paths as first written: the nearest head and the nearest tail weighed apart."""
    here = np.asarray(start, dtype=float)
    heads, tails = np.array([p[0] for p in paths]), np.array([p[-1] for p in paths])
    closed = np.array([is_closed(p) for p in paths])
    chosen, alive = [], np.ones(len(paths), dtype=bool)
    for _ in paths:
        d_head = np.where(alive, snap(np.hypot(*(heads - here).T)), FAR)
        d_tail = np.where(alive & ~closed, snap(np.hypot(*(tails - here).T)), FAR)
        i_h, i_t = int(np.argmin(d_head)), int(np.argmin(d_tail))
        i, path = (i_t, paths[i_t][::-1]) if d_tail[i_t] < d_head[i_h] else (i_h, paths[i_h])
        if closed[i]:
            j = int(np.argmin(snap(np.hypot(*(path[:-1] - here).T))))
            path = np.concatenate([path[j:-1], path[:j + 1]])
        alive[i] = False
        chosen.append(path)
        here = path[-1]
    return two_opt_by_the_book(chosen, np.asarray(start, dtype=float), 30, 500)


@settings(max_examples=100, deadline=None)
@given(st.integers(1, 40), st.integers(0, 2**16))
def test_paths_ordered_as_the_book_orders_them(n, seed):
    # on a coarse grid: ties between heads, tails and loops' corners everywhere
    rng = np.random.default_rng(seed)
    paths = []
    for _ in range(n):
        p = rng.integers(0, 5, size=(int(rng.integers(1, 5)), 2)).astype(float)
        if rng.random() < 0.4:
            p = np.vstack([p, p[:1]])  # a loop
        paths.append(p)
    got, end = order_paths(paths, (1.0, 2.0))
    want = order_by_the_book(paths, (1.0, 2.0))
    assert len(got) == len(want) and all(np.array_equal(a, b) for a, b in zip(got, want))
    assert end == tuple(want[-1][-1])


@settings(max_examples=50, deadline=None)
@given(st.integers(2, 12), st.integers(0, 2**16))
def test_trails_cover_every_edge_once_even_at_a_corner_that_is_not_finite(n, seed):
    """A walk takes an unused edge at every step, whatever the corners' coordinates: a NaN
    corner (a level too small for floating point, refused before layout) once made the
    straightest-edge choice pick none and the walk loop forever. Each edge of a random graph
    is walked exactly once."""
    rng = np.random.default_rng(seed)
    points = rng.random((n, 2))
    points[rng.integers(n)] = np.nan
    pairs = {tuple(sorted(p)) for p in rng.integers(0, n, (3 * n, 2)).tolist() if p[0] != p[1]}
    edges = np.array(sorted(pairs), dtype=np.int64).reshape(-1, 2)
    walks = trails(EdgeGraph(points, edges, np.ones(len(edges), np.int64)))
    index = {tuple(p): i for i, p in enumerate(points.tolist()) if np.isfinite(p).all()}
    walked = []
    for w in walks:
        ids = [index.get(tuple(p), -1) for p in w.tolist()]  # -1: the NaN corner
        nan_id = next(i for i, p in enumerate(points.tolist()) if not np.isfinite(p).all())
        ids = [nan_id if i < 0 else i for i in ids]
        walked += [tuple(sorted(e)) for e in zip(ids[:-1], ids[1:])]
    assert sorted(walked) == sorted(map(tuple, edges.tolist()))
