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

from typing import NamedTuple

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


class Label(NamedTuple):
    """A label as :func:`labels` finds it."""
    colour: str  # its ink's
    core: shapely.Geometry  # its strokes' centre lines (a Text: its box) ...
    pad: float  # ... and how far its ink reaches beyond them (mm; 0 for a Text)
    plate: shapely.Geometry | None  # its own backing, if any

    def ink(self) -> shapely.Geometry:
        """The area its ink covers (its strokes at their width: made when asked for)."""
        return shapely.buffer(self.core, self.pad) if self.pad > 0 else self.core


def labels(sheet: Sheet) -> list[Label]:
    """Every visible label of the sheet."""
    out, texts, words = [], [], []
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
                words.append((len(out), shape, plate))
                out.append(None)
                plate = None
    for (k, shape, plate), lines in zip(words, _strokes([w for _, w, _ in words])):
        pad = max(shape.style.stroke_width, 1e-3) / 2  # round caps and joins
        out[k] = Label(shape.style.stroke, lines, pad, plate)
    for (k, t), box in zip(texts, text_boxes([t for _, t in texts])):
        out[k] = Label(t.fill, box, 0.0, None)
    return out


def _strokes(words: list[Polylines]) -> list:
    """Every word's strokes as one multilinestring: all words' lines made at once."""
    if not words or any(len(w.offsets) < 2 for w in words):  # (a word without strokes)
        return [shapely.multilinestrings(shapely.linestrings(
            w.coords, indices=np.repeat(np.arange(len(w.offsets) - 1), np.diff(w.offsets))))
            for w in words]
    per_word = [len(w.offsets) - 1 for w in words]
    counts = np.diff(np.concatenate([w.offsets for w in words]))
    counts = np.delete(counts, np.cumsum(per_word)[:-1] + np.arange(len(words) - 1))  # (the
    # steps from one word's last offset to the next's first)
    lines = shapely.linestrings(np.concatenate([w.coords for w in words]),
                                indices=np.repeat(np.arange(len(counts)), counts))
    return shapely.multilinestrings(lines, indices=np.repeat(
        np.arange(len(words)), per_word)).tolist()


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
    found = labels(sheet) if found is None else found
    return [min(contrast_ratio(label.colour, c) for c in under)
            for label, under in zip(found, _under(polys, fills, found))]


def _under(polys, fills, found) -> list[list[str]]:
    """:func:`fills_under` every label's ink, all at once where one fill covers it: the
    topmost polygon near its strokes (within its pad) that holds them farther than the pad
    from its edge hides everything under the ink and nothing above reaches it; the other
    labels' inks (their strokes at their width) are made and looked at fill by fill."""
    tree = shapely.STRtree(polys) if polys else None
    out: list[list[str] | None] = [None] * len(found)
    if tree is not None and found:
        core = np.array([f.core for f in found], dtype=object)
        pad = np.array([f.pad for f in found])
        shapes = np.array(polys, dtype=object)
        # the fills whose bounds reach a label's, then those within its pad (in one call:
        # the tree's own dwithin prepares every label, twice the time)
        label, poly = tree.query(shapely.box(*_reach(core, pad).T))
        near = shapely.dwithin(core[label], shapes[poly], pad[label])
        top = np.full(len(found), -1)
        np.maximum.at(top, label[near], poly[near])
        k = np.flatnonzero(top >= 0)
        cover = shapes[top[k]]
        held = shapely.within(core[k], cover)
        held &= shapely.distance(core[k], shapely.boundary(cover)) >= pad[k] + 1e-9
        held &= (pad[k] > 0) | (shapely.area(core[k]) > 1e-9)  # no empty Text box
        for i in k[held].tolist():
            out[i] = [fills[top[i]]]
    return [fills_under(polys, fills, tree, f.ink()) if o is None else o
            for f, o in zip(found, out)]


def _reach(core, pad) -> np.ndarray:
    """(n, 4) the bounds of every label's ink: its core's grown by its pad."""
    return shapely.bounds(core) + pad[:, None] * [-1, -1, 1, 1]


def gaps(sheet: Sheet, found=None) -> list[float]:
    """Per label (``found``: :func:`labels` of the sheet, if at hand): the distance (mm) from
    its ink and plate to the nearest other label's within NEAR mm (infinite if none is; if no
    two labels are that close, to the nearest at all; infinite for a label alone).

    The distance of two inks is that of their centre lines less both pads (exact for strokes
    with round ends), many times faster than between the inks' outlines."""
    found = labels(sheet) if found is None else found
    n = len(found)
    if n < 2:
        return [float("inf")] * n
    core = np.array([f.core for f in found], dtype=object)
    pad = np.array([f.pad for f in found])
    plate = np.array([f.plate for f in found], dtype=object)
    has = ~shapely.is_missing(plate)
    box = _reach(core, pad)
    plated = shapely.bounds(plate[has])
    box[has] = np.hstack([np.minimum(box[has, :2], plated[:, :2]),
                          np.maximum(box[has, 2:], plated[:, 2:])])
    boxes = shapely.box(*box.T)
    a, b = shapely.STRtree(boxes).query(boxes, predicate="dwithin", distance=NEAR)
    if not (a != b).any():  # no two within NEAR: every pair
        a, b = np.nonzero(~np.eye(n, dtype=bool))
    a, b = a[a != b], b[a != b]
    d = shapely.distance(core[a], core[b]) - pad[a] - pad[b]
    for mine, theirs, less in ((core, plate, pad[a]), (plate, core, pad[b]),
                               (plate, plate, 0.0)):
        d = np.fmin(d, shapely.distance(mine[a], theirs[b]) - less)  # NaN where no plate
    out = np.full(n, np.inf)
    np.minimum.at(out, a, np.maximum(d, 0.0))
    return out.tolist()


NEAR = 10.0  # mm: labels farther apart than this are far enough apart (MIN_GAP is 0.5)


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
