"""The woven pattern drawn into a box of a page: the tiles in the strands' colours, the fit, and
each tile's label spot (the assembly sheet, the weaving steps' diagrams, the crossing pages)."""

from __future__ import annotations

import numpy as np
import shapely

from ..layout.drawing import Fit, Style, polygons_from_shapely
from ..layout.labels import inner_centres
from ..weave.model import Weave
from .strips import model_tiles
from .symmetry import rotate

OUTLINE = Style("#333333", 0.1)


def pattern(weave: Weave, turn: float, box, colours, show=None):
    """(tiles on the sheet, fit, paint shape, fills) for the pattern fitted into ``box``; with
    ``show`` (S,) bool only those strands are coloured (the others white)."""
    tiles = model_tiles(weave)
    centre = weave.mesh.vertices.mean(axis=0)
    turned = shapely.transform(tiles, lambda xy: rotate(xy, turn, centre))
    x0, y0, x1, y1 = box
    fit = Fit.into(shapely.total_bounds(turned), x1 - x0, y1 - y0, 0.0)
    fit = Fit(fit.scale, (fit.offset[0] + x0, fit.offset[1] + y0))
    on_sheet = shapely.transform(turned, fit)
    over, under = weave.tile_over, weave.tile_under
    if show is None:
        show = np.ones(weave.n_strands, dtype=bool)
    top = np.where((over >= 0) & show[np.maximum(over, 0)], over,
                   np.where((under >= 0) & show[np.maximum(under, 0)], under, -1))
    fills = [colours[s] if s >= 0 else "#ffffff" for s in top.tolist()]
    return on_sheet, fit, polygons_from_shapely(list(on_sheet), OUTLINE, fills), fills


def label_spots(tiles) -> np.ndarray:
    """(n, 2) each tile's label spot: the centre of the largest circle inside it (the mean of
    its corners lies outside a non-convex or twisted tile of an irregular mesh)."""
    return inner_centres(shapely.make_valid(tiles, method="structure", keep_collapsed=False))
