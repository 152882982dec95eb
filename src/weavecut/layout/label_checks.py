"""What a maker sees of every label on a sheet: the fills under its ink and the room between it
and the next label; the figures ``puzzle --json`` and ``strands --json`` report.

A label is a :class:`~weavecut.layout.drawing.Text` (its outline: :func:`text_box`) or one
single-stroke word: a :class:`~weavecut.layout.drawing.Polylines` on a layer named ``WORDS``
(its outline: its strokes at their width), together with a filled plate drawn on that layer
right before it (a label's own backing, see ``puzzle.guide_numbers``). What lies under a
label is every fill its outline overlaps that shows there: filled polygons in drawing order
(a later one hides an earlier one), and the paper where none is.

>>> from weavecut.layout.drawing import Sheet, Layer, Text
>>> sheet = Sheet(100, 100, (Layer("t", "label", (Text(10, 10, "A", 4.0, fill="#ffffff"),)),))
>>> [round(c, 2) for c in contrasts(sheet)]
[1.0]
"""

from __future__ import annotations

import numpy as np
import shapely

from .contrast import MIN_CONTRAST, contrast_ratio
from .drawing import Polygons, Polylines, Sheet, Text
from .labels import text_boxes

WORDS = "numbers"
"""The name of the layers whose polylines are single-stroke words, one shape per word."""
PAPER = "#ffffff"
MIN_GAP = 0.5
"""mm: the least room between the outlines of two labels, so that neither runs into the other."""


def filled(sheet: Sheet) -> tuple[list, list[str]]:
    """Every filled polygon of the visible layers in drawing order, with its fill (a label's
    plate included)."""
    polys, fills = [], []
    for layer in sheet.layers:
        if not layer.visible:
            continue
        for shape in layer.shapes:
            if isinstance(shape, Polygons):
                colours = shape.fills or (shape.style.fill,) * shape.n_polygons
                for g, c in zip(shape.to_shapely().tolist(), colours):
                    if c is not None:
                        polys.append(g)
                        fills.append(c)
    return polys, fills


QUAD_SEGS = 4  # a round end within 2 % of its radius (a hundredth of a millimetre), and gaps
# measured four times faster than at shapely's default 8


def stroke_outline(shape: Polylines) -> shapely.Geometry:
    """The area the strokes of ``shape`` cover at their width (round caps and joins)."""
    lines = shapely.linestrings(shape.coords, indices=np.repeat(
        np.arange(len(shape.offsets) - 1), np.diff(shape.offsets)))
    return shapely.buffer(shapely.multilinestrings(lines),
                          max(shape.style.stroke_width, 1e-3) / 2, quad_segs=QUAD_SEGS)


def labels(sheet: Sheet) -> list[tuple[shapely.Geometry, str, shapely.Geometry]]:
    """Every visible label of the sheet: (the outline of its ink, its ink colour, its outline
    with its plate: what must keep clear of other labels)."""
    out, texts = [], []
    for layer in sheet.layers:
        if not layer.visible:
            continue
        plate = None
        for shape in layer.shapes:
            if isinstance(shape, Text):
                texts.append((len(out), shape))
                out.append(None)
            elif layer.name == WORDS and isinstance(shape, Polygons):
                plate = shapely.union_all(shape.to_shapely())
            elif layer.name == WORDS and isinstance(shape, Polylines):
                ink = stroke_outline(shape)
                out.append((ink, shape.style.stroke, ink if plate is None
                            else shapely.union(ink, plate)))
                plate = None
    for (k, t), box in zip(texts, text_boxes([t for _, t in texts])):
        out[k] = (box, t.fill, box)
    return out


def fills_under(polys, fills, tree, outline) -> list[str]:
    """The fills that show inside ``outline``, topmost first: each polygon hides what lies
    under it; the paper shows where nothing is."""
    rest, out = outline, []
    for j in sorted(tree.query(outline), reverse=True) if tree is not None else []:
        if rest.is_empty:
            break
        if shapely.intersection(polys[j], rest).area > 1e-9:
            out.append(fills[j])
            rest = shapely.difference(rest, polys[j])
    return out + [PAPER] if rest.area > 1e-9 else out


def contrasts(sheet: Sheet, found=None) -> list[float]:
    """Per label (``found``: :func:`labels` of the sheet, if at hand): its ink's least
    contrast with anything under it."""
    polys, fills = filled(sheet)
    tree = shapely.STRtree(polys) if polys else None
    out = []
    for ink_area, ink, _ in labels(sheet) if found is None else found:
        under = fills_under(polys, fills, tree, ink_area)
        out.append(min(contrast_ratio(ink, c) for c in under))
    return out


def gaps(sheet: Sheet, found=None) -> list[float]:
    """Per label (``found``: :func:`labels` of the sheet, if at hand): the distance (mm) from
    its outline (with its plate) to the nearest other label's; infinite for a label alone."""
    found = labels(sheet) if found is None else found
    outlines = np.array([room for *_, room in found], dtype=object)
    if len(outlines) < 2:
        return [float("inf")] * len(outlines)
    tree = shapely.STRtree(outlines)
    near = tree.query_nearest(outlines, exclusive=True, all_matches=False)
    out = np.full(len(outlines), np.inf)
    d = shapely.distance(outlines[near[0]], outlines[near[1]])
    np.minimum.at(out, near[0], d)
    return out.tolist()


def figures(sheets) -> dict:
    """``min_label_contrast`` and ``min_label_gap_mm`` over the labels of ``sheets``, with how
    many labels fall short of ``MIN_CONTRAST`` and of ``MIN_GAP``."""
    c, g = [], []
    for s in sheets:
        found = labels(s)
        c += contrasts(s, found)
        g += gaps(s, found)
    finite = [x for x in g if np.isfinite(x)]
    return {"min_label_contrast": round(min(c, default=21.0), 2),
            "min_label_gap_mm": round(min(finite), 2) if finite else None,
            "labels_under_contrast": sum(x < MIN_CONTRAST for x in c),
            "labels_too_close": sum(x < MIN_GAP for x in finite)}
