"""The quick look (``strands --preview``, ``puzzle --preview``): the finished pattern in the
colours the kit prints, without strips, pages or cut files."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from click.testing import CliRunner

from tests.papermodel.test_strands import small_book, weaves
from tests.svg_readback import LABEL, SVG_NS, assert_svg_shows
from weavecut import inputs
from weavecut.cli import cli
from weavecut.manifest import MANIFEST
from weavecut.papermodel.preview import MARGIN, WIDTH, pattern_preview
from weavecut.puzzle.colouring import colour_puzzle
from weavecut.puzzle.guides import guide, preview
from weavecut.puzzle.pieces import build_puzzle
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette


def test_the_preview_shows_every_strand_in_the_colour_of_its_printed_strip():
    book = small_book()  # square-grid:2x2, level 2, maritime-12, mixed
    printed = {}  # strand -> the fill of its own tiles on its strips (the oracle)
    for _, strip in book.pieces:
        for fill in np.asarray(strip.fills, dtype=object)[strip.over]:
            assert printed.setdefault(strip.strand, fill) == fill
    weave = weaves("square-grid:2x2", 2)[-1]
    assert set(printed) == set(range(weave.n_strands))
    drawing = pattern_preview(list(weaves("square-grid:2x2", 2)), palette("maritime-12"))
    (sheet,) = drawing.sheets
    (layer,) = sheet.layers
    (paint,) = layer.shapes
    top = np.where(weave.tile_over >= 0, weave.tile_over, weave.tile_under)
    assert list(paint.fills) == [printed[s] if s >= 0 else "#ffffff" for s in top.tolist()]
    xy = paint.coords  # the pattern fills the preview's width or height, inside its margins
    assert xy.min() >= MARGIN - 1e-9 and xy[:, 0].max() <= sheet.width - MARGIN + 1e-9
    assert xy[:, 1].max() <= sheet.height - MARGIN + 1e-9
    assert max(np.ptp(xy, axis=0)) == pytest.approx(WIDTH)


@pytest.mark.parametrize("layout", ["mixed", "module"])
def test_the_preview_turns_as_the_assembly_sheet(layout):
    ws = list(weaves("square-grid:2x2", 2))
    straight = pattern_preview(ws, palette("maritime-12"), 0.0, layout)
    turned = pattern_preview(ws, palette("maritime-12"), np.pi / 4, layout)
    a, b = (d.sheets[0].layers[0].shapes[0] for d in (straight, turned))
    assert len(a.fills) == len(b.fills)
    # a quarter of a right angle turns the square grid's square outline into a diamond
    assert np.ptp(a.coords, axis=0) == pytest.approx([WIDTH, WIDTH], rel=1e-6)
    assert np.ptp(b.coords, axis=0)[1] == pytest.approx(WIDTH, rel=1e-6)


def test_strands_preview_writes_the_pattern_only(tmp_path):
    out = tmp_path / "look.svg"
    result = CliRunner().invoke(cli, ["strands", "square-grid", "--preview", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert sorted(tmp_path.iterdir()) == [tmp_path / MANIFEST, out]  # and what wrote it
    text = out.read_text()
    assert text.count("<svg") == 1 and "preview" in text
    # the preset's level and turn (square-grid: 2, 45 degrees), the default palette
    assert_svg_shows(pattern_preview(list(weaves("square-grid", 2)), palette("maritime-12"),
                                     np.pi / 4), out.read_bytes())


@pytest.mark.parametrize("args, says", [
    (["square-grid", "--preview", "--laser-card", "-o", "card"], "--preview draws the pattern"),
    (["square-grid", "--preview", "--cutter", "silhouette", "-o", "x.pdf"], "without --cutter"),
    (["square-grid", "--preview", "-o", "x.dxf"], "or .png"),
    (["square-grid", "-o", "x.png"], "use .pdf or .svg"),
    (["dodecahedron", "--project", "sphere", "--cutter", "silhouette", "-o", "x.pdf"],
     "flat models"),
])
def test_strands_preview_refuses_what_it_does_not_draw(tmp_path, args, says):
    result = CliRunner().invoke(cli, ["strands", *args[:-1], str(tmp_path / args[-1])])
    assert result.exit_code != 0 and says in result.output
    assert list(tmp_path.iterdir()) == []


def test_a_balls_preview_is_its_front_and_back_as_the_assembly_sheet_paints_them(tmp_path):
    from collections import Counter

    from weavecut.papermodel.ball import ball_book, ball_preview
    from weavecut.weave.snub_weave import snub_weaves

    ws = snub_weaves(subdivide(inputs.get("dodecahedron"), 1, project="sphere"))
    pal = palette("maritime-12")
    look = ball_preview(ws, pal).sheets
    book = ball_book(ws, pal, diameter=120.0)
    assert len(look) == 1 and look[0].width <= 210  # one sheet, about a screen's width

    def layer(sheet, name):
        return next(x for x in sheet.layers if x.name == name)

    assert [t.text for t in layer(look[0], "captions").shapes] == ["front", "back"]
    fills = list(layer(look[0], "views").shapes[0].fills)
    cover = list(layer(book.drawing.sheets[0], "views").shapes[0].fills)  # page 1's six views
    assert not Counter(fills) - Counter(cover)  # tiles painted as page 1 paints them
    half = len(fills) // 2  # a dodecahedron is centrally symmetric: as many tiles each side
    assert len(fills) == 2 * half and fills[:half] == cover[:half]  # page 1's front view
    assert set(fills) == set(book.colours) and len(book.colours) == 6  # every strand
    tiles = len(ws[-1].tile_offsets) - 1
    assert 0.8 * tiles <= len(fills) <= tiles  # front and back see nearly every tile once
    ids = {t.text for t in layer(look[0], "ids").shapes}
    assert ids and ids <= {chr(ord("A") + i) for i in range(6)}  # IDs where a tile faces you
    out = tmp_path / "ball.svg"
    result = CliRunner().invoke(cli, ["strands", "dodecahedron", "--levels", "1", "--project",
                                      "sphere", "--preview", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_text().count("<svg") == 1 and "front" in out.read_text()


def test_puzzle_preview_is_the_painted_front_and_back_without_numbers(tmp_path):
    puzzle = build_puzzle(subdivide(inputs.get("pentagon"), 3), 300.0, 20.0, "diagonal")
    colouring = colour_puzzle(puzzle, palette("puzzle"))
    drawing = preview(puzzle, colouring)
    assert [s.name for s in drawing.sheets] == ["front guide", "back guide"]
    for side, sheet in zip(("front", "back"), drawing.sheets):
        full = guide(puzzle, colouring, side).sheets[0]
        shown = [layer for layer in sheet.layers if layer.name != "caption"]  # "front (...)"
        assert [layer.name for layer in sheet.layers][-1] == "caption"
        assert [layer.name for layer in shown] == [layer.name for layer in full.layers]
        assert "numbers" not in [layer.name for layer in sheet.layers]
        for mine, theirs in zip(shown, full.layers):
            for a, b in zip(mine.shapes, theirs.shapes, strict=True):
                assert np.array_equal(a.coords, b.coords)
                assert getattr(a, "fills", None) == getattr(b, "fills", None)
    out = tmp_path / "look"
    result = CliRunner().invoke(cli, ["puzzle", "--levels", "3", "--size", "30cm", "--preview",
                                      "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST, "puzzle-preview.svg"]
    root = ET.fromstring((out / "puzzle-preview.svg").read_bytes())
    assert [g.get(LABEL) for g in root.iter(f"{SVG_NS}g")] == [
        name for sheet in drawing.sheets
        for name in (sheet.name, *(layer.name for layer in sheet.layers))]
