"""The weave and scheme figures build, and the square-grid figure shows the paper's split."""

from __future__ import annotations

import typing

import pytest

from click.testing import CliRunner

from tests.svg_readback import assert_svg_shows
from weavecut import export
from weavecut.cli import cli
from weavecut.figures import gallery, jigsaw, schemes, subdivision, weaving as weave_figures
from weavecut.layout.drawing import Drawing


@pytest.mark.parametrize("name", sorted(weave_figures.FIGURES))
def test_weave_figures_render(name):
    drawing = weave_figures.FIGURES[name][1]()
    assert isinstance(drawing, Drawing)
    assert_svg_shows(drawing, export.render(drawing, "svg"))


def test_gallery_has_every_figure_once():
    """No figure is lost to a name clash between the modules, none is listed under two names,
    and ``figure --list`` names each once, in the gallery's order."""
    parts = [subdivision.FIGURES, weave_figures.FIGURES, schemes.FIGURES, jigsaw.FIGURES]
    assert len(gallery.FIGURES) == sum(len(p) for p in parts)
    for part in parts:
        assert all(gallery.FIGURES[name] == entry for name, entry in part.items())
    builders = [builder for _, builder in gallery.FIGURES.values()]
    assert len(set(builders)) == len(builders)
    descriptions = [description for description, _ in gallery.FIGURES.values()]
    assert len(set(descriptions)) == len(descriptions)
    listed = CliRunner().invoke(cli, ["figure", "--list"]).output.split("\n")
    names = [line.split()[0] for line in listed if line.strip()]
    assert names == list(gallery.FIGURES)
    assert set(gallery.FIGURES) >= {"first-steps", "square-grid-weaving", "pentagon-weave",
                                     "schemes", "scheme-weaves", "level-image"}
    returns = {name: typing.get_type_hints(builder).get("return")
               for name, (_, builder) in gallery.FIGURES.items()}  # what is_picture reads
    assert set(returns.values()) == {Drawing, bytes}
    assert [name for name in gallery.FIGURES if gallery.is_picture(name)] == ["level-image"]


def test_square_grid_split_panel_uses_two_shades():
    """Panel (e): the chosen strand's two long children are drawn in two different colours."""
    drawing = weave_figures.fig_square_grid_weaving()
    tiles = [layer for layer in drawing.sheets[0].layers if layer.name == "e-tiles"][0]
    fills = tiles.shapes[0].fills
    coloured = {f for f in fills if f not in ("#e9e9e9", "#ffffff")}
    assert len(coloured) >= 2
