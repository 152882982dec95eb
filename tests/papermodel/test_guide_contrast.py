"""Every guide line printed on a strip reads against the paper it lies on (issue 29: a label
tab's cut-off line looked black on navy and dark green tabs): each dash of a tab's cut-off
line and of a ball's fold line has a WCAG contrast of 3 or more (non-text contrast) against
the fill it is drawn on, read from the page's Drawing: the topmost painted polygon under a
point just inside the tab (or, for a fold, beside the line on either side)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
import shapely

from weavecut import inputs
from weavecut.layout.contrast import contrast_ratio
from weavecut.layout.drawing import Polygons, Polylines
from weavecut.papermodel import ball
from weavecut.papermodel.book import strand_book, tile_size_for
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

NON_TEXT = 3.0  # WCAG 2.1 SC 1.4.11


def _painted(sheet):
    """(polygons, fills) of the sheet's paint layers in painting order."""
    polys, fills = [], []
    for layer in sheet.layers:
        if layer.role != "paint":
            continue
        for shape in layer.shapes:
            if isinstance(shape, Polygons):
                geoms = shape.to_shapely().tolist()
                own = shape.fills if shape.fills is not None else [shape.style.fill] * len(geoms)
                for g, f in zip(geoms, own):
                    if f is not None:
                        polys.append(g)
                        fills.append(f)
    return np.array(polys, dtype=object), fills


def _under(polys, fills, point) -> str | None:
    hits = np.flatnonzero(shapely.contains_xy(polys, point[0], point[1]))
    return fills[hits[-1]] if len(hits) else None


def guide_contrasts(drawing, layer_names=("tabs", "folds")) -> list[float]:
    """Per dash of every guide line, the better contrast of its ink against the fills just
    to either side of it (a line on a tab's edge is read on the tab; a fold between two tiles
    on either)."""
    out = []
    for sheet in drawing.sheets:
        polys, fills = _painted(sheet)
        for layer in sheet.layers:
            if layer.name not in layer_names:
                continue
            for shape in layer.shapes:
                if not isinstance(shape, Polylines):
                    continue
                for line in shape.lines():
                    a, b = line[0], line[-1]
                    d = b - a
                    n = np.array([-d[1], d[0]]) / max(np.hypot(*d), 1e-12)
                    mid = (a + b) / 2
                    sides = [_under(polys, fills, mid + s * 0.3 * n) for s in (1, -1)]
                    out.append(max(contrast_ratio(shape.style.stroke, f)
                                   for f in sides if f is not None))
    return out


@lru_cache(maxsize=None)
def _pentagon_book():
    ws = snub_weaves(subdivide(inputs.get("pentagon-flower"), 3))
    return strand_book(ws, palette("maritime-12"), tile_size=tile_size_for(ws[-1], 230.0))


@pytest.mark.slow
def test_every_tab_cut_off_line_reads_on_its_tab():
    book = _pentagon_book()
    found = guide_contrasts(book.drawing, ("tabs",))
    assert len(found) > 100  # 70 tabs, a few dashes each
    assert min(found) >= NON_TEXT


def test_every_fold_line_of_the_ball_reads_on_its_tile():
    ws = snub_weaves(subdivide(inputs.get("dodecahedron"), 1, project="sphere"))
    book = ball.ball_book(ws, palette("maritime-12"), (210.0, 297.0),
                          ball.diameter_for(ws[-1], 40.0))
    found = guide_contrasts(book.drawing, ("folds",))
    assert found and min(found) >= NON_TEXT
