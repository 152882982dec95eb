"""What the maker prints and loads beside the cut: the printed guide keeps the colour key first
and exactly the pages that hold paint, on the page size asked for; separate sheets keep the
documented 5 mm margin and 2 mm spacing, and each sheet's file keeps the cut's metadata; a piece
painted black and white has its number in one half; the summary's times keep a tenth of a minute."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import shapely

from weavecut.errors import WeaveCutError
from weavecut.layout.contrast import BLACK, WHITE
from weavecut.layout.tiling import balanced, tile, word_overlap
from weavecut.layout.lasersetup import laser
from weavecut.puzzle import files as pf
from weavecut.puzzle import workshop
from weavecut.puzzle.frame import fits
from weavecut.puzzle.colouring import UNPAINTED
from weavecut.puzzle.guide_numbers import guide_numbers
from weavecut.puzzle.guides import OUTLINE, SPLIT, colour_key, guide, piece_halves, printed

from tests.built_puzzles import pentagon_paint, pentagon_puzzle


def _has_paint(sheet) -> bool:
    return any(layer.role == "paint" and layer.shapes for layer in sheet.layers)


@pytest.mark.parametrize("page", [(297.0, 210.0), (148.0, 105.0)])  # not A4, the default
def test_printed_guide_is_the_key_then_the_pages_with_paint(page):
    """The key first, then the guide's tiles on the page asked for (or the same turned):
    exactly those with paint, in the order tiled, the 1:1 sheet's crosshairs left off."""
    puzzle, colouring = pentagon_puzzle(3), pentagon_paint(3)
    front = guide(puzzle, colouring, "front")
    key = colour_key(puzzle, colouring, "front", page=page)
    pages = printed(front, key, page)
    assert pages.sheets[:len(key.sheets)] == key.sheets
    rest = pages.sheets[len(key.sheets):]
    size = (rest[0].width, rest[0].height)
    assert size in (page, page[::-1])
    bare = replace(front, sheets=(replace(front.sheets[0], layers=tuple(
        layer for layer in front.sheets[0].layers if layer.name != "registration")),))
    best, shift = balanced(bare.sheets[0], (page, page[::-1]), word_overlap(bare), 10.0)
    assert best == size
    tiles = tile(bare, size, word_overlap(bare), shift=shift).sheets
    assert [s.name for s in rest] == [s.name for s in tiles if _has_paint(s)]
    assert all((s.width, s.height) == size for s in rest)
    assert not any(layer.name == "registration" for s in rest for layer in s.layers)


def test_separate_sheets_keep_the_documented_margin_and_spacing():
    """Defaults: parts 5 mm from the sheet's edges and pieces 2 mm apart (their outlines'
    boxes, as nested; a piece may lie in the frame's box, in its hole or a bay): the tightest
    part touches each limit."""
    puzzle = pentagon_puzzle(2)
    result = pf.separate_cut(puzzle, laser(), 0.2, (500.0, 400.0))
    for parts in pf.nested_parts(result):
        boxes = shapely.box(*shapely.bounds(parts).T)
        lo = shapely.bounds(parts)[:, :2].min(axis=0)
        np.testing.assert_allclose(lo, [5.0, 5.0], atol=1e-9)
        a, b = shapely.STRtree(boxes).query(boxes, predicate="dwithin", distance=10.0)
        a, b = a[a < b], b[a < b]
        frame = shapely.area(parts) > 20 * shapely.area(parts).min()  # its outline, its hole
        apart = ~(frame[a] | frame[b])
        gaps = shapely.distance(boxes[a[apart]], boxes[b[apart]])
        assert gaps.min() == pytest.approx(2.0, abs=1e-9)
    # each sheet's drawing carries the cut's metadata (mode and kerf) into its file
    for one in pf.split_sheets(result.drawing):
        assert one.metadata == (("mode", "separate"), ("kerf", "0.2 mm"))
        assert one.title.startswith("weave-cut puzzle: separate pieces, sheet ")


def test_separate_sheets_keep_a_margin_asked_for():
    """A margin other than the default: every part that far from every edge, the tightest on
    it."""
    puzzle = pentagon_puzzle(2)
    sheet = (500.0, 400.0)
    result = pf.separate_cut(puzzle, laser(), 0.2, sheet, margin=12.0)
    for parts in pf.nested_parts(result):
        bounds = shapely.bounds(parts)
        np.testing.assert_allclose(bounds[:, :2].min(axis=0), [12.0, 12.0], atol=1e-9)
        assert (bounds[:, 2:] <= np.subtract(sheet, 12.0) + 1e-9).all()


def _rings(sheet, name: str) -> list:
    """The closed rings of one cut layer of a sheet, in cutting order."""
    layers = {layer.name: layer for layer in sheet.layers}
    return list(layers[name].shapes[0].rings()) if name in layers else []


@pytest.mark.parametrize("sheet", [(500.0, 400.0), (315.0, 300.0)])
def test_each_sheet_is_cut_from_the_home_corner_along_a_route_no_reversal_shortens(sheet):
    """The head starts every sheet in its top-left corner (0, height): no reversal of a leading
    run of the inner cuts shortens the travel from there (2-opt optimal from home; a closed ring
    ends where it starts), and the frame's outline, cut last, is entered at its corner nearest
    to where the inner cuts ended."""
    puzzle = pentagon_puzzle(2)
    result = pf.separate_cut(puzzle, laser(), 0.2, sheet)
    home = np.array([0.0, sheet[1]])
    outlines = 0
    for s in result.drawing.sheets:
        inner = _rings(s, "cut-1-inner")
        starts = np.array([ring[0] for ring in inner])

        def travel(order):
            return np.hypot(*np.diff(np.vstack([home, starts[order]]), axis=0).T).sum()

        n = len(inner)
        base = travel(np.arange(n))
        for j in range(1, n):
            assert travel(np.r_[np.arange(j, -1, -1), np.arange(j + 1, n)]) >= base - 1e-9
        for ring in _rings(s, "cut-2-outer")[:1]:
            d = np.hypot(*(ring - inner[-1][0]).T)
            assert d[0] <= d.min() + 1e-9
            outlines += 1
    assert outlines == 1 and result.n_sheets >= 1


def test_every_separate_piece_carries_its_number_even_alone_on_a_sheet():
    """Sheets that hold a few pieces each (the frame in two small parts): every piece's outline
    holds engraved strokes, also piece 1's, which this nesting puts alone on its sheet."""
    puzzle = pentagon_puzzle(2)
    tiny = np.array([shapely.box(0, 0, 5, 5), shapely.box(0, 0, 5, 5)], dtype=object)
    result = pf.separate_cut(puzzle, laser(), 0.2, (90.0, 90.0), frame_parts=tiny,
                             numbers=pf.piece_numbers(puzzle))
    numbered, alone = 0, 0
    for s in result.drawing.sheets:
        pieces = [shapely.Polygon(r) for r in _rings(s, "cut-1-inner")]  # split parts: outer
        strokes = [shapely.LineString(ln) for layer in s.layers
                   if layer.name == "engrave-numbers" for shape in layer.shapes
                   for ln in shape.lines()]
        numbered += sum(any(p.contains(st) for st in strokes) for p in pieces)
        alone += len(pieces) == 1
    assert numbered == puzzle.n_pieces and alone >= 1


def test_a_piece_painted_black_and_white_has_its_number_inside_one_half():
    """A piece painted black and white reads in neither ink across both halves (contrast 1
    on one of them): its number moves into one half, in the ink that reads there (contrast
    21); an unpainted piece's number is black. Numbers are drawn in thin strokes (a fraction
    of a millimetre) so digits 3 mm high stay open, bolder than the dashed split lines they
    may cross and lighter than the piece outlines around them (the README tells the maker:
    bold lines are outlines, thin dashed lines split)."""
    puzzle, colouring = pentagon_puzzle(2), pentagon_paint(2)
    front = colouring.front.copy()
    front[0] = ("#000000", "#ffffff")
    front[1] = (UNPAINTED, UNPAINTED)
    tied = type(colouring)(front, colouring.back, colouring.front_strands,
                           colouring.back_strands, colouring.face_colours, colouring.names,
                           colouring.touching)
    numbers = guide_numbers(puzzle, tied, "front")
    assert numbers.inks[1] == BLACK and numbers.plates[0] is None
    halves = piece_halves(puzzle)[0]
    box = shapely.box(*(numbers.labels.centres[0] - 0.01), *(numbers.labels.centres[0] + 0.01))
    inside = [h.contains(box) for h in halves]
    assert sum(inside) == 1 and numbers.inks[0] == (WHITE if inside[0] else BLACK)
    sheet = guide(puzzle, tied, "front", numbers).sheets[0]
    shapes = [s for layer in sheet.layers if layer.name == "numbers" for s in layer.shapes]
    assert all(SPLIT.stroke_width < s.style.stroke_width < OUTLINE.stroke_width
               and s.style.stroke_width <= 0.1 * numbers.labels.heights.max() for s in shapes)


def test_summary_times_keep_a_tenth_of_a_minute():
    """6 m of cutting at 7 mm/s and 3 m of travel at 300 mm/s: 14.29 + 0.17 = 14.5 min."""
    puzzle = pentagon_puzzle(2)
    result = pf.CutResult(pf.shared_cut(puzzle, laser()).drawing, 6000.0, 3000.0, 12, 1)
    info = workshop.summary(puzzle, {"shared": result}, 7.0)
    assert {k: v for k, v in info["modes"]["shared"].items() if k != "layers"} == {
        "cut_length_m": 6.0, "travel_m": 3.0, "paths": 12, "sheets": 1, "time_min": 14.5}


def test_a_part_too_large_for_the_sheet_is_named_as_the_maker_knows_it():
    """The frame is "the frame", a split frame's parts by their engraved labels, pieces by
    their engraved numbers (1-based)."""
    puzzle = pentagon_puzzle(2)
    with pytest.raises(WeaveCutError, match=r"^the frame is [\d.]+ x [\d.]+ mm and does not fit "
                                            r"a 200 x 150 mm sheet with 5 mm margins"):
        pf.separate_cut(puzzle, laser(), 0.2, (200.0, 150.0))
    long = np.array([shapely.box(0, 0, 300, 10), shapely.box(0, 0, 5, 5)], dtype=object)
    with pytest.raises(WeaveCutError, match=r"^frame part F1 is 300\.2 x 10\.2 mm"):
        pf.separate_cut(puzzle, laser(), 0.2, (200.0, 150.0), frame_parts=long)
    tiny = np.array([shapely.box(0, 0, 5, 5), shapely.box(0, 0, 5, 5)], dtype=object)
    sheet = (60.0, 60.0)
    grown = shapely.buffer(puzzle.pieces, 0.1, join_style="mitre")
    first = int(np.flatnonzero(~fits(grown, sheet, 5.0))[0])
    with pytest.raises(WeaveCutError, match=rf"^piece {first + 1} is "):
        pf.separate_cut(puzzle, laser(), 0.2, sheet, frame_parts=tiny)


def test_separate_numbers_are_engraved_in_the_lasers_engrave_style_and_travel_adds_up():
    puzzle = pentagon_puzzle(2)
    las = laser("epilog-uls")  # its engrave style is not the fallback of an unknown role
    assert las.style("engrave") != las.style("no such role")
    sheet = (315.0, 300.0)
    result = pf.separate_cut(puzzle, las, 0.2, sheet, numbers=pf.piece_numbers(puzzle))
    travel, numbered, length, paths = 0.0, 0, 0.0, 0
    for s in result.drawing.sheets:
        layers = {layer.name: layer for layer in s.layers}
        engraved = [shape.style for shape in layers["engrave-numbers"].shapes] if (
            "engrave-numbers" in layers) else []
        assert engraved in ([], [las.style("engrave")])
        numbered += len(engraved)
        assert all(shape.style == las.style("cut") for name in ("cut-1-inner", "cut-2-outer")
                   if name in layers for shape in layers[name].shapes)
        outlines = [shapely.Polygon(r) for name in ("cut-1-inner", "cut-2-outer")
                    if name in layers for r in layers[name].shapes[0].rings()]
        length += sum(p.exterior.length for p in outlines)
        paths += len(outlines)
        if engraved:  # every number stroke inside a piece's outline on its sheet
            strokes = shapely.linestrings(layers["engrave-numbers"].shapes[0].coords,
                                          indices=np.repeat(np.arange(len(
                                              layers["engrave-numbers"].shapes[0].offsets) - 1),
                                              np.diff(layers["engrave-numbers"].shapes[0]
                                                      .offsets)))
            small = [p for p in outlines if p.area < 0.5 * puzzle.frame.area]
            assert all(any(p.contains(st) for p in small) for st in strokes)
        here = np.array([0.0, sheet[1]])  # every sheet starts from the top-left corner
        for name in ("cut-1-inner", "cut-2-outer"):
            for ring in (layers[name].shapes[0].rings() if name in layers else []):
                travel += float(np.hypot(*(ring[0] - here)))
                here = ring[0]
    assert result.n_sheets >= 2 and numbered >= 1
    assert travel == pytest.approx(result.travel_length, rel=1e-9)
    assert length == pytest.approx(result.cut_length, rel=1e-9) and paths == result.n_paths
