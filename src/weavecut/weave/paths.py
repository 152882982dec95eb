"""Ordering states along paths and cycles with arrays only (pointer jumping).

A successor map ``succ`` (-1 at path ends) splits its states into simple paths and cycles.
``rank_paths`` gives every state its path's first state and its distance from it, in
O(n log n) work with no Python loop over states; every cycle is cut before its smallest state.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray


def rank_paths(succ: NDArray[np.integer]) -> tuple[NDArray[np.int64], NDArray[np.int64],
                                                   NDArray[np.bool_]]:
    """(root, rank, on_cycle) of every state of an injective successor map.

    Examples
    --------
    >>> root, rank, cyc = rank_paths(np.array([1, 2, -1, 4, 3]))
    >>> root.tolist(), rank.tolist(), cyc.tolist()
    ([0, 0, 0, 3, 3], [0, 1, 2, 0, 1], [False, False, False, True, True])
    """
    succ = np.asarray(succ, dtype=np.int64)
    n = len(succ)
    h = np.arange(n, dtype=np.int64)
    has = succ >= 0
    if np.bincount(succ[has], minlength=n).max(initial=0) > 1:
        raise ValueError("successor map is not injective")
    pred = np.full(n, -1, dtype=np.int64)
    pred[succ[has]] = h[has]
    rounds = max(1, int(np.ceil(np.log2(max(n, 2)))) + 1)
    p = np.where(pred >= 0, pred, h)
    for _ in range(rounds):
        p = p[p]
    on_cycle = pred[p] >= 0
    low, s = h.copy(), np.where(on_cycle, succ, h)
    for _ in range(rounds):
        low = np.minimum(low, low[s])
        s = s[s]
    pred = np.where(on_cycle & (low == h), -1, pred)
    p = np.where(pred >= 0, pred, h)
    rank = (pred >= 0).astype(np.int64)
    for _ in range(rounds):
        rank = rank + rank[p]
        p = p[p]
    return p, rank, on_cycle
