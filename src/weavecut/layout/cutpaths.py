"""Cut paths: shared edges cut once, joined into long trails, ordered to shorten head travel.

``shared_edges`` turns polygon outlines into a graph (one vertex per distinct corner, one edge
per distinct segment, with how many outlines use it). ``trails`` covers that graph with as few
walks as a greedy pass finds: walks start at odd-degree vertices (each then ends at another),
and at every junction continue along the straightest unused edge, so a walk follows the long
zig-zag lines of the tiling instead of stopping at every corner. ``order_paths`` puts paths in
a nearest-neighbour order, entering each at whichever end (or, for a closed loop, whichever
corner) is nearer, then improves the order with 2-opt moves (reversing a run of paths).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..numeric import snap

FAR = np.iinfo(np.int64).max  # no path left there


@dataclass(frozen=True)
class EdgeGraph:
    """Distinct corners and segments of a set of outlines.

    points : (V, 2) mm;  edges : (E, 2) int64 with u < w;  uses : (E,) outlines per segment
    """

    points: NDArray[np.float64]
    edges: NDArray[np.int64]
    uses: NDArray[np.int64]


def shared_edges(coords: NDArray[np.float64], ring_offsets: NDArray[np.int64],
                 decimals: int = 6) -> EdgeGraph:
    """The segments of closed rings, each once (corners equal to ``decimals`` mm merge)."""
    key = np.round(coords, decimals) + 0.0
    points, vid = np.unique(key, axis=0, return_inverse=True)
    vid = vid.reshape(-1)
    nxt = np.arange(1, len(coords) + 1)
    nxt[ring_offsets[1:] - 1] = ring_offsets[:-1]
    u, w = vid, vid[nxt]
    ok = u != w
    pair = np.column_stack([np.minimum(u, w), np.maximum(u, w)])[ok].astype(np.int64)
    edges, uses = np.unique(pair, axis=0, return_counts=True)
    return EdgeGraph(points, edges, uses)


def trails(graph: EdgeGraph, select: NDArray[np.bool_] | None = None) -> list[NDArray]:
    """Walks covering every selected edge exactly once, as (n, 2) point arrays."""
    edges = graph.edges if select is None else graph.edges[select]
    pts = graph.points
    n_v = len(pts)
    if not len(edges):
        return []
    # adjacency in CSR form: for vertex v, half-edges adj[start[v]:start[v+1]]
    ends = np.concatenate([edges[:, 0], edges[:, 1]])
    other = np.concatenate([edges[:, 1], edges[:, 0]])
    eid = np.concatenate([np.arange(len(edges))] * 2)
    order = np.lexsort((other, ends))
    start = np.searchsorted(ends[order], np.arange(n_v + 1))
    adj_other, adj_edge = other[order].tolist(), eid[order].tolist()
    start = start.tolist()
    degree = np.diff(np.asarray(start))
    used = [False] * len(edges)
    remaining = degree.copy().tolist()
    px, py = pts[:, 0].tolist(), pts[:, 1].tolist()
    # odd vertices first, in a stable order (left to right, bottom to top), then the rest
    seeds = np.lexsort((pts[:, 1], pts[:, 0], degree % 2 == 0)).tolist()
    out: list[NDArray] = []
    for seed in seeds:  # a graph walk: no array form
        while remaining[seed]:
            walk = [seed]
            v, dx, dy = seed, 0.0, 0.0
            while remaining[v]:
                best, best_cos = -1, -3.0
                for k in range(start[v], start[v + 1]):
                    e = adj_edge[k]
                    if used[e]:
                        continue
                    w = adj_other[k]
                    ex, ey = px[w] - px[v], py[w] - py[v]
                    norm = (ex * ex + ey * ey) ** 0.5 or 1.0
                    c = (ex * dx + ey * dy) / norm
                    if best < 0 or c > best_cos:  # (a NaN corner still takes an edge)
                        best, best_cos = k, c
                e, w = adj_edge[best], adj_other[best]
                used[e] = True
                remaining[v] -= 1
                remaining[w] -= 1
                ex, ey = px[w] - px[v], py[w] - py[v]
                norm = (ex * ex + ey * ey) ** 0.5 or 1.0
                dx, dy = ex / norm, ey / norm
                walk.append(w)
                v = w
            out.append(pts[walk])
    return out


def path_length(paths: list[NDArray]) -> float:
    """Total length of polylines (mm)."""
    return float(sum(np.linalg.norm(np.diff(p, axis=0), axis=1).sum() for p in paths))


def is_closed(path: NDArray) -> bool:
    return len(path) > 2 and bool(np.allclose(path[0], path[-1]))


def are_closed(paths: list[NDArray], fewest: int = 3) -> NDArray[np.bool_]:
    """For every path at once, whether it has at least ``fewest`` points and ends where it
    starts (``is_closed`` by default; ``allclose`` is all of ``isclose``)."""
    if not paths:
        return np.zeros(0, dtype=bool)
    ends = np.array([(p[0], p[-1]) if len(p) else np.full((2, 2), np.nan) for p in paths],
                    dtype=float)
    return (np.array([len(p) for p in paths]) >= fewest) & np.isclose(
        ends[:, 0], ends[:, 1]).all(axis=1)


TWO_OPT_WINDOW = 500  # longest run of paths 2-opt reverses


def order_paths(paths: list[NDArray], start=(0.0, 0.0), passes: int = 30
                ) -> tuple[list[NDArray], tuple[float, float]]:
    """Paths reordered (and reversed or rotated) to shorten the travel between them.

    Returns the ordered paths and the point where the last one ends."""
    if not paths:
        return [], tuple(start)
    here = np.asarray(start, dtype=float)
    n = len(paths)
    ends = np.array([p[0] for p in paths] + [p[-1] for p in paths])  # heads, then tails
    closed = are_closed(paths)
    usable = np.concatenate([np.ones(n, dtype=bool), ~closed])  # a loop is entered at its head
    chosen: list[NDArray] = []
    for _ in range(n):  # greedy nearest neighbour, one path per step
        d = np.where(usable, snap(_hypot(ends - here)), FAR)
        k = int(np.argmin(d))  # the nearest end; ties: a head first, then the first path
        i, path = (k, paths[k]) if k < n else (k - n, paths[k - n][::-1])
        if closed[i]:  # enter a loop at its nearest corner
            j = int(np.argmin(snap(np.hypot(*(path[:-1] - here).T))))
            path = np.concatenate([path[j:-1], path[:j + 1]])
        usable[[i, n + i]] = False
        chosen.append(path)
        here = path[-1]
    chosen = _two_opt(chosen, np.asarray(start, dtype=float), passes)
    return chosen, tuple(float(c) for c in chosen[-1][-1])


def _two_opt(paths: list[NDArray], start: NDArray, passes: int,
             window: int = TWO_OPT_WINDOW) -> list[NDArray]:
    """Reverse runs of paths (each path reversed too) while that shortens the travel; runs are
    at most ``window`` paths long (every run on a sheet of fewer paths), so a pass over a
    large sheet costs n x window instead of n**2. The way from each path to the next
    (``link``) is kept, and only the links a reversal changes are measured again."""
    n = len(paths)
    if n < 3:
        return paths
    ends = np.full((2, n + 1, 2), np.nan)  # where each path starts and ends, in travel order
    ends[0, :n] = [p[0] for p in paths]
    ends[1, :n] = [p[-1] for p in paths]
    s, e = ends[0, :n], ends[1, :n]  # views, so that a reversal updates ``after`` too
    after = ends[0, 1:]  # after[j]: where the path after path j starts (nan after the last)
    link = np.zeros(n)  # from each path's end to the next path's start; 0 after the last
    link[:-1] = _hypot(e[:-1] - s[1:])
    order = np.arange(n)
    flipped = np.zeros(n, dtype=bool)
    for _ in range(passes):
        improved = False
        for i in range(n - 1):  # segment [i, j] for j in i+1 .. stop-1; before it: prev
            prev = start if i == 0 else e[i - 1]
            stop = min(n, i + 1 + window)
            # the way out of each path j and the way into path i (kept, but from the start)
            old = link[i + 1:stop] + (link[i - 1] if i else _hypot(start - s[0]))
            d = prev - e[i + 1:stop]
            new = np.hypot(d[:, 0], d[:, 1])
            d = s[i] - after[i + 1:stop]
            back = np.hypot(d[:, 0], d[:, 1])
            if stop == n:  # a run to the last path leaves no way to a next one
                back[-1] = 0.0
            gain = snap(old - (new + back))
            k = int(np.argmax(gain))
            if gain[k] > 0:  # at least 1 nm shorter
                run = slice(i, i + 2 + k)  # reversed: each path's ends swap too
                order[run] = order[run][::-1].copy()
                flipped[run] = ~flipped[run][::-1]
                s[run], e[run] = e[run][::-1].copy(), s[run][::-1].copy()
                near = slice(max(i - 1, 0), min(run.stop, n - 1))  # the links it changed
                link[near] = _hypot(e[near] - after[near])
                improved = True
        if not improved:
            break
    return [paths[o][::-1] if f else paths[o] for o, f in zip(order.tolist(), flipped.tolist())]


def _hypot(d: NDArray) -> NDArray:
    return np.hypot(d[..., 0], d[..., 1])


def travel_length(paths: list[NDArray], start=(0.0, 0.0)) -> float:
    """Head travel (mm) from ``start`` through the paths in order, not cutting."""
    if not paths:
        return 0.0
    s = np.array([p[0] for p in paths])
    e = np.array([start] + [p[-1] for p in paths[:-1]], dtype=float)  # one path: start only
    return float(np.hypot(*(s - e).T).sum())
