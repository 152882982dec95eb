"""The separate cut uses the room the frame leaves (its hole, and the bays between a frame
part's outline and its rectangle) before it starts a new sheet: pieces keep the spacing from
the frame and from each other, stay on the sheet, are cut before the hole that frees them, and
a piece left on the last sheet has no place in an earlier frame's room, found by a brute-force
search with shapely that shares nothing with the packer's grid."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st

from tests.built_puzzles import pentagon_puzzle
from weavecut.layout import nesting
from weavecut.layout.lasersetup import laser
from weavecut.puzzle import files as pf
from weavecut.puzzle.frame import split_frame

KERF, SPACING, MARGIN = 0.2, 2.0, 5.0  # separate_cut's defaults: spacing = max(2 mm, kerf)
DEFAULT = (4, 500.0, (800.0, 500.0), False)  # the default puzzle (jigsaw-50cm-poplar)
SMALL = (4, 500.0, (600.0, 400.0), True)  # jigsaw-small-sheets: the frame in parts


def _cut(levels, size, sheet, split):
    puzzle = pentagon_puzzle(levels, size)
    parts = split_frame(puzzle.frame, puzzle.outer, sheet, MARGIN, KERF) if split else None
    return puzzle, parts, pf.separate_cut(puzzle, laser(), KERF, sheet, frame_parts=parts)


def _sheets(result):
    """Per sheet: (frame parts, pieces) as shapely polygons with holes, read from the cut
    layers (a ring inside another's area is its hole when it is the frame's)."""
    out = []
    for parts in pf.nested_parts(result):
        rings = sorted(parts, key=lambda p: -p.area)
        frames, pieces = [], []
        for r in rings:
            outer = [f for f in frames if f.contains(r)]
            if outer:  # the frame's hole
                k = frames.index(outer[0])
                frames[k] = shapely.Polygon(frames[k].exterior, [*frames[k].interiors,
                                                                 r.exterior])
            elif r.area > 20 * min(p.area for p in parts):
                frames.append(r)
            else:
                pieces.append(r)
        out.append((frames, pieces))
    return out


@pytest.mark.parametrize("case", [DEFAULT, SMALL], ids=["default", "small sheets"])
def test_pieces_keep_the_spacing_from_the_frame_and_each_other_on_the_sheet(case):
    puzzle, _, result = _cut(*case)
    sheet = case[2]
    n = 0
    for frames, pieces in _sheets(result):
        every = np.array(frames + pieces, dtype=object)
        assert shapely.box(MARGIN, MARGIN, sheet[0] - MARGIN, sheet[1] - MARGIN).buffer(
            1e-9).covers(shapely.union_all(every))
        tree = shapely.STRtree(every)
        a, b = tree.query(every, predicate="dwithin", distance=SPACING - 1e-6)
        assert not (a < b).any(), "two parts closer than the spacing"
        n += len(pieces)
    assert n == puzzle.n_pieces


@pytest.mark.parametrize("case", [DEFAULT, SMALL], ids=["default", "small sheets"])
def test_the_frames_room_is_used_before_a_new_sheet(case):
    """Fewer sheets than the skyline alone (default: 2 -> 1; small sheets 3 -> 2), pieces
    inside the frame's rectangle, and no piece of the last sheet fits an earlier frame's room
    (the brute-force search below)."""
    puzzle, parts, result = _cut(*case)
    frames = np.array([puzzle.frame] if parts is None else parts, dtype=object)
    grown = np.concatenate([nesting.offset(frames, KERF), nesting.offset(puzzle.pieces, KERF)])
    alone = nesting.nest(grown, case[2], SPACING, MARGIN, rooms=np.zeros(len(grown), bool))
    assert result.n_sheets < alone.n_sheets
    sheets = _sheets(result)
    in_room = sum(f.envelope.contains(p) for frames_, pieces in sheets for f in frames_
                  for p in pieces)
    assert in_room > 0
    last = sheets[-1][1]
    if result.n_sheets == 1:
        return
    smallest = min(last, key=lambda p: (p.envelope.area, p.bounds))
    for frames_, pieces in sheets[:-1]:
        for f in frames_:
            spot = _brute_force_spot(f, [p for p in pieces if f.envelope.intersects(p)],
                                     smallest)
            assert spot is None, f"a piece of the last sheet fits at {spot} on an earlier sheet"


def _brute_force_spot(frame, pieces, piece, step: float = 1.0, slack: float = 2.0):
    """A lower-left corner where ``piece``'s box, grown by half the spacing and ``slack``
    more, lies in the frame's rectangle, SPACING clear of the frame and of the boxes of the
    ``pieces`` already there (grown alike), on a ``step`` grid; None if there is none. The
    slack covers the packer's grid: a spot found here is one the packer's grid sees too."""
    x0, y0, x1, y1 = frame.bounds
    room = shapely.difference(shapely.box(x0, y0, x1, y1), frame.buffer(SPACING / 2))
    taken = shapely.union_all([shapely.box(*p.bounds).buffer(SPACING / 2 + slack,
                                                            join_style="mitre")
                               for p in pieces])
    free = shapely.difference(room, taken)
    px0, py0, px1, py1 = piece.bounds
    w, h = px1 - px0 + SPACING + 2 * slack, py1 - py0 + SPACING + 2 * slack
    xs, ys = np.meshgrid(np.arange(x0, x1 - w, step), np.arange(y0, y1 - h, step))
    boxes = shapely.box(xs.ravel(), ys.ravel(), xs.ravel() + w, ys.ravel() + h)
    fits = np.flatnonzero(shapely.covers(free, boxes))
    return None if not len(fits) else (xs.ravel()[fits[0]], ys.ravel()[fits[0]])


def test_pieces_in_the_hole_are_cut_before_the_hole():
    """A piece inside the frame's hole is cut before the hole's outline frees its slug."""
    _, _, result = _cut(*DEFAULT)
    for sheet in result.drawing.sheets:
        rings = [shapely.Polygon(r) for layer in sheet.layers if layer.name == "cut-1-inner"
                 for shape in layer.shapes for r in shape.rings()]
        holes = [k for k, r in enumerate(rings) if r.area > 20 * min(x.area for x in rings)]
        assert holes
        for k in holes:
            inside = [j for j, r in enumerate(rings) if j != k and rings[k].contains(r)]
            assert inside and max(inside) < k


@settings(max_examples=25, deadline=None)
@given(st.floats(60, 160), st.floats(0.3, 0.8),
       st.lists(st.tuples(st.floats(4, 40), st.floats(4, 40)), min_size=1, max_size=60),
       st.floats(0.5, 3.0))
def test_a_frame_with_a_hole_takes_boxes_apart_and_inside(size, hole, boxes, spacing):
    """Random frames (a square with a round hole) and boxes: every box inside the sheet, no two
    parts nearer than the spacing (a box in the hole keeps it from the frame too)."""
    sheet = (size * 1.5 + 20, size + 20)
    frame = shapely.box(0, 0, size, size).difference(
        shapely.Point(size / 2, size / 2).buffer(size * hole / 2))
    parts = np.array([frame] + [shapely.box(0, 0, w, h) for w, h in boxes], dtype=object)
    placement = nesting.nest(parts, sheet, spacing, MARGIN)
    placed = placement.apply(parts)
    for s in range(placement.n_sheets):
        on = placed[placement.sheet == s]
        assert shapely.box(MARGIN, MARGIN, sheet[0] - MARGIN, sheet[1] - MARGIN).buffer(
            1e-9).covers(shapely.union_all(on))
        a, b = shapely.STRtree(on).query(on, predicate="dwithin", distance=spacing * 0.999)
        assert not (a < b).any()
    assert (placement.room_of[1:] == 0).any() == (placement.room_of[1:] >= 0).any()
