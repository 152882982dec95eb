"""Every number on a painting guide can be found, read from the drawn guide by an oracle of its
own (tests/puzzle/word_oracle.py): its ink has WCAG contrast at least 4.5 with every fill
under its strokes (ring hexagons, plates and paper included), it keeps clear of every other
number (its plate too) and stands further from the next number's ink than its digits do from
each other, it reads upright on the page as printed (the back is mirrored, its numbers not), and
it is one tight word: the font's own strokes of its text, turned and scaled as a whole, with
no gap inside it wider than a digit's spacing. Checked on the default puzzle, the heart
recipe's, both sides, and random puzzles; the summary's figures agree with the oracle."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from weavecut import inputs
from weavecut.cli import cli
from weavecut.layout import label_checks
from weavecut.layout.contrast import MIN_CONTRAST
from weavecut.layout.labels import MIN_CAP
from weavecut.puzzle.colouring import colour_puzzle, palette_names
from weavecut.puzzle.guide_numbers import LEAST, RING_CAP, guide_numbers, warnings
from weavecut.puzzle.guides import colour_key, guide, printed
from weavecut.puzzle.pieces import build_puzzle
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette

from tests.built_puzzles import heart_puzzle, pentagon_paint, pentagon_puzzle
from tests.puzzle.word_oracle import contrasts, gaps, pose, split_mark, spread, words

SPREAD = 0.4  # per cap height: a digit's spacing is 2/7 of it, a tabular '1' left 4/7
WORD_GAP = 0.3  # per cap height: two numbers stand further apart than a digit's spacing


def _puzzles():
    return {"default": lambda: (pentagon_puzzle(4, 500.0), pentagon_paint(4, 500.0)),
            "heart": heart_puzzle}


def check_guide(puzzle, colouring, side) -> dict:
    """Assert every property on ``side``'s guide; returns the drawn sheet and figures."""
    numbers = guide_numbers(puzzle, colouring, side)
    sheet = guide(puzzle, colouring, side, numbers).sheets[0]
    drawn = words(sheet)
    heights = numbers.labels.heights
    shown = np.flatnonzero(heights > 0)
    assert len(drawn) == len(shown)
    c = contrasts(sheet)
    assert c.min(initial=21.0) >= MIN_CONTRAST, shown[c < MIN_CONTRAST] + 1
    sizes = []
    for k, (word, _) in zip(shown.tolist(), drawn):
        digits, _ = split_mark(word, str(k + 1))  # its mark: tests/puzzle/test_turned_numbers
        angle, height, misfit = pose(digits, str(k + 1))
        assert misfit < 1e-6 * max(height, 1.0), k + 1  # the text's strokes, not mirrored
        assert abs(angle) <= 90.0 + 1e-6, (k + 1, angle)  # upright as printed
        assert spread(digits, angle, height) <= SPREAD, k + 1  # digits together
        assert height >= LEAST - 1e-6
        sizes.append(height)
    g, ink = gaps(sheet), gaps(sheet, plates=False)
    assert (g >= label_checks.MIN_GAP).all(), shown[g < label_checks.MIN_GAP] + 1
    want = WORD_GAP * np.array(sizes)  # ink to ink: further than digits stand apart
    assert (ink >= want).all(), shown[ink < want] + 1
    # a number under MIN_CAP (a ring piece's on its paint: under RING_CAP, its size by design)
    # or none at all: the pieces are named, never left out silently
    said = " ".join(warnings(numbers, side))
    least = np.where(puzzle.hexagons != None, RING_CAP, MIN_CAP)  # noqa: E711
    for k in np.flatnonzero(heights < least - 1e-9)[:3].tolist():
        assert f" {k + 1}," in said.replace("pieces ", " ").replace(" are", ",")
    assert bool(said) == bool((heights < least - 1e-9).any())
    return {"sheet": sheet, "contrast": c.min(initial=21.0), "gap": g.min(initial=np.inf),
            "numbers": numbers}


@pytest.mark.parametrize("side", ["front", "back"])
@pytest.mark.parametrize("name", ["default", "heart"])
def test_every_number_reads_on_what_is_under_it_apart_and_upright(name, side):
    puzzle, colouring = _puzzles()[name]()
    seen = check_guide(puzzle, colouring, side)
    # the library's figures (puzzle --json) agree with the oracle's
    figures = label_checks.figures([seen["sheet"]])
    assert figures["min_label_contrast"] == pytest.approx(seen["contrast"], abs=0.01)
    assert figures["min_label_gap_mm"] == pytest.approx(seen["gap"], abs=0.01)
    assert figures["labels_under_contrast"] == figures["labels_too_close"] == 0


def _shapes(sheet) -> set:
    """Every word of the sheet as its strokes relative to its first point (mm, rounded)."""
    return {(len(w.coords), np.round(w.coords - w.coords[0], 6).tobytes())
            for w, _ in words(sheet)}


@pytest.mark.parametrize("side", ["front", "back"])
@pytest.mark.parametrize("name", ["default", "heart"])
def test_printed_pages_show_every_number_whole_and_readable(name, side):
    """Tiled on A4 (after the colour key), every number is whole on some page, none is cut
    at a page's edge, and every label of every page (numbers, the key's lines, the page
    marks) reads on what is under it and keeps 0.5 mm from the next."""
    puzzle, colouring = _puzzles()[name]()
    sheet = guide(puzzle, colouring, side, guide_numbers(puzzle, colouring, side))
    pages = printed(sheet, colour_key(puzzle, colouring, side), (210.0, 297.0))
    on_pages = set().union(*(_shapes(p) for p in pages.sheets))
    assert _shapes(sheet.sheets[0]) <= on_pages  # whole somewhere
    assert on_pages <= _shapes(sheet.sheets[0])  # never a part of one
    figures = label_checks.figures(pages.sheets)
    assert figures["labels_under_contrast"] == figures["labels_too_close"] == 0
    assert figures["min_label_contrast"] >= MIN_CONTRAST
    assert figures["min_label_gap_mm"] >= label_checks.MIN_GAP


@pytest.mark.slow
@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(["pentagon", "square-grid", "ngon", "tiling-8-4", "hex-grid"]),
       levels=st.integers(2, 3), size=st.floats(150.0, 600.0), frame=st.floats(8.0, 30.0),
       pal=st.sampled_from(["puzzle", "maritime-12", "maritime-4"]),
       side=st.sampled_from(["front", "back"]))
def test_random_puzzles_keep_their_numbers_readable(name, levels, size, frame, pal, side):
    puzzle = build_puzzle(subdivide(inputs.get(name), levels), size, frame,
                          "diagonal" if name == "pentagon" else "width")
    p = palette(pal)
    check_guide(puzzle, colour_puzzle(puzzle, p, palette_names(pal, p)), side)


def test_the_summary_reports_the_smallest_contrast_and_gap(tmp_path):
    out = tmp_path / "p"
    result = CliRunner().invoke(cli, ["puzzle", "-o", str(out), "--levels", "2",
                                      "--mode", "shared", "--json"])
    assert result.exit_code == 0, result.output
    info = json.loads(result.stdout)
    puzzle, colouring = pentagon_puzzle(2, 500.0), pentagon_paint(2, 500.0)
    sheets = [check_guide(puzzle, colouring, side)["sheet"] for side in ("front", "back")]
    assert info["min_label_contrast"] == round(min(contrasts(s).min() for s in sheets), 2)
    assert info["min_label_gap_mm"] == pytest.approx(min(gaps(s).min() for s in sheets),
                                                     abs=0.006)
    assert info["min_label_contrast"] >= MIN_CONTRAST and info["min_label_gap_mm"] >= 0.5


def test_numbers_too_large_for_a_tiny_puzzle_shrink_or_are_named():
    """At 10 cm the default puzzle's level-3 pieces are a few millimetres across: numbers that
    do not fit at 2.5 mm are printed smaller, down to 1.5 mm, where one reads (on a plate
    where no ink reads on the paint), and the pieces without room even for that have none;
    both kinds are named in a warning, and every property holds for what is printed."""
    puzzle = build_puzzle(subdivide(inputs.get("pentagon"), 3), 100.0, 10.0)
    p = palette("puzzle")
    colouring = colour_puzzle(puzzle, p, palette_names("puzzle", p))
    for side in ("front", "back"):
        numbers = check_guide(puzzle, colouring, side)["numbers"]
        h = numbers.labels.heights
        assert ((h > 0) & (h < MIN_CAP)).any() and (h == 0).any()
        said = warnings(numbers, side)
        assert len(said) == 2 and "smaller" in said[0] and "without one" in said[1]
