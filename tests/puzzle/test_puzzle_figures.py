"""The puzzle's figures: jigsaw-closeup shows the three kinds of piece in the puzzle's front
paints, and pentagon-weave paints its strands as the puzzle does."""

from __future__ import annotations

from weavecut import inputs
from weavecut.figures import gallery
from weavecut.figures.jigsaw import fig_jigsaw_closeup
from weavecut.figures.weaving import fig_pentagon_weave
from weavecut.puzzle.colouring import colour_puzzle
from weavecut.puzzle.pieces import build_puzzle
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette


def _puzzle_paints():
    puzzle = build_puzzle(subdivide(inputs.get("pentagon"), 4))
    return colour_puzzle(puzzle, palette("puzzle"))


def test_closeup_shows_a_border_a_two_coloured_and_a_single_coloured_piece():
    assert "jigsaw-closeup" in gallery.FIGURES
    drawing = fig_jigsaw_closeup()
    layers = {layer.name: layer for layer in drawing.sheets[0].layers}
    fills = [set(layers[f"{p}-paint"].shapes[0].fills) for p in "abc"]
    assert [len(f) for f in fills] == [1, 2, 1]
    assert "a-wood" in layers and "b-split" in layers and "c-wood" not in layers
    paints = set(_puzzle_paints().front_colours)
    assert set().union(*fills) <= paints


def test_pentagon_weave_uses_the_puzzles_front_and_back_paints():
    colouring = _puzzle_paints()
    drawing = fig_pentagon_weave()
    fills = {layer.name: {f for shape in layer.shapes if getattr(shape, "fills", None)
                          for f in shape.fills}
             for layer in drawing.sheets[0].layers}
    assert fills["a-tiles"] == set(colouring.front_colours)
    assert fills["b-tiles"] == set(colouring.back_colours)
