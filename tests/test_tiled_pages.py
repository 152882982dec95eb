"""Tiled pages a maker assembles: every page names itself by its number in the file and names
only pages that exist, each the true neighbour it says (their overlap strips show the same
paint); a drawing takes no more pages than its content needs, and no page holds only a sliver
of it. Read from the pages as drawn: the label's text, the window's corner ticks, the paint."""

from __future__ import annotations

import itertools
import math
import re

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from weavecut.layout import raster
from weavecut.layout.drawing import Drawing, Layer, Polylines, Raster, Sheet, Style, Text
from weavecut.layout.drawing import polygons_from_rings, polylines_from_lines, vectors
from weavecut.layout.labels import text_width
from weavecut.layout.tiling import SHIFTS, balanced, on_pages, tile
from weavecut.puzzle.guide_numbers import guide_numbers
from weavecut.puzzle.guides import colour_key, guide, printed

from tests.built_puzzles import heart_puzzle, pentagon_paint, pentagon_puzzle

A4 = (210.0, 297.0)
TICK = 8.0  # mm, a window corner's tick, end to end


def _marks(sheet):
    return next(layer for layer in sheet.layers if layer.name == "page-marks")


def window(sheet) -> tuple[float, float, float, float]:
    """The page's window, from its corner ticks (the horizontal strokes TICK mm long)."""
    lines = next(s for s in _marks(sheet).shapes if isinstance(s, Polylines)).lines()
    mids = [ln.mean(axis=0) for ln in lines
            if len(ln) == 2 and abs(ln[0, 1] - ln[1, 1]) < 1e-9
            and abs(abs(ln[1, 0] - ln[0, 0]) - TICK) < 1e-9]
    xy = np.array(mids)
    assert len(xy) == 4
    return (*xy.min(axis=0), *xy.max(axis=0))


def words_of(sheet) -> str:
    return " ".join(s.text for s in _marks(sheet).shapes if isinstance(s, Text))


def _paint(sheet, box):
    polys = [g for layer in sheet.layers if layer.role == "paint" for s in layer.shapes
             for g in s.to_shapely().tolist()]
    return shapely.intersection(shapely.union_all(polys), shapely.box(*box))


def check_labels(pages, first: int) -> None:
    """Pages ``first``.. of ``pages`` (1-based: the tiles after a key): each says "page n of
    N" with its own place in the file, and every page it names exists and joins it where it
    says: their overlap strips hold the same paint."""
    total = len(pages)
    for n in range(first, total + 1):
        sheet = pages[n - 1]
        text = words_of(sheet)
        assert f" - page {n} of {total}; " in text, text
        overlap = float(re.search(r"overlap (\d+(?:\.\d+)?) mm", text).group(1))
        x0, y0, x1, y1 = window(sheet)
        for k, where in re.findall(r"page (\d+) (on the right|below)", text):
            k = int(k)
            assert first <= k <= total and k != n
            other = pages[k - 1]
            u0, v0, u1, v1 = window(other)
            if where == "on the right":
                mine = _paint(sheet, (x1 - overlap, y0, x1, y1))
                theirs = shapely.transform(_paint(other, (u0, v0, u0 + overlap, v1)),
                                           lambda xy: xy + (x1 - overlap - u0, y0 - v0))
            else:
                mine = _paint(sheet, (x0, y0, x1, y0 + overlap))
                theirs = shapely.transform(_paint(other, (u0, v1 - overlap, u1, v1)),
                                           lambda xy: xy + (x0 - u0, y0 + overlap - v1))
            assert mine.area == pytest.approx(theirs.area, rel=1e-6, abs=1e-6), (n, k)
            assert shapely.symmetric_difference(mine, theirs).area < 1e-3 * max(mine.area, 1)


def _guides():
    out = []
    for name, (puzzle, colouring) in {"default": (pentagon_puzzle(4, 500.0),
                                                  pentagon_paint(4, 500.0)),
                                      "heart": heart_puzzle()}.items():
        for side in ("front", "back"):
            out.append((name, side, puzzle, colouring))
    return out


@pytest.mark.parametrize("name,side", [(n, s) for n, s, *_ in _guides()])
def test_every_page_names_itself_and_only_pages_that_exist(name, side):
    (_, _, puzzle, colouring), = [g for g in _guides() if g[:2] == (name, side)]
    g = guide(puzzle, colouring, side, guide_numbers(puzzle, colouring, side))
    key = colour_key(puzzle, colouring, side)
    pages = printed(g, key, A4).sheets
    check_labels(pages, len(key.sheets) + 1)
    assert not any("page row" in words_of(s) for s in pages[len(key.sheets):])


def _fewest(width, height, page, overlap=10.0) -> int:
    """The fewest pages that hold a width x height box: per orientation and margin (10 mm, or
    8), the least count of windows that, stepped by their size less the overlap, reach across
    it."""
    best = math.inf
    for p in (page, page[::-1]):
        for m in (10.0, 8.0):
            w, h = p[0] - 2 * m, p[1] - 2 * m
            cols = next(c for c in range(1, 99) if c * (w - overlap) + overlap >= width)
            rows = next(r for r in range(1, 99) if r * (h - overlap) + overlap >= height)
            best = min(best, cols * rows)
    return best


@pytest.mark.parametrize("name,side", [(n, s) for n, s, *_ in _guides()])
def test_a_guide_takes_the_fewest_pages_and_none_is_a_sliver(name, side):
    """As many pages as the guide's frame needs (it fits no fewer), every page with paint,
    and on every page what is drawn spans at least half the window each way where the guide
    is wider (taller) than one window."""
    (_, _, puzzle, colouring), = [g for g in _guides() if g[:2] == (name, side)]
    g = guide(puzzle, colouring, side)
    key = colour_key(puzzle, colouring, side)
    tiles = printed(g, key, A4).sheets[len(key.sheets):]
    frame = next(layer for layer in g.sheets[0].layers if layer.name == "frame")
    x0, y0, x1, y1 = shapely.total_bounds(frame.shapes[0].to_shapely())
    assert len(tiles) <= _fewest(x1 - x0 + 2, y1 - y0 + 2, A4)
    for sheet in tiles:
        assert _paint(sheet, window(sheet)).area > 0
        check_spans(sheet, len(tiles))
    if name == "heart":  # the whole heart, its tip too, on two pages (it had 2 and lost its tip)
        assert len(tiles) == 2


def check_spans(sheet, n_pages: int) -> None:
    """What is drawn inside the window spans at least half of it each way (on a page among
    several)."""
    wx0, wy0, wx1, wy1 = window(sheet)
    drawn = [g for layer in sheet.layers if layer.name != "page-marks" for s in layer.shapes
             if not isinstance(s, Text)
             for g in (s.to_shapely().tolist() if hasattr(s, "to_shapely") else
                       [shapely.multipoints(s.coords)])]
    bx0, by0, bx1, by1 = shapely.total_bounds(drawn)
    if n_pages > 1:
        assert (bx1 - bx0) >= 0.5 * (wx1 - wx0) and (by1 - by0) >= 0.5 * (wy1 - wy0)


def _box_drawing(w: float, h: float) -> Drawing:
    """A w x h rectangle, filled as paint, on a sheet 30 mm larger each way."""
    ring = np.array([[15, 15], [15 + w, 15], [15 + w, 15 + h], [15, 15 + h]], dtype=float)
    shape = polygons_from_rings([ring], Style("#000000", 0.3), ["#88aa44"])
    return Drawing((Sheet(w + 30, h + 30, (Layer("paint", "paint", (shape,)),)),), "box")


@given(w=st.floats(150.0, 900.0), h=st.floats(150.0, 900.0))
def test_tiles_of_any_box_are_few_centred_and_never_slivers(w, h):
    """The pages over a box: as few as the box needs (pad included) on the page as given; each
    window holds at least half a window's width (height) of it where there are several
    columns (rows); labels name pages that exist and join where they say."""
    pages = tile(_box_drawing(w, h), A4).sheets
    cols = {s.name.split()[-1] for s in pages}
    rows = {s.name.split()[-2] for s in pages}
    assert len(pages) == len(cols) * len(rows)
    fewest = math.inf
    for m in (10.0, 8.0):
        ww, wh = A4[0] - 2 * m, A4[1] - 2 * m
        c = next(c for c in range(1, 99) if c * (ww - 10) + 10 >= w + 2.3)
        r = next(r for r in range(1, 99) if r * (wh - 10) + 10 >= h + 2.3)
        fewest = min(fewest, c * r)
    assert len(pages) <= fewest
    for sheet in pages:
        x0, y0, x1, y1 = window(sheet)
        inside = _paint(sheet, (x0, y0, x1, y1))
        bx0, by0, bx1, by1 = inside.bounds
        if len(cols) > 1:
            assert bx1 - bx0 >= 0.5 * (x1 - x0) - 1e-6
        if len(rows) > 1:
            assert by1 - by0 >= 0.5 * (y1 - y0) - 1e-6
    check_labels(pages, 1)


def test_pages_of_several_sheets_are_numbered_through_the_file():
    """on_pages: a small sheet on one page, then a large one tiled: its pages say 2.. of N."""
    small = _box_drawing(50, 50).sheets[0]
    large = _box_drawing(400, 500).sheets[0]
    pages = on_pages(Drawing((small, large), "two"), A4).sheets
    assert len(pages) > 2
    check_labels(pages, 2)


def test_a_page_naming_a_page_beyond_the_file_is_caught():
    """The planted bug: tiles numbered as if the key ahead of them were not there."""
    puzzle, colouring = pentagon_puzzle(2), pentagon_paint(2)
    g = guide(puzzle, colouring, "front")
    pages = tile(g, A4, before=0).sheets
    key = colour_key(puzzle, colouring, "front").sheets
    with pytest.raises(AssertionError):
        check_labels(key + pages, len(key) + 1)


def _paint_shares(pages) -> list[float]:
    """Per page: the share of its window its paint covers (exact areas)."""
    out = []
    for sheet in pages:
        x0, y0, x1, y1 = window(sheet)
        polys = [g for layer in sheet.layers if layer.name == "paint" for s in layer.shapes
                 for g in s.to_shapely().tolist()]
        out.append(shapely.union_all(polys).area / ((x1 - x0) * (y1 - y0)))
    return out


@pytest.mark.parametrize("name,side", [(n, s) for n, s, *_ in _guides()])
def test_the_emptiest_page_holds_as_much_paint_as_the_centred_grids_does(name, side):
    """The printed guide's pages: no more than the centred grid's on either orientation, and
    its emptiest page holds at least as much paint (to 1 % of a page) as theirs."""
    (_, _, puzzle, colouring), = [g for g in _guides() if g[:2] == (name, side)]
    g = guide(puzzle, colouring, side)
    key = colour_key(puzzle, colouring, side)
    tiles = printed(g, key, A4).sheets[len(key.sheets):]
    bare = Drawing((Sheet(g.sheets[0].width, g.sheets[0].height, tuple(
        layer for layer in g.sheets[0].layers if layer.name != "registration")),), g.title)
    centred = [[s for s in tile(bare, p).sheets if _paint_shares([s])[0] > 0]
               for p in (A4, A4[::-1])]
    fewest = min(len(c) for c in centred)
    assert len(tiles) <= fewest
    best = max(min(_paint_shares(c)) for c in centred if len(c) == fewest)
    assert min(_paint_shares(tiles)) >= best - 0.01


ISLANDS = {  # (sheet width, height), 30 mm squares of paint whose centred grid paints a page more
    "four": ((352.3, 387.4), [(23.1, 261.7), (172.3, 123.0), (15.0, 15.0), (307.3, 342.4)]),
    "six": ((341.3, 362.1), [(45.9, 76.4), (94.8, 109.9), (103.0, 189.2), (288.3, 249.0),
                             (15.0, 15.0), (296.3, 317.1)]),
}


@pytest.mark.parametrize("name", sorted(ISLANDS))
def test_the_balanced_grid_paints_the_fewest_pages_of_any_shift(name):
    """``balanced`` (which weighs paint by points on a grid) against every shift of each page
    that needs the fewest windows, each tiled and its pages' paint measured with shapely: the
    choice paints no more pages than the best of them, and fewer than the centred grid."""
    (w, h), corners = ISLANDS[name]
    rings = [np.array([[x, y], [x + 30, y], [x + 30, y + 30], [x, y + 30]]) for x, y in corners]
    shape = polygons_from_rings(rings, Style("#000000", 0.3), ["#88aa44"] * len(rings))
    drawing = Drawing((Sheet(w, h, (Layer("paint", "paint", (shape,)),)),), name)

    def painted(page, shift):
        pages = tile(drawing, page, 10.0, 10.0, shift=shift).sheets
        return sum(shapely.union_all([g for layer in s.layers if layer.name == "paint"
                                      for p in layer.shapes for g in p.to_shapely().tolist()]
                                     ).area > 1.0 for s in pages)

    windows = {page: len(tile(drawing, page, 10.0, 10.0).sheets) for page in (A4, A4[::-1])}
    pages = [page for page in windows if windows[page] == min(windows.values())]
    every = {(page, shift): painted(page, shift) for page in pages
             for shift in itertools.product(SHIFTS, SHIFTS)}
    page, shift = balanced(drawing.sheets[0], (A4, A4[::-1]), 10.0, 10.0)
    assert every[(tuple(page), tuple(shift))] == min(every.values()) < every[(pages[0],
                                                                              (0.5, 0.5))]


def test_the_scale_bars_length_is_written_on_the_page_right_of_the_bar():
    """Each page's 100 mm bar: its words start past the bar's right end and end on the page
    (a ruler a maker checks the print against, so it must be readable beside the bar)."""
    for sheet in tile(_box_drawing(400, 500), A4).sheets:
        marks = _marks(sheet)
        label = next(s for s in marks.shapes if isinstance(s, Text) and s.text == "100 mm")
        bar = next(line for s in marks.shapes if isinstance(s, Polylines) for line in s.lines()
                   if len(line) == 2 and abs(line[1, 0] - line[0, 0]) == 100.0)
        assert label.anchor == "start" and label.x > bar[:, 0].max()
        assert label.x + text_width(label.text, label.size) <= sheet.width


def test_a_picture_centred_on_a_page_takes_the_lines_it_stands_for_along():
    """A picture's lines (what a DXF or a laser job draws instead of its pixels) lie on the
    picture wherever the page puts it: the lines' bounds inside its box, as far from its
    corner as before it was centred."""
    lines = polylines_from_lines([[(40.0, 60.0), (90.0, 75.0)], [(45.0, 90.0), (70.0, 62.0)]],
                                 Style("#000000", 0.03))
    picture = raster.picture([lines])
    drawing = Drawing((Sheet(300.0, 400.0, (Layer("fine", "engrave", (picture,)),)),), "pic")
    page, = on_pages(drawing, A4).sheets
    moved, = (s for layer in page.layers for s in layer.shapes if isinstance(s, Raster))
    assert (moved.x, moved.y) != (picture.x, picture.y)  # centred: moved on the page
    drawn, = vectors([moved])
    x0, y0 = drawn.coords.min(axis=0)
    x1, y1 = drawn.coords.max(axis=0)
    assert moved.x < x0 and x1 < moved.x + moved.width
    assert moved.y < y0 and y1 < moved.y + moved.height
    assert np.allclose(drawn.coords - (moved.x, moved.y), lines.coords - (picture.x, picture.y),
                       rtol=0, atol=1e-9)
