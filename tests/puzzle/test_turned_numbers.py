"""A number that reads as another number turned half a turn (6/9, 16/91, 86/98, ...) carries a
mark, as on bingo balls: an underline, on the painting guides and on the engraved wood alike;
no other number does. The oracle lists the ambiguous numbers itself (digit strings turned with
0, 1, 8 kept and 6, 9 swapped, read backwards; a different number without a leading 0) and
reads the marks from the Drawings alone (tests/puzzle/word_oracle.py: the strokes a word has
beyond the font's strokes of its digits, read as an underline)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from weavecut.layout.drawing import Polylines
from weavecut.layout.lasersetup import laser
from weavecut.puzzle import files as pf
from weavecut.puzzle.guide_numbers import guide_numbers
from weavecut.puzzle.guides import guide

from tests.built_puzzles import heart_puzzle, pentagon_paint, pentagon_puzzle
from tests.puzzle.word_oracle import pose, split_mark, underlined, words

HALF_TURN = {"0": "0", "1": "1", "6": "9", "8": "8", "9": "6"}


def ambiguous(k: int) -> bool:
    """Whether k, turned half a turn, reads as a different number."""
    s = str(k)
    if any(c not in HALF_TURN for c in s):
        return False
    turned = "".join(HALF_TURN[c] for c in s[::-1])
    return turned != s and turned[0] != "0"


def test_the_oracle_lists_the_numbers_the_maker_named():
    named = [6, 9, 16, 91, 18, 81, 19, 61, 68, 89, 66, 99, 86, 98, 161, 191]
    assert all(ambiguous(k) for k in named)
    assert not any(ambiguous(k) for k in [1, 8, 10, 11, 60, 69, 88, 96, 101, 609, 12, 25])
    assert sum(ambiguous(k) for k in range(1, 100)) == 14  # 6, 9 and 12 of two digits


def _marks(sheet_words, numbers) -> dict[int, bool]:
    """{piece number: underlined} of (word, number) pairs, the word read by the oracle."""
    out = {}
    for word, k in zip(sheet_words, numbers):
        digits, mark = split_mark(word, str(k))
        angle, height, misfit = pose(digits, str(k))
        assert misfit < 1e-6 * max(height, 1.0), k  # its digits are the font's
        assert not mark or underlined(digits, mark, angle, height), k  # a mark is an underline
        out[k] = bool(mark)
    return out


def _check(marks: dict[int, bool]) -> None:
    wrong = sorted(k for k, m in marks.items() if m != ambiguous(k))
    assert not wrong, wrong


def _puzzles():
    return {"default": (pentagon_puzzle(4, 500.0), pentagon_paint(4, 500.0)),
            "heart": heart_puzzle()}


@pytest.mark.parametrize("name", ["default", "heart"])
def test_every_ambiguous_number_on_a_guide_is_underlined_and_no_other(name):
    puzzle, colouring = _puzzles()[name]
    for side in ("front", "back"):
        numbers = guide_numbers(puzzle, colouring, side)
        sheet = guide(puzzle, colouring, side, numbers).sheets[0]
        shown = np.flatnonzero(numbers.labels.heights > 0) + 1
        _check(_marks([w for w, _ in words(sheet)], shown.tolist()))


def _engraved_words(puzzle, drawing) -> tuple[list, list]:
    """The engraved words of the shared cut, each the lines whose middle lies in one piece
    (in piece order), with its piece number."""
    (layer,) = [layer for layer in drawing.sheets[0].layers if layer.name == "engrave-numbers"]
    (shape,) = layer.shapes
    shift = pf.placement(puzzle)[2]
    pieces = shapely.transform(puzzle.pieces, lambda xy: xy + shift)
    lines = shape.lines()
    mids = shapely.points([(line[0] + line[-1]) / 2 if len(line) == 2 else line.mean(axis=0)
                           for line in lines])
    hit_line, hit_piece = shapely.STRtree(pieces).query(mids, predicate="within")
    owner = np.full(len(lines), -1)
    owner[hit_line] = hit_piece
    assert (owner >= 0).all()  # every stroke lies in a piece
    out, numbers = [], []
    for k in np.unique(owner).tolist():
        mine = [lines[j] for j in np.flatnonzero(owner == k).tolist()]
        offsets = np.r_[0, np.cumsum([len(m) for m in mine])].astype(np.int64)
        out.append(Polylines(np.concatenate(mine), offsets, shape.style))
        numbers.append(k + 1)
    return out, numbers


@pytest.mark.parametrize("name", ["default", "heart"])
def test_every_ambiguous_engraved_number_is_underlined_and_no_other(name):
    puzzle, _ = _puzzles()[name]
    drawing = pf.shared_cut(puzzle, laser(), pf.piece_numbers(puzzle)).drawing
    marks = _marks(*_engraved_words(puzzle, drawing))
    assert len(marks) == puzzle.n_pieces
    _check(marks)


def test_a_missing_mark_is_caught():
    """The planted bug: the 6's underline left off; the check names it."""
    puzzle, colouring = pentagon_puzzle(2), pentagon_paint(2)
    numbers = guide_numbers(puzzle, colouring, "front")
    drawn = [w for w, _ in words(guide(puzzle, colouring, "front", numbers).sheets[0])]
    shown = (np.flatnonzero(numbers.labels.heights > 0) + 1).tolist()
    k = shown.index(6)
    drawn[k], _ = split_mark(drawn[k], "6")
    with pytest.raises(AssertionError, match=r"\[6\]"):
        _check(_marks(drawn, shown))


@given(st.integers(1, 2000))
def test_the_library_marks_what_the_oracle_lists(k):
    texts = pf.piece_texts(k)
    assert [t != str(j) for j, t in enumerate(texts, start=1)] == \
        [ambiguous(j) for j in range(1, k + 1)]
