"""``guide_numbers`` fits a number without room round it, and into a ring piece's hexagon or
whole piece, only for the pieces that can still take one (the others never look at those
fits): the numbers, inks and plates must be exactly those of fitting every candidate for every
piece, as the choice's rules read (``eager`` below, the same steps without the shortcut)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from weavecut.layout.labels import MIN_CAP
from weavecut.puzzle import guide_numbers as gn
from weavecut.puzzle.files import piece_texts

from tests.built_puzzles import heart_puzzle, pentagon_paint, pentagon_puzzle


def eager(puzzle, colouring, side) -> tuple:
    """(heights, centres, angles, inks, plated): every candidate fitted for every piece, with
    room round the number and without, then chosen on the paint first, at MIN_CAP (a ring
    piece's paint down to RING_CAP), then at LEAST."""
    texts = piece_texts(puzzle.n_pieces)
    candidates = gn._candidates(puzzle, colouring, side)
    painted = len(candidates) - 2 * bool((puzzle.hexagons != None).any())  # noqa: E711
    splits = gn.split_lines(puzzle, colouring, side)
    fits = [(gn._off_the_splits(gn._fit(r, texts, pad), texts, splits),
             [gn._ink(f) for f in fills], pad)
            for r, fills, pad in candidates + [(r, f, 0.0) for r, f, _ in candidates]]
    on_paint = fits[:painted] + fits[len(candidates):len(candidates) + painted]
    chosen = gn._unchosen(len(texts))
    ring = puzzle.hexagons != None  # noqa: E711
    gn._choose(on_paint, MIN_CAP, chosen)
    gn._choose(on_paint, gn.RING_CAP, chosen, ring, plates=False)  # a ring piece's paint
    for floor in (MIN_CAP, gn.LEAST):
        for group in (on_paint, fits)[floor == MIN_CAP:]:
            gn._choose(group, floor, chosen)
    return chosen


PUZZLES = {"pentagon level 4": lambda: (pentagon_puzzle(4, 500.0), pentagon_paint(4, 500.0)),
           "pentagon level 3, small": lambda: (pentagon_puzzle(3, 160.0),
                                               pentagon_paint(3, 160.0)),
           "heart": heart_puzzle}


@pytest.mark.parametrize("name", PUZZLES)
@pytest.mark.parametrize("side", ["front", "back"])
def test_numbers_as_if_every_fit_were_made(name, side):
    puzzle, colouring = PUZZLES[name]()
    numbers = gn.guide_numbers(puzzle, colouring, side)
    heights, centres, angles, inks, plated = eager(puzzle, colouring, side)
    np.testing.assert_array_equal(numbers.labels.heights, heights)
    np.testing.assert_array_equal(numbers.labels.centres, centres)
    np.testing.assert_array_equal(numbers.labels.angles, angles)
    assert numbers.inks.tolist() == inks.tolist()
    assert (numbers.plates != None).tolist() == plated.tolist()  # noqa: E711


@given(st.lists(st.lists(st.integers(1, 4), min_size=0, max_size=4), min_size=1, max_size=6))
def test_largest_parts_as_python_max_takes_them(sizes):
    """Each geometry's largest part, the first of equal ones (as ``max`` takes it), itself
    where it has none (an empty one)."""
    geoms = np.array([shapely.MultiPolygon([shapely.box(3 * k, 0, 3 * k + s, s)
                                            for k, s in enumerate(row)]) if row
                      else shapely.Polygon() for row in sizes], dtype=object)
    want = [max(shapely.get_parts(g), key=shapely.area, default=g) for g in geoms.tolist()]
    got = gn._largest_parts(geoms)
    assert shapely.to_wkb(got).tolist() == shapely.to_wkb(np.array(want, dtype=object)).tolist()
