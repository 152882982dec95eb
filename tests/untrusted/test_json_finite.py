"""JSON is JSON: every writer refuses NaN and Infinity (``allow_nan=False``, checked in the
sources), and the figures that have no value say so as null (the smallest colour difference
of a one-colour puzzle, the standard error of a fit through two box sizes) or are skipped
with the reason (a dimension from a single box size)."""

from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from weavecut.analysis.boxcount import box_counting
from weavecut.puzzle import workshop
from weavecut.puzzle.colouring import colour_puzzle
from weavecut.weave.colour import Palette

from tests.built_puzzles import pentagon_puzzle

from .helpers import run, strict_json

SRC = Path(__file__).resolve().parents[2] / "src" / "weavecut"


def lax_json_calls(text: str) -> list[int]:
    """Lines of the ``json.dump``/``json.dumps`` calls in ``text`` without
    ``allow_nan=False``."""
    lines = []
    for node in ast.walk(ast.parse(text)):
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                and node.func.attr in ("dump", "dumps")
                and isinstance(node.func.value, ast.Name) and node.func.value.id == "json"):
            strict = any(k.arg == "allow_nan" and isinstance(k.value, ast.Constant)
                         and k.value.value is False for k in node.keywords)
            if not strict:
                lines.append(node.lineno)
    return lines


def test_every_json_writer_refuses_nan():
    lax = {str(p.relative_to(SRC)): lines for p in sorted(SRC.rglob("*.py"))
           if (lines := lax_json_calls(p.read_text(encoding="utf-8")))}
    assert lax == {}
    assert sum("json.dump" in p.read_text(encoding="utf-8") for p in SRC.rglob("*.py")) >= 8


@pytest.mark.parametrize("text, found", [
    ("import json\njson.dumps(x)\n", [2]),
    ("import json\nf(json.dump(x, f, indent=2))\n", [2]),
    ("import json\njson.dumps(x, allow_nan=True)\n", [2]),
    ("import json\njson.dumps(x, allow_nan=0 == 1)\n", [2]),
    ("import json\njson.dumps(x, allow_nan=False)\njson.loads(y)\n", []),
])
def test_the_scan_sees_every_lax_call(text, found):
    """Plant the bug: calls without the keyword, or with another value, are found."""
    assert lax_json_calls(text) == found


# -- the reported case: a one-colour palette ---------------------------------------------------

def test_one_colour_puzzle_has_no_smallest_difference(tmp_path):
    pal = tmp_path / "one.toml"
    pal.write_text('name = "one"\ndescription = "one paint"\nfamilies = [["#336699"]]\n')
    result = run("puzzle", "--levels", "2", "--palette", pal, "-o", tmp_path / "pz", "--json")
    assert result.exit_code == 0, result.output
    printed = strict_json(result.output[result.output.index("{"):])
    written = strict_json((tmp_path / "pz" / "puzzle-summary.json").read_bytes())
    for info in (printed, written):
        assert info["smallest_delta_e"] is None
        assert info["smallest_delta_e_reason"] == "no two different paints touch on the front"
    assert result.output.count("Infinity") == 0


def test_summary_text_without_a_smallest_difference():
    info = {"front_colours": 1, "back_colours": 1, "smallest_delta_e": None,
            "single_coloured_pieces": 4, "pieces_by_type": {}, "piece_across_mm": [1, 2],
            "levels": 2, "pieces": 4, "piece_width_min_mm": 1, "ring_hexagons_in_frame": 0,
            "frame_diagonal_mm": 3, "frame_mm": [2, 2], "modes": {}, "speed_mm_s": 7}
    assert ("paints: front 1, back 1; no two different paints touch on the front; 4 "
            "single-coloured pieces on the front") in workshop.summary_text(info).splitlines()


colours = st.sampled_from(["#000000", "#000001", "#336699", "#ff0000", "#ffffff", "#123456"])


@given(families=st.lists(st.lists(colours, min_size=1, max_size=3).map(tuple), min_size=1,
                         max_size=4))
def test_puzzle_summary_is_strict_json_for_any_palette(families):
    """Null exactly when no two different paints touch, a finite number otherwise."""
    puzzle = pentagon_puzzle(2)
    colouring = colour_puzzle(puzzle, Palette("p", tuple(families)))
    info = workshop.summary(puzzle, {}, 7.0, colouring)
    strict_json(json.dumps(info, allow_nan=False))
    if len(colouring.touching):
        assert isinstance(info["smallest_delta_e"], float) and info["smallest_delta_e"] >= 0
        assert "smallest_delta_e_reason" not in info
    else:
        assert info["smallest_delta_e"] is None and info["smallest_delta_e_reason"]
    if len({c for f in families for c in f}) == 1:
        assert info["smallest_delta_e"] is None


# -- box counting through too few sizes --------------------------------------------------------

def test_fractal_of_a_coarse_boundary_is_strict_json():
    """Two box sizes: the slope has no standard error and the finer half no slope."""
    result = run("fractal", "square-grid", "--levels", "3", "--json")
    assert result.exit_code == 0, result.output
    box = strict_json(result.output)["boundary_box_counting"]
    assert len(box["sizes"]) == 2
    assert box["stderr"] is None and box["halves"][1] is None
    assert isinstance(box["halves"][0], float)
    text = run("fractal", "square-grid", "--levels", "3").output
    assert "\u00b1 - (least-squares" in text and "nan" not in text


@given(n=st.integers(1, 8), scale=st.floats(0.02, 0.5))
def test_box_counting_is_strict_json_for_any_number_of_sizes(n, scale):
    segments = [[[0.0, 0.0], [1.0, 0.0]], [[1.0, 0.0], [1.0, 1.0]], [[1.0, 1.0], [0.3, 0.6]]]
    sizes = [scale / 2 ** (k / 2) for k in range(n)]
    if n < 2:  # no slope through one point: refused, and the report says it was skipped
        with pytest.raises(ValueError, match="too few segments for box counting"):
            box_counting(segments, sizes)
        return
    box = box_counting(segments, sizes)
    strict_json(json.dumps(box, allow_nan=False))
    assert (box["stderr"] is None) == (n < 3)
    assert [h is None for h in box["halves"]] == [False, n < 3]


def test_fractal_of_a_boundary_with_one_box_size_is_skipped():
    """The boundary of a single triangle at level 4 spans one box size: its dimension was
    NaN."""
    result = run("fractal", "triangle-grid:1x1", "--levels", "4", "--json")
    assert result.exit_code == 0, result.output
    box = strict_json(result.output)["boundary_box_counting"]
    assert box == {"skipped": "the curve has too few segments for box counting (1 box size "
                              "between its extent/32 and two segments); use more levels"}
