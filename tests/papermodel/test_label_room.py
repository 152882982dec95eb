"""Every label of a strand book reads on what lies under it and keeps clear of every other
label, as ``strands --json`` reports it (``min_label_contrast``, ``min_label_gap_mm``),
recounted here from the drawing by an oracle of its own: points on a grid over every label's
box, each looked up in the filled polygons in drawing order (the topmost that covers it, the
paper where none does), and the distance between every two boxes of a page."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
import shapely

from weavecut.layout.contrast import MIN_CONTRAST, contrast_ratio
from weavecut.layout.drawing import Polygons, Text
from weavecut.layout.label_checks import MIN_GAP
from weavecut.layout.labels import text_box
from weavecut.papermodel.ball import ball_book, diameter_for
from weavecut.papermodel.checks import report
from weavecut.weave.colour import palette

from tests.papermodel.test_ball import ball_weaves
from tests.papermodel.test_strands import pentagon_book, small_book


@lru_cache(maxsize=None)
def _ball():
    weaves = ball_weaves("dodecahedron", 1)
    return ball_book(weaves, palette("maritime-12"), (210.0, 297.0),
                     diameter_for(weaves[-1], 40.0))


BOOKS = {"square-grid": small_book, "pentagon-flower": pentagon_book, "ball": _ball}


def _recount(sheet) -> tuple[float, float]:
    """(least contrast, least gap) of the sheet's texts, from the drawing alone."""
    polys, fills = [], []
    for layer in sheet.layers:
        for shape in layer.shapes:
            if layer.visible and isinstance(shape, Polygons):
                colours = shape.fills or (shape.style.fill,) * shape.n_polygons
                polys += [g for g, c in zip(shape.to_shapely().tolist(), colours) if c]
                fills += [c for c in colours if c]
    tree = shapely.STRtree(polys)
    texts = [t for layer in sheet.layers if layer.visible for t in layer.shapes
             if isinstance(t, Text)]
    boxes = [text_box(t) for t in texts]
    least = 21.0
    for t, box in zip(texts, boxes):
        x0, y0, x1, y1 = box.bounds
        xy = np.stack(np.meshgrid(np.linspace(x0, x1, 40), np.linspace(y0, y1, 12)), -1)
        pts = shapely.points(xy.reshape(-1, 2))
        pts = pts[shapely.covers(box, pts)]
        hit, poly = tree.query(pts, predicate="intersects")
        top = np.full(len(pts), -1)
        np.maximum.at(top, hit, poly)
        under = {fills[j] if j >= 0 else "#ffffff" for j in top.tolist()}
        least = min(least, *(contrast_ratio(t.fill, c) for c in under))
    gap = min((shapely.distance(a, b) for i, a in enumerate(boxes) for b in boxes[i + 1:]),
              default=np.inf)
    return least, gap


@pytest.mark.slow
@pytest.mark.parametrize("name", BOOKS)
def test_labels_read_on_what_is_under_them_and_keep_apart(name):
    book = BOOKS[name]()
    rep = report(book)
    seen = [_recount(s) for s in book.drawing.sheets]
    contrast, gap = min(c for c, _ in seen), min(g for _, g in seen)
    assert contrast >= MIN_CONTRAST and gap >= MIN_GAP
    # the report's figures are these, up to the grid's reach (a box corner between points)
    assert rep["min_label_contrast"] <= round(contrast, 2) + 0.01
    assert rep["min_label_contrast"] >= MIN_CONTRAST
    assert rep["min_label_gap_mm"] == pytest.approx(gap, abs=0.006)
