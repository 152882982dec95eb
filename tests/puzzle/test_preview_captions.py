"""The painted preview (``puzzle --preview``) names its two halves (issue 29: a maker could not
tell the front from the back): each sheet carries a caption that starts with its side, front
first, whole inside its sheet and above the frame, and the written SVG shows both."""

from __future__ import annotations

import shapely
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.layout.drawing import Polygons, Text
from weavecut.layout.strokefont import ink_box
from weavecut.puzzle.guides import preview

from tests.built_puzzles import pentagon_paint, pentagon_puzzle


def test_each_half_of_the_preview_says_which_side_it_is():
    drawing = preview(pentagon_puzzle(2), pentagon_paint(2))
    assert len(drawing.sheets) == 2
    for sheet, side in zip(drawing.sheets, ("front", "back")):
        texts = [s for layer in sheet.layers for s in layer.shapes if isinstance(s, Text)]
        assert [t.text.split(" ")[0] for t in texts] == [side]
        t = texts[0]
        outline = [s for layer in sheet.layers if layer.name == "frame" for s in layer.shapes
                   if isinstance(s, Polygons)][0]
        top = float(shapely.get_coordinates(outline.to_shapely()).max(axis=0)[1])
        # a generous width: the font's ink box at this size, 0.7 cap a letter
        assert 0 < t.x and t.x + 0.7 * t.size * len(t.text) < sheet.width
        assert top < t.y and t.y + t.size <= sheet.height
        assert ink_box(t.text)  # a text the font can draw


def test_the_written_preview_shows_both_captions(tmp_path):
    result = CliRunner().invoke(cli, ["puzzle", "--levels", "2", "--preview", "-o",
                                      str(tmp_path)])
    assert result.exit_code == 0, result.output
    svg = (tmp_path / "puzzle-preview.svg").read_text(encoding="utf-8")
    assert 0 < svg.index(">front (") < svg.index(">back (")
