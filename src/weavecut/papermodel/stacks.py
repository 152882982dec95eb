"""Stacks of congruent pieces: the move that nests a copy of a piece beside it most tightly
(the packer lays a stack of a strip's copies as one piece, :mod:`.packing`)."""

from __future__ import annotations

import numpy as np
import shapely
from numpy.typing import NDArray


def nest_offset(shape, gap: float, step: float = 0.25,
                longest: float = np.inf) -> NDArray[np.float64]:
    """(dx, dy): the move that nests a copy of ``shape`` (long axis along x) ``gap`` mm clear of
    it most tightly: for every slide dx along the axis a clear dy across it, bisected to within
    ``step`` of one that is not, and of those the one whose pair has the smallest convex hull
    (congruent wavy strips nest). Slides go up to ``longest`` mm beyond the shape's length (a
    pair slid further than the page is long would lie only aslant on it)."""
    x0, y0, x1, y1 = shape.bounds
    slide = min(x1 - x0, 30.0)
    slide = slide if slide <= longest else max(float(np.floor(longest)), 0.0)
    dxs = np.arange(-slide, slide + 1e-9, 1.0)
    low, high = np.zeros_like(dxs), np.full_like(dxs, y1 - y0 + gap)  # overlapping, clear

    def copies(dys):
        moves = np.column_stack([dxs, dys])
        return shapely.transform(np.full(len(dxs), shape, dtype=object),
                                 lambda xy: xy + np.repeat(moves, len(xy) // len(moves), axis=0))

    while (high - low > step).any():  # a few halvings, every slide at once
        mid = (low + high) / 2
        clear = shapely.distance(shape, copies(mid)) >= gap
        low, high = np.where(clear, low, mid), np.where(clear, mid, high)
    pairs = np.column_stack([np.full(len(dxs), shape, dtype=object), copies(high)]).ravel()
    box = shapely.area(shapely.convex_hull(shapely.geometrycollections(  # the pairs' hulls, no
        pairs, indices=np.repeat(np.arange(len(dxs)), 2))))  # union needed
    best = np.lexsort((np.abs(dxs), np.round(box, 3)))[0]
    return np.array([dxs[best], high[best]])
