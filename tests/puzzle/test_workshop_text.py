"""README.txt and the summary text as a maker reads them: each laser file's paragraph names its
own layers in the order they are cut and says what to keep in mind, warnings are wrapped whole
(no word or option split) under 92 columns, missing figures read "?" or 0 instead of failing,
and the summary starts with the chosen cell and level when the command chose them."""

from __future__ import annotations

import re
import textwrap

import pytest

from weavecut.puzzle import workshop

INFO = {"levels": 3, "pieces": 85, "pieces_by_type": {"octagon": 40, "enneagon": 45},
        "piece_across_mm": [20.5, 31.0], "piece_width_min_mm": 10.2,
        "ring_hexagons_in_frame": 25, "frame_diagonal_mm": 300.0, "frame_mm": [285.3, 271.3],
        "speed_mm_s": 20.0,
        "modes": {"shared": {"cut_length_m": 5.02, "travel_m": 1.0, "paths": 30, "sheets": 1,
                             "time_min": 4.5},
                  "separate": {"cut_length_m": 6.0, "travel_m": 2.0, "paths": 90,
                               "sheets": 2, "time_min": 5.5}}}
# a warning whose words (options, hyphenated file names) must not be split, long enough to wrap
WARNING = ("A: pieces 3, 7, 12 are too small for 3 mm digits; use --levels 2 or --cell 24mm, or "
           "print the guides puzzle-front-guide-a4.pdf and puzzle-back-guide-a4.pdf at a larger "
           "size, for the well-being of two-coloured seven-sided over-long left-over pieces")
HYPHENS = "pieces are small: " + " ".join(["two-coloured"] * 12)


def _section(text: str, start: str, end: str) -> list[str]:
    lines = text.splitlines()
    return lines[lines.index(start) + 1:lines.index(end)]


def _paragraphs(lines: list[str]) -> list[str]:
    """Items of an indented list (a line at two spaces starts one; deeper lines continue it),
    each joined into one line."""
    out: list[str] = []
    for line in lines:
        if line.startswith("  ") and not line.startswith("   "):
            out.append(line.strip())
        elif line.strip():
            out[-1] += " " + line.strip()
    return out


@pytest.mark.parametrize("levels", [3, 12])  # from level 10 on, a wrap at 93 would differ
def test_each_laser_file_names_its_layers_in_cutting_order(levels):
    text = workshop.readme({**INFO, "levels": levels, "frame_parts": 3, "kerf_mm": 0.15}, "a4")
    # plain text: no control character but the newline (a vertical tab reads as a line break
    # to splitlines, not to a text editor)
    assert all(ch == "\n" or ch.isprintable() for ch in text)
    laser = _paragraphs(_section(text, "1. To the laser", "2. To the printer (at 100 %, no "
                                                           "scaling; check the 100 mm bar)"))
    assert laser == [
        "puzzle-shared-cut.svg / .dxf - everything from one board, every shared edge cut "
        "once. Layers in order: engrave-numbers (engrave, lowest power), score-ring (score: "
        "low power, fast), cut-1-inner, cut-2-hole, cut-3-outer (cut: full power). Keep the "
        "order: the outline last, so nothing shifts before its inner cuts are done.",
        "puzzle-separate-sheet-1..2.svg / .dxf - pieces and frame nested on 2 sheets (pieces "
        "in the frame's hole too), each outline offset by half the kerf so the pieces fit "
        "snugly. Layers in order: engrave-numbers (engrave), cut-1-inner (the pieces, then "
        "the frame's hole), cut-2-outer (cut).",
        "In the .svg and .dxf files every cut layer has the same colour, so a laser program "
        "that takes its layers from the colours (LightBurn) imports them as one layer and "
        'orders them itself: in LightBurn keep "Optimize Cut Path" on, and "Cut inner shapes '
        'first" in its Optimization Settings (both on by default): it cuts a closed shape '
        "before the shape around it. The shared cut's cut-1-inner lines are open, not "
        "shapes, so it may cut them after cut-2-hole: write its LightBurn project (--formats "
        "svg,dxf,lbrn2), which keeps the order.",
        "The frame comes in 3 parts (F1, F2, F3 engraved, counter-clockwise), joined by "
        "dovetails: F1 joins F2, F2 joins F3, F3 joins F1. Glue them on a flat surface.",
        "Test first: cut a 20 mm square, measure it; kerf = 20 mm - its size. Rerun with",
        "--kerf if it differs from 0.15 mm."]
    lines = [line for line in _section(text, "==========================================",
                                       "Material: ?, kerf 0.15 mm.") if line]
    assert all(len(line) <= 92 for line in lines)  # the intro, filled to 92 columns
    for line, nxt in zip(lines, lines[1:]):
        assert len(line) + 1 + len(nxt.split()[0]) > 92
    assert " ".join(" ".join(lines).split()) == (
        "The paper's two-sided puzzle (Lipschuetz, Reitebuch, Skrodzki, Polthier, section 6): "
        f"level {levels} pieces of the pentagon snub subdivision; the front is painted with the "
        f"level {levels - 1} weave, the back with the level {levels} weave.")


@pytest.mark.parametrize("parts", [1, 2, 3])
def test_the_frame_paragraph_appears_for_a_split_frame_only(parts):
    text = workshop.readme({**INFO, "frame_parts": parts}, "a4")
    assert ("The frame comes in" in text) == (parts > 1)
    if parts > 1:
        names = ", ".join(f"F{k}" for k in range(1, parts + 1))
        assert f"The frame comes in {parts} parts ({names} engraved" in text
    assert ("The frame comes in" in workshop.readme(INFO, "a4")) is False


def test_missing_figures_read_as_unknown_and_the_lists_as_empty():
    """The README of a bare summary (no material, kerf, files, warnings or split frame)."""
    text = workshop.readme(INFO, "letter")
    lines = text.splitlines()
    assert "Material: ?, kerf 0 mm." in lines
    assert "Paints: ? on the front, ? on the back (the same paints)." in lines
    assert "  --kerf if it differs from 0 mm." in lines
    assert _section(text, "Warnings:", "Files:") == ["  none", ""]
    assert lines[-1] == "Files:" and text.endswith("Files:\n")


def test_warnings_are_wrapped_whole_as_a_list():
    text = workshop.readme({**INFO, "warnings": [WARNING, "a second warning", HYPHENS]}, "a4")
    lines = _section(text, "Warnings:", "Files:")
    assert lines[-1] == ""
    starts = [k for k, line in enumerate(lines) if line.startswith("  - ")]
    assert len(starts) == 3 and lines[starts[1]] == "  - a second warning"
    first, last = lines[:starts[1]], lines[starts[2]:-1]
    assert " ".join(" ".join(last).split()[1:]) == HYPHENS  # no word split at its hyphen
    assert first[0].startswith("  - A: pieces 3, 7, 12") and len(first) >= 2
    assert all(line.startswith("    ") and line[4] != " " for line in first[1:] + last[1:])
    assert all(len(line) <= 92 for line in first)
    # whole words: the wrapped lines hold exactly the warning's words, none split at a hyphen
    assert " ".join(" ".join(first).split()[1:]) == WARNING
    # and filled: no line could take the next word without passing 92 columns
    for line, nxt in zip(first, first[1:]):
        assert len(line) + 1 + len(nxt.split()[0]) > 92
    # a wrap at 93 columns, or one that splits at hyphens, would differ for these warnings
    assert textwrap.fill(WARNING, 93, initial_indent="  - ", subsequent_indent="    ",
                         break_on_hyphens=False).splitlines() != first
    assert textwrap.fill(HYPHENS, 92, initial_indent="  - ", subsequent_indent="    ",
                         break_on_hyphens=True).splitlines() != last


def test_summary_text_starts_with_what_the_command_chose():
    chosen = {"cell_mm": 24.0, "levels": 2, "text": "chose --cell 24mm --levels 2 (56 faces)"}
    lines = workshop.summary_text({**INFO, "chosen": chosen}).splitlines()
    plain = workshop.summary_text(INFO).splitlines()
    assert lines[0] == chosen["text"] and lines[1:] == plain
    assert plain[0].startswith("level 3 puzzle: 85 pieces (40 octagons, 45 enneagons)")


def _order_of_work(text: str) -> str:
    return " ".join(_section(text, "3. Order of work", "Warnings:")).split(" b. ")[0]


@pytest.mark.parametrize("parts", [1, 2, 3, 5])
@pytest.mark.parametrize("modes", [("shared",), ("separate",), ("shared", "separate")])
def test_the_order_of_work_fits_the_files(modes, parts):
    """Step a. says what the cut files allow: scoring only where a shared cut has its ring
    scored, the pieces kept in the frame only by the shared cut, the separate pieces laid in
    by number after a frame in parts is glued; the dovetails join the parts in one ring."""
    info = {**INFO, "frame_parts": parts, "modes": {m: INFO["modes"][m] for m in modes}}
    text = workshop.readme(info, "a4")
    step = " ".join(_order_of_work(text).split())
    assert ("score" in step) == ("shared" in modes)
    assert ("stay in the frame" in step) == ("shared" in modes)
    assert ("lay the pieces into the frame" in step) == ("separate" in modes)
    assert ("glue the frame's" in step) == ("separate" in modes and parts > 1)
    flat = " ".join(text.split())
    if parts == 2:
        assert "F1 and F2 join at both ends" in flat
    elif parts > 2:
        joins = [tuple(int(n) for n in pair) for pair in
                 re.findall(r"F(\d+) joins F(\d+)", flat)]
        after = dict(joins)
        assert sorted(after) == list(range(1, parts + 1)) == sorted(after.values())
        k, seen = 1, []
        for _ in range(parts):  # one ring through every part
            seen.append(k)
            k = after[k]
        assert k == 1 and sorted(seen) == list(range(1, parts + 1))
    else:
        assert " joins " not in flat and "glue the frame" not in flat
