"""No number on a painting guide crosses a dashed line (issue 29: piece 377 of the 50 cm
puzzle, turned to lie across its ring piece's hexagon line, a "7" on the dashes). A dashed line
splits a piece into the parts painted apart (the parent edge across a two-coloured piece, a
ring piece's bare hexagon off its paint); a number across it reads as split in two. Read off
the guide Drawing: each dash lengthened over the gaps beside it is the line it draws, and no
stroke of the numbers layer meets one."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from weavecut.puzzle.guide_numbers import guide_numbers
from weavecut.puzzle.guides import GAP, WORDS, guide

from tests.built_puzzles import heart_puzzle, pentagon_paint, pentagon_puzzle

DASHED = ("split-lines", "hexagon-lines")


def _crossings(sheet) -> int:
    """How many numbers of a guide sheet meet a dashed line (its dashes joined over GAP)."""
    dashes = [line for layer in sheet.layers if layer.name in DASHED for shape in layer.shapes
              for line in shape.lines()]
    a = np.array([d[0] for d in dashes])
    b = np.array([d[-1] for d in dashes])
    step = (b - a) / np.linalg.norm(b - a, axis=1)[:, None] * (GAP / 2 + 1e-6)
    lines = shapely.linestrings(np.stack([a - step, b + step], axis=1))
    words = [shapely.multilinestrings([shapely.linestrings(s) for s in shape.lines()])
             for layer in sheet.layers if layer.name == WORDS for shape in layer.shapes
             if hasattr(shape, "lines")]
    hit = shapely.STRtree(lines).query(np.array(words, dtype=object), predicate="intersects")
    return len(set(hit[0].tolist()))


@pytest.mark.parametrize("which", ["pentagon-4-50cm", "pentagon-3", "heart"])
@pytest.mark.parametrize("side", ["front", "back"])
def test_no_number_crosses_a_dashed_line(which, side):
    if which == "heart":
        puzzle, colouring = heart_puzzle()
    else:
        levels, size = (4, 500.0) if which.endswith("50cm") else (3, 300.0)
        puzzle, colouring = pentagon_puzzle(levels, size), pentagon_paint(levels, size)
    numbers = guide_numbers(puzzle, colouring, side)
    sheet = guide(puzzle, colouring, side, numbers).sheets[0]
    assert any(layer.name in DASHED for layer in sheet.layers)
    assert _crossings(sheet) == 0
