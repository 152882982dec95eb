"""The painting guides checked from what they draw: every number's strokes lie inside its own
piece (placed, and mirrored on the back), one word per piece,
split lines are dashes of the stated length along the parent edge, the crosshairs register
front and back, and the colour key lists for each paint exactly the pieces painted with it.
The puzzles and their paint are made once per process (tests/built_puzzles.py); the guides
in every test."""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np
import pytest
import shapely

from weavecut.layout.contrast import BLACK, WHITE
from weavecut.layout.labels import text_box
from weavecut.puzzle import files as pf
from weavecut.puzzle.colouring import UNPAINTED
from weavecut.puzzle.guide_numbers import guide_numbers
from weavecut.puzzle.guides import (DASH, GAP, colour_key, guide, painted, piece_halves,
                                    split_ends)
from weavecut.puzzle.pieces import OCTAGON

from tests.built_puzzles import pentagon_paint, pentagon_puzzle


def _coloured(levels=3):
    return pentagon_puzzle(levels), pentagon_paint(levels)


def _layer(sheet, name):
    return next(layer for layer in sheet.layers if layer.name == name)


def _placed(puzzle, sheet, side):
    """The pieces as the guide places them (shifted; the back mirrored)."""
    _, _, shift = pf.placement(puzzle)

    def move(xy):
        xy = xy + shift
        return np.column_stack([sheet.width - xy[:, 0], xy[:, 1]]) if side == "back" else xy

    return shapely.transform(puzzle.pieces, move)


@pytest.mark.parametrize("side", ["front", "back"])
def test_numbers_sit_inside_their_piece_one_word_each(side):
    """Word k of the numbers layer lies inside piece k (placed, mirrored on the back), in
    black or white, and draws str(k + 1): as many strokes as the unplaced number has (what
    is under it and how it reads: tests/puzzle/test_guide_numbers.py)."""
    puzzle, colouring = _coloured()
    numbers = guide_numbers(puzzle, colouring, side)
    sheet = guide(puzzle, colouring, side, numbers).sheets[0]
    pieces = _placed(puzzle, sheet, side)
    words = [s for s in _layer(sheet, "numbers").shapes if hasattr(s, "offsets")]
    assert len(words) == puzzle.n_pieces  # every piece numbered
    for k, shape in enumerate(words):
        assert shape.style.stroke in (BLACK, WHITE)
        strokes = shapely.linestrings(shape.coords, indices=np.repeat(
            np.arange(len(shape.offsets) - 1), np.diff(shape.offsets)))
        assert shapely.within(strokes, pieces[k]).all()
        _, offsets = numbers.labels.strokes(pick=[k])
        assert len(shape.offsets) == len(offsets)


def test_split_lines_are_dashes_along_the_parent_edge_of_two_coloured_pieces():
    puzzle, colouring = _coloured()
    sheet = guide(puzzle, colouring, "front").sheets[0]
    _, _, shift = pf.placement(puzzle)
    u, w = split_ends(puzzle)
    two = colouring.front[:, 0] != colouring.front[:, 1]
    assert two.any() and not two.all()
    chords = shapely.linestrings(np.stack([u[two], w[two]], axis=1) + shift)
    lines = _layer(sheet, "split-lines").shapes[0]
    dashes = np.asarray(lines.lines())
    assert dashes.shape[1:] == (2, 2)
    # every dash on one chord; per chord: dashes of DASH mm, GAP mm apart, centred
    tree = shapely.STRtree(chords)
    dash_lines = shapely.linestrings(dashes)
    where, chord = tree.query(dash_lines, predicate="dwithin", distance=1e-9)
    assert len(np.unique(where)) == len(dashes)
    assert sorted(set(chord.tolist())) == list(range(len(chords)))
    for c in range(len(chords)):
        mine = dashes[where[chord == c]]
        start = np.asarray(chords[c].coords[0])
        along = np.sort(np.hypot(*(mine - start).transpose(2, 0, 1)), axis=1)
        along = along[np.argsort(along[:, 0])]
        total = chords[c].length
        if total >= DASH:
            np.testing.assert_allclose(along[:, 1] - along[:, 0], DASH, atol=1e-9)
            np.testing.assert_allclose(along[1:, 0] - along[:-1, 1], GAP, atol=1e-9)
            assert along[0, 0] == pytest.approx(total - along[-1, 1], abs=1e-9)  # centred
            assert along[0, 0] >= -1e-9 and along[-1, 1] <= total + 1e-9
            assert along[0, 0] < DASH + GAP  # as many dashes as fit
    assert lines.style.stroke == "#000000"


def test_crosshairs_register_front_and_back_at_the_sheet_corners():
    puzzle, colouring = _coloured(2)
    front = guide(puzzle, colouring, "front").sheets[0]
    back = guide(puzzle, colouring, "back").sheets[0]
    marks = [np.asarray(_layer(s, "registration").shapes[0].lines()) for s in (front, back)]
    assert marks[0].shape == (8, 2, 2)
    centres = marks[0].mean(axis=1)
    expected = [(5.0, 5.0), (front.width - 5.0, 5.0), (5.0, front.height - 5.0),
                (front.width - 5.0, front.height - 5.0)]
    np.testing.assert_allclose(centres, np.repeat(expected, 2, axis=0), atol=1e-9)
    np.testing.assert_allclose(np.hypot(*(marks[0][:, 1] - marks[0][:, 0]).T), 8.0)
    horizontal = marks[0][0::2]
    assert (horizontal[:, 0, 1] == horizontal[:, 1, 1]).all()
    vertical = marks[0][1::2]
    assert (vertical[:, 0, 0] == vertical[:, 1, 0]).all()
    # the back's marks, mirrored about the sheet's centre, are the front's
    mirrored = marks[1].reshape(-1, 2) * [-1, 1] + [back.width, 0]
    key = {tuple(np.round(p, 9)) for p in marks[0].reshape(-1, 2)}
    assert {tuple(np.round(p, 9)) for p in mirrored} == key


@pytest.mark.parametrize("side", ["front", "back"])
def test_guide_paint_is_the_colouring_on_the_placed_pieces(side):
    """Every painted polygon lies in its piece (placed, mirrored on the back) and wears the
    colour of that piece's half; the ring hexagons are drawn unpainted; the title names the
    level and the mirror."""
    puzzle, colouring = _coloured()
    drawing = guide(puzzle, colouring, side)
    sheet = drawing.sheets[0]
    pieces = _placed(puzzle, sheet, side)
    paint = _layer(sheet, "paint").shapes[0]
    polys = paint.to_shapely()
    fills = np.array(paint.fills, dtype=object)
    where, piece = shapely.STRtree(shapely.buffer(pieces, 1e-6)).query(polys, predicate="within")
    assert len(np.unique(where)) == len(polys)
    if side == "front":
        allowed = [set(colouring.front[k]) for k in piece.tolist()]
        halves = piece_halves(puzzle)
        n = int((colouring.front[:, 0] != UNPAINTED).sum() + (
            (colouring.front[:, 1] != UNPAINTED) & ~shapely.equals(halves[:, 0], halves[:, 1])
        ).sum())
        assert len(polys) == n
    else:
        allowed = [{colouring.back[k]} for k in piece.tolist()]
        assert len(polys) == int((colouring.back != UNPAINTED).sum())
    assert all(f in ok for f, ok in zip(fills[where].tolist(), allowed))
    area = shapely.area(polys).sum()
    hexes = puzzle.hexagons[puzzle.hexagons != None].astype(object)  # noqa: E711
    assert area == pytest.approx(shapely.area(puzzle.pieces).sum() - shapely.area(hexes).sum(),
                                 rel=1e-9)
    ring = _layer(sheet, "ring-unpainted").shapes[0]
    assert set(ring.fills) == {UNPAINTED} if ring.fills else ring.style.fill == UNPAINTED
    assert len(ring.to_shapely()) == len(hexes)
    outlines = _layer(sheet, "pieces").shapes[0].to_shapely()
    assert len(outlines) == puzzle.n_pieces
    level = puzzle.levels - (side == "front")
    assert drawing.title == (f"weave-cut puzzle: {side} painting guide (level {level} weave)"
                             + (", mirrored" if side == "back" else ""))
    assert ("split-lines" in [layer.name for layer in sheet.layers]) == (side == "front")


def test_back_paint_is_each_piece_without_its_hexagon_in_its_strand_colour():
    puzzle, colouring = _coloured()
    back = painted(puzzle, colouring, "back")
    has = puzzle.hexagons != None  # noqa: E711
    expected = shapely.area(puzzle.pieces) - np.where(
        has, shapely.area(np.where(has, puzzle.hexagons, shapely.Polygon())), 0.0)
    keep = colouring.back != UNPAINTED
    np.testing.assert_allclose(shapely.area(back.polygons), expected[keep], rtol=1e-9)
    assert back.colours.tolist() == colouring.back[keep].tolist()
    assert back.piece.tolist() == np.flatnonzero(keep).tolist()
    for colour in set(back.colours.tolist()):
        assert back.pieces(colour).tolist() == (np.flatnonzero(colouring.back == colour)
                                                + 1).tolist()
        assert back.areas()[colour] == pytest.approx(expected[colouring.back == colour].sum())
    assert list(back.areas()) == list(dict.fromkeys(back.colours.tolist()))


@pytest.mark.parametrize("side", ["front", "back"])
def test_colour_key_lists_each_paints_pieces_and_area(side):
    """Read from the key's text: one row per paint in palette order, naming the paint, its hex
    code, its area in cm² and exactly the pieces painted with it; then the bare wood of the
    ring pieces' hexagons, white, naming exactly those pieces."""
    puzzle, colouring = _coloured()
    key = colour_key(puzzle, colouring, side, page=(210.0, 297.0))
    texts = [s.text for sheet in key.sheets for layer in sheet.layers for s in layer.shapes
             if hasattr(s, "text")]
    paint = painted(puzzle, colouring, side)
    colours = colouring.front_colours if side == "front" else colouring.back_colours
    rows = [k for k, t in enumerate(texts) if re.search(r"   #[0-9a-f]{6}   ", t)]
    assert len(rows) == len(colours)
    total = 0.0
    for colour, k in zip(colours, rows):
        name, code, area = texts[k].split("   ")
        assert (name, code) == (colouring.names[colour], colour)
        expected = shapely.area(paint.polygons[paint.colours == colour]).sum() / 100
        assert area == f"{expected:.1f} cm²"
        total += expected
        listed = []
        for t in texts[k + 1:]:
            if not re.fullmatch(r"(pieces: )?[\d ]+", t):
                break
            listed += [int(n) for n in t.removeprefix("pieces: ").split()]
        assert listed == (np.unique(paint.piece[paint.colours == colour]) + 1).tolist()
    level = puzzle.levels - (side == "front")
    assert texts[0] == (f"Colour key, {side}: {len(colours)} paints, {total:.0f} cm² painted "
                        f"(level {level} weave)")
    # swatches: one filled square per paint, 25 x 12 mm, in the paint's colour
    swatches = [s for sheet in key.sheets for layer in sheet.layers for s in layer.shapes
                if getattr(s, "fills", None)]
    ring = (np.flatnonzero(puzzle.hexagons != None) + 1).tolist()  # noqa: E711
    assert ring  # then the ring pieces' bare hexagons, white as the guide shows them
    assert [f for s in swatches for f in s.fills] == colours + [UNPAINTED]
    (k,) = [k for k, t in enumerate(texts) if t.startswith("bare wood, not painted")]
    bare = shapely.area(puzzle.hexagons[np.array(ring) - 1].astype(object)).sum() / 100
    assert texts[k].endswith(f"   {bare:.1f} cm²")
    listed = " ".join(texts[k + 1:]).removeprefix("the hexagon of pieces: ").split()
    assert [int(n) for n in listed] == ring
    for s in swatches:
        minx, miny, maxx, maxy = shapely.total_bounds(s.to_shapely())
        assert (maxx - minx, maxy - miny) == pytest.approx((25.0, 12.0))
    assert all(sheet.width == 210.0 and sheet.height == 297.0 for sheet in key.sheets)


def test_a_long_colour_key_continues_on_further_pages():
    puzzle, colouring = _coloured(4)
    key = colour_key(puzzle, colouring, "back", page=(210.0, 148.0), margin=15.0)
    assert len(key.sheets) >= 2
    assert [s.name for s in key.sheets] == [f"back colour key {k + 1}"
                                            for k in range(len(key.sheets))]
    for sheet in key.sheets:  # every page starts with the heading, rows stay above the margin
        texts = [s for layer in sheet.layers for s in layer.shapes if hasattr(s, "text")]
        assert texts[0].text.startswith("Colour key, back: ")
        assert min(t.y for t in texts) >= 15.0
    rows = sum(1 for sheet in key.sheets for layer in sheet.layers for s in layer.shapes
               if getattr(s, "fills", None))
    assert rows == len(colouring.back_colours) + 1  # and the bare hexagons


def test_only_octagons_have_two_front_halves_painted_apart():
    puzzle, colouring = _coloured()
    front = painted(puzzle, colouring, "front")
    counts = np.bincount(front.piece, minlength=puzzle.n_pieces)
    octagon = puzzle.kinds == OCTAGON
    assert (counts[~octagon] == 1).all() and (counts[octagon] == 2).all()


@pytest.mark.parametrize("page", [(210.0, 297.0), (148.0, 105.0)])
def test_colour_key_rows_stack_without_overlap_beside_their_swatches(page):
    """Read from the key's boxes: on every page the heading is above every row; a row's texts
    start right of its swatch, its name line lies level with the swatch and its piece lines
    below it; no two texts and no text and swatch overlap; rows stay above the bottom margin."""
    puzzle, colouring = _coloured(4)
    margin = 12.0
    for sheet in colour_key(puzzle, colouring, "front", page=page, margin=margin).sheets:
        shapes = [s for layer in sheet.layers for s in layer.shapes]
        texts = [s for s in shapes if hasattr(s, "text")]
        swatches = [shapely.Polygon(s.rings()[0]) for s in shapes if getattr(s, "fills", None)]
        boxes = [text_box(t) for t in texts]
        assert texts[0].text.startswith("Colour key, front: ")
        assert all(boxes[0].bounds[1] > s.bounds[3] for s in swatches)
        assert boxes[0].bounds[2] <= page[0] - margin + 1e-6
        everything = boxes + swatches
        for i, a in enumerate(everything):
            for b in everything[i + 1:]:
                assert a.intersection(b).area < 1e-9
        rows = [k for k, t in enumerate(texts) if re.search(r"   #[0-9a-f]{6}   ", t.text)
                or t.text.startswith("bare wood")]
        assert len(rows) == len(swatches)
        for k, end, swatch in zip(rows, rows[1:] + [len(texts)], swatches):
            name, following = boxes[k], boxes[k + 1:end]  # the name, then the piece lines
            assert following and all(re.fullmatch(r"(pieces: |the hexagon of pieces: )?[\d ]+",
                                                  t.text) for t in texts[k + 1:end])
            assert name.bounds[0] > swatch.bounds[2]  # right of the swatch
            assert swatch.bounds[1] <= name.bounds[1] and name.bounds[3] <= swatch.bounds[3]
            tops = [b.bounds[3] for b in [name] + following]
            assert tops == sorted(tops, reverse=True)
            assert all(b.bounds[0] == pytest.approx(name.bounds[0]) for b in following)
        assert min(min(b.bounds[1] for b in boxes), min(s.bounds[1] for s in swatches)) \
            >= margin - 1e-6


def test_a_sides_paint_is_made_once_and_kept_read_only():
    # the guide and the colour key of a side share it; another colouring gets its own
    puzzle, colouring = _coloured()
    first = painted(puzzle, colouring, "back")
    assert painted(puzzle, colouring, "back") is first
    assert not any(a.flags.writeable for a in (first.polygons, first.colours, first.piece))
    other = replace(colouring, back=np.full(puzzle.n_pieces, "#123456", dtype=object))
    assert set(painted(puzzle, other, "back").colours.tolist()) == {"#123456"}
