"""The weave and scheme figures build, and the square-grid figure shows the paper's split."""

from __future__ import annotations

import pytest

from weavecut import export
from weavecut.figures import gallery, weaving as weave_figures
from weavecut.layout.drawing import Drawing


@pytest.mark.parametrize("name", sorted(weave_figures.FIGURES))
def test_weave_figures_render(name):
    drawing = weave_figures.FIGURES[name][1]()
    assert isinstance(drawing, Drawing)
    svg = export.render(drawing, "svg")
    assert svg.startswith(b"<svg") and len(svg) > 5000


def test_gallery_has_every_figure_once():
    assert set(gallery.FIGURES) >= {"first-steps", "square-grid-weaving", "pentagon-weave",
                                     "schemes", "scheme-weaves", "level-image"}


def test_square_grid_split_panel_uses_two_shades():
    """Panel (e): the chosen strand's two long children are drawn in two different colours."""
    drawing = weave_figures.fig_square_grid_weaving()
    tiles = [layer for layer in drawing.sheets[0].layers if layer.name == "e-tiles"][0]
    fills = tiles.shapes[0].fills
    coloured = {f for f in fills if f not in ("#e9e9e9", "#ffffff")}
    assert len(coloured) >= 2
