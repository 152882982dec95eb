"""What the maker prints and loads beside the cut: the printed guide keeps the colour key first
and exactly the pages that hold paint, on the page size asked for; separate sheets keep the
documented 5 mm margin and 2 mm spacing, and each sheet's file keeps the cut's metadata; number
inks break a tie towards black; the summary's times keep a tenth of a minute."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from weavecut.layout.contrast import BLACK
from weavecut.layout.tiling import tile
from weavecut.puzzle import files as pf
from weavecut.puzzle import workshop
from weavecut.puzzle.colouring import UNPAINTED
from weavecut.puzzle.guides import _number_colours, _number_shapes, colour_key, guide, printed

from tests.built_puzzles import pentagon_paint, pentagon_puzzle


def _has_paint(sheet) -> bool:
    return any(layer.role == "paint" and layer.shapes for layer in sheet.layers)


@pytest.mark.parametrize("page", [(297.0, 210.0), (148.0, 105.0)])  # not A4, the default
def test_printed_guide_is_the_key_then_the_pages_with_paint(page):
    puzzle, colouring = pentagon_puzzle(3), pentagon_paint(3)
    front = guide(puzzle, colouring, "front")
    key = colour_key(puzzle, colouring, "front", page=page)
    pages = printed(front, key, page)
    assert pages.sheets[:len(key.sheets)] == key.sheets
    rest = pages.sheets[len(key.sheets):]
    tiles = tile(front, page).sheets
    assert [s.name for s in rest] == [s.name for s in tiles if _has_paint(s)]
    assert len(rest) < len(tiles)  # the frame's corners hold no paint: those pages are left out
    assert all((s.width, s.height) == page for s in rest)


def test_separate_sheets_keep_the_documented_margin_and_spacing():
    """Defaults: parts 5 mm from the sheet's edges and 2 mm apart (their outlines' boxes, as
    nested): the tightest part touches each limit."""
    puzzle = pentagon_puzzle(2)
    result = pf.separate_cut(puzzle, pf.laser(), 0.2, (500.0, 400.0))
    for parts in pf.nested_parts(result):
        boxes = shapely.box(*shapely.bounds(parts).T)
        lo = shapely.bounds(parts)[:, :2].min(axis=0)
        np.testing.assert_allclose(lo, [5.0, 5.0], atol=1e-9)
        a, b = shapely.STRtree(boxes).query(boxes, predicate="dwithin", distance=10.0)
        a, b = a[a < b], b[a < b]
        apart = ~(shapely.contains(boxes[a], boxes[b]) | shapely.contains(boxes[b], boxes[a]))
        gaps = shapely.distance(boxes[a[apart]], boxes[b[apart]])
        assert gaps.min() == pytest.approx(2.0, abs=1e-9)
    # each sheet's drawing carries the cut's metadata (mode and kerf) into its file
    for one in pf.split_sheets(result.drawing):
        assert one.metadata == (("mode", "separate"), ("kerf", "0.2 mm"))
        assert one.title.startswith("weave-cut puzzle: separate pieces, sheet ")


def test_a_tie_between_black_and_white_numbers_goes_to_black():
    """A piece painted black and white reads as badly in either ink (contrast 1 on one half):
    its number is black, like every number on unpainted wood; numbers are drawn in thin
    strokes (a fraction of a millimetre) so digits 3 mm high stay open."""
    puzzle, colouring = pentagon_puzzle(2), pentagon_paint(2)
    front = colouring.front.copy()
    front[0] = ("#000000", "#ffffff")
    front[1] = (UNPAINTED, UNPAINTED)
    tied = type(colouring)(front, colouring.back, colouring.front_strands,
                           colouring.back_strands, colouring.face_colours, colouring.names,
                           colouring.touching)
    inks = _number_colours(puzzle, tied, "front")
    assert inks[0] == BLACK and inks[1] == BLACK
    numbers = pf.piece_numbers(puzzle)
    shapes = _number_shapes(numbers, inks)
    assert all(0.2 <= s.style.stroke_width <= 0.1 * numbers.heights.max() for s in shapes)


def test_summary_times_keep_a_tenth_of_a_minute():
    """6 m of cutting at 7 mm/s and 3 m of travel at 300 mm/s: 14.29 + 0.17 = 14.5 min."""
    puzzle = pentagon_puzzle(2)
    result = pf.CutResult(pf.shared_cut(puzzle, pf.laser()).drawing, 6000.0, 3000.0, 12, 1)
    info = workshop.summary(puzzle, {"shared": result}, 7.0)
    assert info["modes"]["shared"] == {"cut_length_m": 6.0, "travel_m": 3.0, "paths": 12,
                                       "sheets": 1, "time_min": 14.5}
