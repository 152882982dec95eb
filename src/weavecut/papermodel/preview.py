"""A quick look at a paper model: the woven pattern in the kit's colours, drawn without strips,
packing or pages (``weave-cut strands --preview``; the web app's live preview)."""

from __future__ import annotations

import numpy as np
import shapely

from ..layout.drawing import Drawing, Layer, Sheet
from ..weave.colour import Palette
from ..weave.model import Weave
from .modules import book_colours, plan_modules
from .pattern import pattern

WIDTH = 200.0  # mm: the preview's size on its sheet (the pattern keeps its proportions)
MARGIN = 5.0


def pattern_preview(weaves: list[Weave], pal: Palette, turn: float = 0.0,
                    layout: str = "mixed", title: str = "weave-cut strands: preview") -> Drawing:
    """One sheet showing ``weaves[-1]`` as the finished model, turned by ``turn`` radians as on
    the assembly sheet, every strand in the colour its strip is printed in (``layout``:
    ``mixed`` or ``module``, as :func:`.book.strand_book`)."""
    weave = weaves[-1]
    plan = plan_modules(weave, heading=-np.pi / 2 - turn)
    colours = book_colours(weaves, plan, pal, layout)
    box = (MARGIN, MARGIN, MARGIN + WIDTH, MARGIN + WIDTH)
    on_sheet, _, paint, _ = pattern(weave, turn, box, colours)
    x1, y1 = shapely.total_bounds(on_sheet)[2:]  # the fit fills the box's width or height
    sheet = Sheet(float(x1 + MARGIN), float(y1 + MARGIN), (Layer("pattern", "paint", (paint,)),),
                  "preview")
    return Drawing((sheet,), title)
