"""Tile a large 1:1 Drawing onto printer pages (A4, Letter) with overlap and assembly marks.

Every page shows a window of the big sheet: the printable area (page minus ``margin``) steps by
its size minus ``overlap``, so neighbouring pages repeat an ``overlap`` mm strip. The grid of
windows covers what is drawn (not the sheet's empty margins), centred on it, so the first and
the last page of a row or column share the slack and none holds only a sliver; where a
narrower margin (``LEAST_MARGIN``, still clear of the page marks) saves a row or a column, it
is used. Pages may be left out (``keep``: a guide keeps only pages with paint). Dashed lines
mark where the next page's window starts (cut or fold there and glue the strip under), corner
ticks mark the window, a label names the page by its number in the file ("page 3 of 5") and
the pages that join it on the right and below, and a 100 mm bar checks the scale. Shapes are
clipped to the window with shapely, fills kept.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import shapely
from numpy.typing import NDArray

from .. import budget
from ..numeric import offsets_of
from .drawing import (Drawing, Layer, Polygons, Polylines, Raster, Sheet, Style, Text,
                      polygons_from_shapely)
from .label_checks import WORDS
from .labels import text_width

MARK = Style("#808080", 0.2)
MARK_MARGIN = 10.0  # mm: the page marks (label, scale bar) lie in the outer half of this margin
LEAST_MARGIN = 8.0  # mm: the narrowest margin a window may take, clear of the marks
PAD = 1.0  # mm round what is drawn (strokes' widths) that the windows cover


def on_pages(drawing: Drawing, page: tuple[float, float], overlap: float = 10.0,
             margin: float = 10.0, printer_margin: float = 5.0) -> Drawing:
    """Every sheet of ``drawing`` at 1:1 on printer pages: its content centred on one page,
    upright or turned a quarter (landscape), when it fits inside ``printer_margin``; else the
    sheet tiled, on whichever orientation needs fewer pages (when equal, the one shaped like
    the sheet)."""
    turned = (page[1], page[0])
    plan = []  # per sheet: the page it fits on, centred, or the page it is tiled on
    for sheet in drawing.sheets:
        x0, y0, x1, y1 = _content_box(sheet)
        room = 2 * printer_margin
        fits = [p for p in (page, turned) if x1 - x0 <= p[0] - room and y1 - y0 <= p[1] - room]
        if fits:
            plan.append((sheet, fits[0], (x0, y0, x1, y1), 1))
            continue
        wide = sheet.width > sheet.height
        best = min((page, turned), key=lambda p: (count(sheet, p, overlap, margin),
                                                  (p[0] > p[1]) != wide))
        plan.append((sheet, best, None, count(sheet, best, overlap, margin)))
    total = sum(n for *_, n in plan)
    check_pages(drawing, page, total)
    pages: list[Sheet] = []
    for sheet, (w, h), box, n in plan:
        if box is None:
            pages.extend(tile(replace(drawing, sheets=(sheet,)), (w, h), overlap, margin,
                              before=len(pages), after=total - len(pages) - n).sheets)
            continue
        dx, dy = (w - box[0] - box[2]) / 2, (h - box[1] - box[3]) / 2
        pages.append(replace(sheet, width=w, height=h, layers=tuple(
            replace(layer, shapes=tuple(_moved(s, dx, dy) for s in layer.shapes))
            for layer in sheet.layers)))
    return replace(drawing, sheets=tuple(pages))


def check_pages(drawing: Drawing, page: tuple[float, float], n: int) -> None:
    """Refuse, before any page is made, a print of ``drawing`` on more than
    ``budget.MAX_PAGES`` pages."""
    big = max(drawing.sheets, key=lambda s: s.width * s.height)
    budget.check_count(n, budget.MAX_PAGES, "pages",
                       f"printing the {big.width:,.0f} x {big.height:,.0f} mm drawing 1:1 on "
                       f"{page[0]:g} x {page[1]:g} mm paper",
                       "a ream; use a smaller --size or a larger --page")


def _content_box(sheet: Sheet) -> tuple[float, float, float, float]:
    """Bounds of everything drawn on ``sheet`` (text by its anchor point); the whole sheet
    when it is empty."""
    points = [s.coords for layer in sheet.layers for s in layer.shapes if not isinstance(s, Text)]
    points += [np.array([[s.x, s.y]]) for layer in sheet.layers for s in layer.shapes
               if isinstance(s, Text)]
    xy = np.concatenate(points) if points else np.zeros((0, 2))
    if not len(xy):
        return (0.0, 0.0, sheet.width, sheet.height)
    (x0, y0), (x1, y1) = xy.min(axis=0), xy.max(axis=0)
    return (float(x0), float(y0), float(x1), float(y1))


def _moved(shape, dx: float, dy: float):
    if isinstance(shape, Raster):
        return shape.moved(dx, dy)
    if isinstance(shape, Text):
        return replace(shape, x=shape.x + dx, y=shape.y + dy)
    return replace(shape, coords=shape.coords + (dx, dy))


def count(sheet: Sheet, page, overlap: float, margin: float) -> int:
    """How many pages :func:`tile` lays over ``sheet`` (before any is left out)."""
    cols, rows, *_ = grid(_cover(sheet), page, overlap, margin)
    return cols * rows


def _cover(sheet: Sheet) -> tuple[float, float, float, float]:
    """The box the windows cover: what is drawn on ``sheet``, ``PAD`` mm round it."""
    x0, y0, x1, y1 = _content_box(sheet)
    return (x0 - PAD, y0 - PAD, x1 + PAD, y1 + PAD)


def grid(box, page, overlap: float, margin: float, shift=(0.5, 0.5)
         ) -> tuple[int, int, float, float, float]:
    """(columns, rows, margin, left, top) of the windows over ``box`` (x0, y0, x1, y1): at
    ``margin``, or at ``LEAST_MARGIN`` where that needs fewer pages; the grid's slack (what
    it covers beyond the box) ``shift`` (x, y: 0 to 1) of it left of and above the box, half
    by default: centred (``left``, ``top``: the first window's left and top edges)."""
    width, height = box[2] - box[0], box[3] - box[1]
    best = None
    for m in dict.fromkeys((margin, min(margin, LEAST_MARGIN))):
        window = (page[0] - 2 * m, page[1] - 2 * m)
        cols, rows = (max(1, math.ceil((size - overlap) / (w - overlap)))
                      for size, w in ((width, window[0]), (height, window[1])))
        if best is None or cols * rows < best[0] * best[1]:
            slack_x = cols * (window[0] - overlap) + overlap - width
            slack_y = rows * (window[1] - overlap) + overlap - height
            best = (cols, rows, m, box[0] - slack_x * shift[0], box[3] + slack_y * shift[1])
    return best


def _windows(page, overlap, cols, rows, margin, left, top) -> NDArray[np.float64]:
    """(rows * cols, 4) the windows (x0, y0, x1, y1), row by row from the top."""
    pw, ph = page[0] - 2 * margin, page[1] - 2 * margin
    r, c = np.divmod(np.arange(rows * cols), cols)
    x0 = left + c * (pw - overlap)
    y0 = top - ph - r * (ph - overlap)
    return np.column_stack([x0, y0, x0 + pw, y0 + ph])


SHIFTS = (0.5, 0.25, 0.75, 0.0, 1.0)  # where a grid may lie in its slack: centred first
SAMPLE = 2.0  # mm between the points that weigh what a window holds


def balanced(sheet: Sheet, pages, overlap: float, margin: float, name: str = "paint"):
    """(page, shift): of ``pages`` (sizes) and the grid's ``SHIFTS``, the one that leaves the
    fewest windows holding any of the polygons of the sheet's layer ``name`` (the others are
    left out), then whose emptiest window holds the most of them (points on a ``SAMPLE`` mm
    grid); the first of equals (centred, on the first page)."""
    box = _cover(sheet)
    polys = np.array([g for layer in sheet.layers if layer.name == name
                      for shape in layer.shapes if isinstance(shape, Polygons)
                      for g in shape.to_shapely().tolist()], dtype=object)
    shapely.prepare(polys)  # each is asked about many points
    xs = np.arange(box[0], box[2], SAMPLE) + SAMPLE / 2
    ys = np.arange(box[1], box[3], SAMPLE) + SAMPLE / 2
    inside = np.zeros((len(ys), len(xs)), dtype=bool)
    bounds = shapely.bounds(polys).reshape(-1, 4)
    # each polygon against the points of its bounds, all in one call
    i0, j0, i1, j1 = (np.searchsorted(v, bounds[:, k]) for k, v in enumerate((xs, ys) * 2))
    ni, nj = np.maximum(i1 - i0, 0), np.maximum(j1 - j0, 0)
    per = ni * nj
    owner = np.repeat(np.arange(len(polys)), per)
    k = np.arange(per.sum()) - np.repeat(np.cumsum(per) - per, per)  # row by row in its box
    i, j = i0[owner] + k % ni[owner], j0[owner] + k // ni[owner]
    hit = shapely.contains_xy(polys[owner], xs[i], ys[j])
    inside[j[hit], i[hit]] = True
    held = np.zeros((len(ys) + 1, len(xs) + 1), dtype=np.int64)  # points below-left, summed
    held[1:, 1:] = inside.cumsum(axis=0).cumsum(axis=1)
    counts = [math.prod(grid(box, p, overlap, margin)[:2]) for p in pages]  # count(): box once
    best, choice = None, (pages[0], (0.5, 0.5))
    for page, n_pages in zip(pages, counts):
        if n_pages > min(counts):
            continue
        for shift in ((x, y) for x in SHIFTS for y in SHIFTS):
            w = _windows(page, overlap, *grid(box, page, overlap, margin, shift))
            i0, i1 = (np.searchsorted(xs, w[:, k]) for k in (0, 2))
            j0, j1 = (np.searchsorted(ys, w[:, k]) for k in (1, 3))
            n = held[j1, i1] - held[j0, i1] - held[j1, i0] + held[j0, i0]
            score = (int((n > 0).sum()), -int(n[n > 0].min(initial=n.sum())))
            if best is None or score < best:
                best, choice = score, (page, shift)
    return choice


def tile(drawing: Drawing, page: tuple[float, float] = (210.0, 297.0), overlap: float = 10.0,
         margin: float = 10.0, keep=None, before: int = 0, after: int = 0,
         shift=(0.5, 0.5)) -> Drawing:
    """One page per window over what is drawn on the first sheet of ``drawing`` (rows from the
    top; the grid centred on it, or ``shift``ed as :func:`grid` says), less those ``keep`` (a
    test of a page) leaves out; each names itself "page n of N" in a file with ``before``
    pages ahead of these and ``after`` behind."""
    big = drawing.sheets[0]
    cols, rows, margin, left, top = grid(_cover(big), page, overlap, margin, shift)
    check_pages(drawing, page, cols * rows)
    geoms = [_geoms(layer) for layer in big.layers]
    made = {}
    boxes = _windows(page, overlap, cols, rows, margin, left, top)
    for k, (x0, y0, x1, y1) in enumerate(boxes.tolist()):  # pages, a handful
        r, c = divmod(k, cols)
        window = shapely.box(x0, y0, x1, y1)
        moved = np.array([margin - x0, margin - y0])
        layers = [_clip_layer(layer, g, window, moved) for layer, g in zip(big.layers, geoms)]
        sheet = Sheet(page[0], page[1], tuple(layers), f"page r{r + 1} c{c + 1}")
        if keep is None or keep(sheet):
            made[r, c] = sheet
    number = {rc: before + k + 1 for k, rc in enumerate(made)}
    total = before + len(made) + after
    pages = [replace(sheet, layers=sheet.layers + (_marks(
        page, margin, overlap, number[r, c], total, number.get((r, c + 1)),
        number.get((r + 1, c)), drawing.title),)) for (r, c), sheet in made.items()]
    return replace(drawing, sheets=tuple(pages))


def _geoms(layer: Layer):
    """What :func:`_clip_layer` needs of ``layer``, once for all its pages: the shapely
    geometries of its Polygons and Polylines (not its words) in one array, their bounds (n, 4),
    the shape each belongs to, whether it is a line, where each shape's run of them starts
    (S + 1); and every word's least and greatest point (S, 2; NaN for other shapes)."""
    parts, lines = [], []
    lo, hi = np.full((2, len(layer.shapes), 2), np.nan)
    words = [i for i, s in enumerate(layer.shapes)
             if layer.name == WORDS and isinstance(s, Polylines) and len(s.coords)]
    if words:
        lo[words], hi[words] = _extents([layer.shapes[i] for i in words])
    for shape in layer.shapes:
        if isinstance(shape, Polylines) and layer.name == WORDS:
            geoms = np.empty(0, dtype=object)
        elif isinstance(shape, Polygons):
            geoms = shape.to_shapely()
        elif isinstance(shape, Polylines):
            geoms = shapely.linestrings(shape.coords, indices=np.repeat(
                np.arange(len(shape.offsets) - 1), np.diff(shape.offsets)))
        else:
            geoms = np.empty(0, dtype=object)
        parts.append(np.asarray(geoms, dtype=object))
        lines.append(isinstance(shape, Polylines))
    sizes = np.array([len(g) for g in parts], dtype=np.int64)
    geoms = np.concatenate(parts) if parts else np.empty(0, dtype=object)
    owner = np.repeat(np.arange(len(parts)), sizes)
    reach = np.array([s.style.stroke_width / 2 if isinstance(s, Polylines) else 0.0
                      for s in layer.shapes]).reshape(-1, 1)  # a word's ink beyond its points
    drawn = np.array([isinstance(s, (Polygons, Polylines)) for s in layer.shapes], dtype=bool)
    return (geoms, shapely.bounds(geoms).reshape(-1, 4), owner,
            np.repeat(np.array(lines, dtype=bool), sizes), offsets_of(sizes), lo, hi,
            reach, drawn)


def _clip_layer(layer: Layer, geoms, window, shift) -> Layer:
    """``layer`` clipped to ``window`` and moved by ``shift``; ``geoms`` (:func:`_geoms` of
    the layer) are clipped, all in one call, where their bounds reach the window. A
    single-stroke word (a Polylines of a ``WORDS`` layer) is kept whole where it lies inside
    the window and left to the neighbouring page where it does not: no number is printed cut
    in two (with an overlap as wide as the widest word, each is whole on some page:
    :func:`word_overlap`)."""
    x0, y0, x1, y1 = window.bounds
    margin_box = np.array([x0, y0, x1, y1]) + np.r_[shift, shift]
    every, b, owner, lines, start, lo, hi, reach, drawn = geoms
    near = np.flatnonzero((b[:, 0] <= x1) & (b[:, 2] >= x0) & (b[:, 1] <= y1) & (b[:, 3] >= y0))
    parts, at = shapely.get_parts(_clip(every[near], b[near], window, lines[near]),
                                  return_index=True)
    at = near[at]  # each part's geometry, in shape order
    cuts = np.searchsorted(owner[at], np.arange(len(layer.shapes) + 1))
    kind = shapely.get_type_id(parts)
    area = (kind == 3) & (shapely.area(parts) > 0)
    line = (kind == 1) & ~shapely.is_empty(parts)
    with np.errstate(invalid="ignore"):  # NaN: not a word
        whole = ((lo + shift - reach >= margin_box[:2]) & (hi + shift + reach <= margin_box[2:])
                 ).all(axis=1)
    shapes = []
    # the shapes with a part in the window, the whole words and the rest (text), in order
    for i in np.flatnonzero((cuts[1:] > cuts[:-1]) | whole | ~drawn).tolist():
        shape = layer.shapes[i]
        mine = slice(cuts[i], cuts[i + 1])
        if isinstance(shape, Polygons):
            keep = area[mine]
            if not keep.any():
                continue
            fills = np.asarray(shape.fills, dtype=object)[at[mine][keep] - start[i]].tolist() \
                if shape.fills else None
            moved = shapely.transform(parts[mine][keep], lambda xy: xy + shift)
            shapes.append(polygons_from_shapely(moved, shape.style, fills))
        elif isinstance(shape, Polylines) and layer.name == WORDS:  # a word: whole or not
            if whole[i]:
                shapes.append(Polylines(shape.coords + shift, shape.offsets, shape.style))
        elif isinstance(shape, Polylines):
            kept = parts[mine][line[mine]]
            if len(kept):
                coords, idx = shapely.get_coordinates(kept, return_index=True)
                offsets = offsets_of(np.bincount(idx))
                shapes.append(Polylines(coords + shift, offsets, shape.style))
        elif isinstance(shape, Text):
            if window.contains(shapely.Point(shape.x, shape.y)):
                shapes.append(replace(shape, x=shape.x + shift[0], y=shape.y + shift[1]))
        elif isinstance(shape, Raster):  # the whole pixels that reach into the window
            part = shape.cropped(x0, y0, x1, y1)
            if part is not None:
                shapes.append(part.moved(*shift))
    return replace(layer, shapes=tuple(shapes))


def word_overlap(drawing: Drawing, least: float = 10.0) -> float:
    """The overlap (mm) at which every single-stroke word of ``drawing``'s first sheet lies
    whole on some page: at least ``least``, and more than the widest or tallest word."""
    words = [s for layer in drawing.sheets[0].layers if layer.name == WORDS
             for s in layer.shapes if isinstance(s, Polylines) and len(s.coords)]
    if not words:
        return least
    lo, hi = _extents(words)
    sizes = (hi - lo).max(axis=1) + [s.style.stroke_width for s in words]
    return max([least, *(math.ceil(x + 0.5) for x in sizes.tolist())])


def _extents(words: list[Polylines]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(W, 2) twice: every word's least and greatest point (each has points), all at once."""
    at = np.cumsum([0] + [len(s.coords) for s in words[:-1]])
    xy = np.concatenate([s.coords for s in words])
    return np.minimum.reduceat(xy, at), np.maximum.reduceat(xy, at)


def _clip(geoms: NDArray[np.object_], bounds: NDArray[np.float64], window, lines
          ) -> NDArray[np.object_]:
    """``shapely.intersection(geoms, window)`` (a box); ``lines``: whether they are lines (one
    bool for all, or one each). GEOS gives a line strictly inside the
    box back as it is when the line is simple and has no point twice in a row (it drops such
    repeats and splits lines where they cross or touch themselves): those lines, open ones
    only (to be safe: a closed one might come back starting elsewhere), are kept without
    asking it (most of a guide's numbers and dashes; tests/test_tiling_clip.py)."""
    out = geoms.copy()
    cut = np.ones(len(geoms), dtype=bool)
    lines = np.broadcast_to(np.asarray(lines, dtype=bool), (len(geoms),))
    if lines.any():
        x0, y0, x1, y1 = window.bounds
        within = np.flatnonzero(lines & (bounds[:, 0] > x0) & (bounds[:, 2] < x1)
                                & (bounds[:, 1] > y0) & (bounds[:, 3] < y1))
        coords, line = shapely.get_coordinates(geoms[within], return_index=True)
        repeats = (coords[1:] == coords[:-1]).all(axis=1) & (line[1:] == line[:-1])
        twice = np.bincount(line[1:][repeats], minlength=len(within)) > 0
        kept = shapely.is_simple(geoms[within]) & ~shapely.is_closed(geoms[within]) & ~twice
        cut[within[kept]] = False
    out[cut] = shapely.intersection(geoms[cut], window)
    return out


def _marks(page, margin, overlap, n, total, right, below, title) -> Layer:
    """Page ``n`` of ``total``'s marks: dashes where the window of page ``right`` (or
    ``below``; None: no page there) starts, the window's corner ticks, its label and the
    100 mm bar (in the outer half of ``MARK_MARGIN``)."""
    w, h = page
    x1, y1 = w - margin, h - margin
    segs = []
    if right is not None:  # the next column's window starts overlap mm before this one ends
        segs += _dashes((x1 - overlap, margin), (x1 - overlap, y1))
    if below is not None:
        segs += _dashes((margin, margin + overlap), (x1, margin + overlap))
    t = 4.0
    for x, y, sx, sy in ((margin, margin, 1, 1), (x1, margin, -1, 1), (margin, y1, 1, -1),
                         (x1, y1, -1, -1)):
        segs += [((x - sx * t, y), (x + sx * t, y)), ((x, y - sy * t), (x, y + sy * t))]
    bar_x, bar_y = margin, MARK_MARGIN / 2
    segs += [((bar_x, bar_y), (bar_x + 100.0, bar_y)), ((bar_x, bar_y - 1.5), (bar_x, bar_y + 1.5)),
             ((bar_x + 100, bar_y - 1.5), (bar_x + 100, bar_y + 1.5))]
    coords = np.array(segs, dtype=float).reshape(-1, 2)
    lines = Polylines(coords, np.arange(0, len(coords) + 1, 2, dtype=np.int64), MARK)
    grey = "#606060"
    name = f"{title} - page {n} of {total}; overlap {overlap:g} mm"
    shapes = [lines, Text(bar_x + 103.0, bar_y - 1.2, "100 mm", 2.5, fill=grey)]
    joins = ", ".join([f"page {right} on the right"] * (right is not None)
                      + [f"page {below} below"] * (below is not None))
    room = x1 - (bar_x + 103.0 + text_width("100 mm", 2.5) + 3.0)  # right of the bar
    if joins and room >= text_width(joins, 2.0):
        size = min(2.5, 2.5 * room / text_width(joins, 2.5))
        shapes.append(Text(x1, bar_y - 1.2, joins, size, "end", fill=grey))
    elif joins:  # a page too narrow for both: in its label
        name += f"; {joins}"
    shapes.append(Text(margin, h - MARK_MARGIN / 2 - 1.5, name, 2.5, fill=grey))
    return Layer("page-marks", "guide", tuple(shapes))


def _dashes(a, b, dash: float = 3.0, gap: float = 2.0) -> list:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    length = float(np.hypot(*(b - a)))
    starts = np.arange(0.0, length, dash + gap)
    ends = np.minimum(starts + dash, length)
    d = (b - a) / length
    return [(tuple(a + s * d), tuple(a + e * d)) for s, e in zip(starts, ends)]
