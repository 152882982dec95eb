"""The packer as a maker relies on it (``nesting.nest``): whatever the parts and their turns,
no two placed parts come closer than the spacing, every part stays inside the sheet's
margins, and a frame's hole takes the small parts by default (``rooms`` left out). Checked on
the placed shapes with shapely, not on the packer's own rectangles; the skyline's spot and the
room search's free runs against trying every place (#34: the layout package's survivors)."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout import nesting
from weavecut.layout.nesting import nest

SHEET, SPACING, MARGIN = (200.0, 150.0), 2.0, 5.0


def _placed(parts, placement):
    return placement.apply(np.asarray(parts, dtype=object))


@settings(deadline=None)
@given(st.lists(st.tuples(st.floats(3, 90), st.floats(3, 90), st.floats(-90, 90)), min_size=1,
                max_size=24))
def test_placed_parts_keep_the_spacing_and_the_margins(specs):
    parts = np.array([shapely.affinity.rotate(shapely.box(0, 0, w, h), a, origin=(0, 0))
                      for w, h, a in specs], dtype=object)
    placement = nest(parts, SHEET, SPACING, MARGIN)
    placed = _placed(parts, placement)
    assert np.allclose(shapely.area(placed), shapely.area(parts))  # moved, not changed
    x0, y0, x1, y1 = shapely.bounds(placed).T
    assert (x0 >= MARGIN - 1e-6).all() and (y0 >= MARGIN - 1e-6).all()
    assert (x1 <= SHEET[0] - MARGIN + 1e-6).all() and (y1 <= SHEET[1] - MARGIN + 1e-6).all()
    assert set(placement.sheet.tolist()) == set(range(placement.n_sheets))
    for s in range(placement.n_sheets):
        here = placed[placement.sheet == s]
        for k in range(len(here)):
            gaps = shapely.distance(here[k], here[k + 1:])
            assert (gaps >= SPACING - 1e-6).all(), (s, k, gaps.min())


def test_a_frames_hole_takes_the_small_parts_by_default():
    frame = shapely.box(0, 0, 100, 100).difference(shapely.box(10, 10, 90, 90))
    small = [shapely.box(0, 0, 15, 15)] * 6
    parts = np.array([frame, *small], dtype=object)
    placement = nest(parts, SHEET, SPACING, MARGIN)
    placed = _placed(parts, placement)
    hole = shapely.Polygon(placed[0].interiors[0])
    assert placement.n_sheets == 1 and placement.room_of.tolist() == [-1] + [0] * 6
    assert all(hole.contains(p) for p in placed[1:])


@given(st.lists(st.tuples(st.integers(1, 20), st.integers(0, 30)), min_size=1, max_size=8),
       st.integers(1, 60), st.integers(1, 40))
def test_the_skyline_spot_is_the_lowest_then_leftmost_of_every_segment_start(segments, w, h):
    """``_skyline_fit`` against trying each segment's start: the rectangle rests on the highest
    segment it overlaps, and the lowest such rest (then the leftmost) that fits is chosen."""
    sky, x = [], 0.0
    for width, height in segments:
        sky.append([x, float(height), float(width)])
        x += width
    room_w, room_h = x, 50.0
    tries = []
    for i, (x0, _, _) in enumerate(sky):
        if x0 + w <= room_w:
            rest = max(y for s, y, sw in sky if s < x0 + w and s + sw > x0)
            if rest + h <= room_h:
                tries.append((rest, x0, i))
    best = min(tries, default=None)
    assert nesting._skyline_fit(sky, w, h, room_w, room_h) == (
        None if best is None else (best[2], best[1], best[0]))


@given(st.integers(1, 9), st.integers(1, 9), st.integers(0, 2**32 - 1))
def test_the_free_run_above_each_cell_is_counted_from_that_cell_up(rows, cols, seed):
    inside = np.random.default_rng(seed).random((rows, cols)) < 0.7
    want = np.zeros((rows, cols), dtype=np.int32)
    for r in range(rows):
        for c in range(cols):
            while r + want[r, c] < rows and inside[r + want[r, c], c]:
                want[r, c] += 1
    assert np.array_equal(nesting._free_above(inside), want)
