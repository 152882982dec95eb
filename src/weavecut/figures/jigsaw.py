"""The jigsaw puzzle's figures (paper section 6).

``FIGURES`` has the same shape as ``figures.subdivision.FIGURES``; ``figures.gallery`` joins them.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import shapely

from .. import inputs
from ..layout.drawing import Drawing, Layer, Polylines, Style, polygons_from_shapely
from ..puzzle.colouring import colour_puzzle
from ..puzzle.guides import OUTLINE, piece_halves, split_ends
from ..puzzle.pieces import ENNEAGON, OCTAGON, build_puzzle
from ..subdivision import subdivide
from ..weave.colour import palette
from .panels import Panel, compose

WOOD = "#e8d3a9"


def fig_jigsaw_closeup() -> Drawing:
    """Figure JigsawPuzzleHighlight: a border piece, a two-coloured piece and a single-coloured
    piece of the default puzzle (50 cm, level 4) in its front paints, each drawn to the same
    scale, the two-coloured one split along its replaced parent edge."""
    puzzle = build_puzzle(subdivide(inputs.get("pentagon"), 4))
    colouring = colour_puzzle(puzzle, palette("puzzle"))
    halves = piece_halves(puzzle)
    single = (colouring.front[:, 0] == colouring.front[:, 1]) & (puzzle.kinds == OCTAGON)
    centres = shapely.get_coordinates(shapely.centroid(puzzle.pieces))
    distance = np.hypot(*centres.T)
    one = int(np.flatnonzero(single)[np.argmin(distance[single])])
    two_coloured = ~single & (puzzle.kinds == OCTAGON)
    touching = shapely.touches(puzzle.pieces, puzzle.pieces[one]) & two_coloured
    two = int(np.flatnonzero(touching)[0])
    border = puzzle.kinds == ENNEAGON
    edge = int(np.flatnonzero(border)[np.argmin(np.hypot(*(centres[border] - centres[one]).T))])
    size = max(np.ptp(np.asarray(puzzle.pieces[k].exterior.coords), axis=0).max()
               for k in (edge, two, one)) * 1.1
    panels = [_piece_panel(puzzle, colouring, halves, k, size, caption)
              for k, caption in ((edge, "a border piece"), (two, "a two-coloured piece"),
                                 (one, "a single-coloured piece"))]
    return compose(panels, columns=3, cell=60.0, title="jigsaw close-up")


def _piece_panel(puzzle, colouring, halves, k: int, size: float, caption: str) -> Panel:
    cx, cy = np.asarray(puzzle.pieces[k].centroid.coords[0])
    bounds = (cx - size / 2, cy - size / 2, cx + size / 2, cy + size / 2)

    def draw(fit):
        def place(geoms):
            return shapely.transform(np.asarray(geoms, dtype=object), fit)

        layers = []
        hexagon = puzzle.hexagons[k]
        if hexagon is not None:
            layers.append(Layer("wood", "paint", (polygons_from_shapely(
                place([hexagon]), Style(None, 0.0, WOOD)),)))
            paint = place([halves[k, 0]]), [colouring.front[k, 0]]
        else:
            paint = place(halves[k]), list(colouring.front[k])
        layers.append(Layer("paint", "paint", (polygons_from_shapely(
            paint[0], Style(None, 0.0), paint[1]),)))
        if colouring.front[k, 0] != colouring.front[k, 1] and hexagon is None:
            u, w = split_ends(puzzle)
            line = fit(np.array([u[k], w[k]]))
            layers.append(Layer("split", "guide", (Polylines(line, np.array([0, 2]),
                                                             Style("#000000", 0.3)),)))
        layers.append(Layer("outline", "guide", (polygons_from_shapely(
            place([puzzle.pieces[k]]), Style(OUTLINE.stroke, 0.6)),)))
        return layers

    return Panel(bounds, draw, f"{caption} ({k + 1})")


FIGURES: dict[str, tuple[str, Callable[[], Drawing | bytes]]] = {
    "jigsaw-closeup": ("a border piece, a two-coloured piece and a single-coloured piece of "
                       "the puzzle in its front paints (Figure JigsawPuzzleHighlight)",
                       fig_jigsaw_closeup),
}
