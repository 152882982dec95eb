"""Labels that print: the extent a text takes, upright turning, and the largest size that fits.

A :class:`~weavecut.layout.drawing.Text` has its cap height as ``size``. Its extent is measured
with Helvetica's widths (what the PDF writer uses), widened by ``WIDEN`` so that the SVG
writer's DejaVu Sans fits too, and runs from the cap height down to the baseline (``DESCENT``
below it for a text with descenders).
Checks and placement both use :func:`text_box`, so a label that passes them prints inside its
box in either format.

>>> t = centred_text((10.0, 5.0), "A12", 3.0, 200.0)
>>> upright(t).angle, round(text_box(upright(t)).centroid.x, 6)
(20.0, 10.0)
"""

from __future__ import annotations

import re
from functools import lru_cache

import numpy as np
import shapely
from reportlab.pdfbase.pdfmetrics import stringWidth

from ..numeric import GRID, dot, turn
from .drawing import Text

MIN_CAP = 2.5
"""The smallest cap height (mm) a printed label may have."""
CAP_RATIO = 0.72  # Helvetica cap height per em (the PDF writer sets size / 0.72)
WIDEN = 1.1  # margin for the SVG writer's DejaVu Sans, a little wider than Helvetica
DESCENT = 0.3  # share of the cap height below the baseline for texts with descenders
DESCENDERS = frozenset("gjpqy,;()[]{}/|_")
PART = re.compile(r"\d+/\d+\W?")  # "1/2,": the number of a strip's part, kept with its strip


def text_width(text: str, size: float) -> float:
    """Width in mm of ``text`` at cap height ``size`` (the wider of the two writers' fonts)."""
    return stringWidth(text, "Helvetica", size / CAP_RATIO) * WIDEN


@lru_cache(maxsize=4096)
def _unit_extent(text: str) -> tuple[float, float]:
    """(width, depth below the baseline) of ``text`` at cap height 1."""
    return text_width(text, 1.0), DESCENT if DESCENDERS.intersection(text) else 0.05


def _frames(texts, sizes, anchors) -> tuple[np.ndarray, ...]:
    """(x0, y0, x1, y1), each (n,): the boxes of ``texts`` in their own frames (baseline start
    at the origin)."""
    extent = np.array([_unit_extent(t) for t in texts], dtype=float).reshape(-1, 2)
    sizes = np.broadcast_to(np.asarray(sizes, dtype=float), (len(extent),))
    w = extent[:, 0] * sizes
    anchors = np.broadcast_to(np.asarray(anchors), (len(extent),))
    x0 = np.where(anchors == "start", 0.0, np.where(anchors == "middle", -w / 2, -w))
    return x0, -extent[:, 1] * sizes, x0 + w, sizes


def _corners(x0, y0, x1, y1) -> np.ndarray:
    return np.stack([np.stack([x0, y0], -1), np.stack([x1, y0], -1), np.stack([x1, y1], -1),
                     np.stack([x0, y1], -1)], axis=1)


def text_boxes(texts) -> np.ndarray:
    """(n,) the rectangles ``texts`` cover on the sheet (mm), turned with them."""
    if not len(texts):
        return np.zeros(0, dtype=object)
    frame = _frames([t.text for t in texts], [t.size for t in texts], [t.anchor for t in texts])
    return shapely.polygons(turn(_corners(*frame), np.array([t.angle for t in texts])[:, None],
                                 np.array([(t.x, t.y) for t in texts])[:, None]))


def text_box(t: Text) -> shapely.Polygon:
    """The rectangle ``t`` covers on the sheet (mm), turned with it."""
    return text_boxes([t])[0]


def unit_boxes(texts, angles) -> np.ndarray:
    """(n, 4, 2) the corners of every text's box at cap height 1, centred on the origin, turned
    by its angle (degrees): the shapes :func:`largest_fit` scales."""
    return turn(unit_corners(texts), np.asarray(angles, dtype=float)[:, None])


def unit_corners(texts) -> np.ndarray:
    """(n, 4, 2) the corners of every text's box at cap height 1, centred on the origin, not
    turned (lower left, lower right, upper right, upper left)."""
    x0, y0, x1, y1 = _frames(texts, 1.0, "middle")
    mid = (y0 + y1) / 2
    return _corners(x0, y0 - mid, x1, y1 - mid)


def centred_texts(centres, texts, sizes, angles, fills) -> list[Text]:
    """A ``Text`` per text whose box is centred on its centre, turned by its angle (degrees)."""
    if not len(texts):
        return []
    x0, y0, x1, y1 = _frames(texts, sizes, "middle")
    base = turn(np.stack([np.zeros_like(y0), -(y0 + y1) / 2], -1), angles, centres)
    return [Text(x, y, t, z, "middle", a, f) for (x, y), t, z, a, f in
            zip(base.tolist(), texts, np.asarray(sizes, dtype=float).tolist(),
                np.asarray(angles, dtype=float).tolist(), fills)]


def centred_text(centre, text: str, size: float, angle: float = 0.0,
                 fill: str = "#000000") -> Text:
    """A ``Text`` whose box is centred on ``centre``, turned by ``angle`` degrees."""
    return centred_texts([centre], [text], [size], [angle], [fill])[0]


def upright(t: Text) -> Text:
    """``t`` turned by 180 degrees about its box centre if it would read upside down, so that its
    angle lies in (-90, 90]; the box covers the same rectangle either way (a turned text is
    anchored at its middle)."""
    return uprights([t])[0]


def uprights(texts) -> list[Text]:
    """:func:`upright` of each of ``texts``, the turned ones' boxes worked out at once."""
    out: list = []
    flip = []  # (index, angle) of the texts turned by half a turn
    for i, t in enumerate(texts):
        angle = (t.angle + 180.0) % 360.0 - 180.0
        if -90.0 < angle <= 90.0 + 1e-9:
            out.append(Text(t.x, t.y, t.text, t.size, t.anchor, angle, t.fill))
        else:
            out.append(None)
            flip.append((i, angle % 360.0 - 180.0))
    if flip:
        turned = [texts[i] for i, _ in flip]
        centres = shapely.get_coordinates(shapely.centroid(text_boxes(turned)))
        for (i, _), t in zip(flip, centred_texts(centres, [t.text for t in turned],
                                                 [t.size for t in turned], [a for _, a in flip],
                                                 [t.fill for t in turned])):
            out[i] = t
    return out


def largest_fit(regions, shapes, centres, low: float, high) -> np.ndarray:
    """(n,) the largest scale in [low, high] (``high`` a number or one per shape) at which
    ``shapes[i]`` (the corners (k, 2) of a polygon round the origin: shapes is (n, k, 2)),
    scaled and moved to ``centres[i]``, lies inside ``regions[i]``; NaN where it does not fit
    even at ``low`` (or the centre is outside).

    In closed form: as the scale grows from 0 the shape first leaves its region where a corner
    of one meets an edge of the other, so the answer is the least scale of such a contact, over
    every pair of a region's edge and a shape's edge; snapped down to ``GRID``. Equal fits (a
    module's copies ask for many) are worked out once."""
    regions = np.asarray(regions, dtype=object)
    centres = np.asarray(centres, dtype=float).reshape(-1, 2)
    n = len(regions)
    if n == 0:
        return np.zeros(0)
    w = np.asarray(shapes, dtype=float).reshape(n, -1, 2)
    top = np.broadcast_to(np.asarray(high, dtype=float), (n,))
    of, distinct = distinct_geoms(regions)
    first, back = _distinct_rows(np.column_stack([of, centres, w.reshape(n, -1), top]))
    return _least_scales(distinct, of[first], w[first], centres[first], low, top[first])[back]


def _distinct_rows(rows) -> tuple[np.ndarray, np.ndarray]:
    """(first, back): the first of each distinct row of ``rows`` (2-D, the same bytes), and
    which of those each row is."""
    rows = np.ascontiguousarray(rows)
    flat = rows.view(np.dtype((np.void, rows.dtype.itemsize * rows.shape[1]))).ravel()
    _, first, back = np.unique(flat, return_index=True, return_inverse=True)
    return first, back.reshape(-1)


def _least_scales(distinct, of, w, centres, low: float, top) -> np.ndarray:
    """:func:`largest_fit` of the regions ``distinct[of]``."""
    n = len(of)
    ra, rb, start, count = _edges(distinct)
    # the point of every region edge nearest a centre, once per region and centre (a site;
    # the fits of a text's turns share one) ...
    site, at = _distinct_rows(np.column_stack([of, centres]))
    span = count[of[site]]
    home = np.cumsum(span) - span  # the site's first edge in the rows below
    e = np.arange(span.sum()) - np.repeat(home - start[of[site]], span)
    q, d = ra[e] - centres[site][np.repeat(np.arange(len(site)), span)], rb[e] - ra[e]
    t = np.clip(-dot(q, d) / np.maximum(dot(d, d), 1e-300), 0.0, 1.0)
    near = q + t[:, None] * d  # the edge's point nearest the centre
    near = dot(near, near)
    # ... then every region edge of every fit that the shape can reach at ``top``, against
    # every corner of its shape (columns)
    fit = np.repeat(np.arange(n), count[of])
    e = np.arange(len(fit)) - np.repeat(np.cumsum(count[of]) - count[of] - home[at], count[of])
    reach = top * np.sqrt(dot(w, w).max(axis=1))
    keep = near[e] <= (reach[fit] * (1.0 + 1e-9)) ** 2
    fit, e = fit[keep], e[keep]
    (qx, qy), (dx, dy) = q[e].T, d[e].T
    rows = np.bincount(fit, minlength=n)
    wx, wy = w[fit, :, 0], w[fit, :, 1]
    qw = qx[:, None] * wy - qy[:, None] * wx  # q x w
    ww = (w[:, :, 0] * np.roll(w[:, :, 1], -1, 1) - w[:, :, 1] * np.roll(w[:, :, 0], -1, 1))[fit]
    with np.errstate(divide="ignore", invalid="ignore"):
        # a shape's corner w on a region's edge: s w = q + t d, 0 <= t <= 1
        wd = wx * dy[:, None] - wy * dx[:, None]
        s, t = (qx * dy - qy * dx)[:, None] / wd, qw / wd
        scale = np.where((s > 0.0) & (t >= -1e-9) & (t <= 1.0 + 1e-9), s, np.inf)
        # a region's corner on a shape's edge w w': q = s w + u (w' - w), 0 <= u <= s
        s, u = (np.roll(qw, -1, 1) - qw) / ww, -qw / ww
        scale = np.minimum(scale, np.where((s > 0.0) & (u >= -1e-9 * s) & (u <= s * (1 + 1e-9)),
                                           s, np.inf))
    least = np.full(n, np.inf)
    some = rows > 0
    if len(fit):
        least[some] = np.minimum.reduceat(scale.min(axis=1), (np.cumsum(rows) - rows)[some])
    least = np.floor(least * (1.0 - 1e-9) / GRID) * GRID
    inside = shapely.contains_xy(distinct[of], centres[:, 0], centres[:, 1])
    return np.where(inside & (least >= low), np.minimum(least, top), np.nan)


def distinct_geoms(geoms) -> tuple[np.ndarray, np.ndarray]:
    """(which of the distinct geometries each of ``geoms`` equals, the distinct geometries):
    equal means the same coordinates (the same WKB); each object is read once."""
    geoms = np.asarray(geoms, dtype=object)
    ids = np.fromiter(map(id, geoms), dtype=np.uint64, count=len(geoms))
    _, first, back = np.unique(ids, return_index=True, return_inverse=True)
    order = np.argsort(first)  # the objects in the order they first come
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    of, objects = rank[back.reshape(-1)], geoms[first[order]]
    by_wkb: dict[bytes, int] = {}
    same = np.array([by_wkb.setdefault(b, len(by_wkb)) for b in shapely.to_wkb(objects)],
                    dtype=np.int64)
    return same[of], objects[np.unique(same, return_index=True)[1]]


def _edges(geoms):
    """(edge starts, edge ends, each geometry's first edge and number of edges) of the
    polygons ``geoms``."""
    parts, part_of = shapely.get_parts(geoms, return_index=True)
    rings, ring_of = shapely.get_rings(parts, return_index=True)
    xy, at = shapely.get_coordinates(rings, return_index=True)
    same = at[:-1] == at[1:]  # consecutive corners of one ring: an edge
    count = np.bincount(part_of[ring_of[at[:-1][same]]], minlength=len(geoms))
    return xy[:-1][same], xy[1:][same], np.cumsum(count) - count, count


def inner_centres(regions) -> np.ndarray:
    """(n, 2) the centre of the largest circle inside every region (where a label has most
    room), its circle's radius within a hundredth of the square root of the region's area
    (1 µm at least) of the largest: a long, thin strip's centre stays across its middle;
    empty regions give the origin. Equal regions are worked out once."""
    regions = np.asarray(regions, dtype=object)
    if len(regions) == 0:
        return np.zeros((0, 2))
    of, distinct = distinct_geoms(regions)
    tolerance = np.maximum(np.sqrt(shapely.area(distinct)) * 0.01, 1e-3)
    ok = ~shapely.is_empty(distinct)
    out = np.zeros((len(distinct), 2))
    if ok.any():
        lines = shapely.maximum_inscribed_circle(distinct[ok], tolerance[ok])
        out[ok] = shapely.get_coordinates(shapely.get_point(lines, 0))
    return out[of]


def wrap(text: str, width: float, size: float) -> list[str]:
    """``text`` broken at spaces into lines no wider than ``width`` mm at cap height ``size``,
    never before a part number ("A7" | "1/2") nor after "p." ("p." | "5").

    >>> wrap("A21, A22 1/2, on p. 5, A23", 16.0, 2.5)  # not "A21, A22" | "1/2, on p." | "5, A23"
    ['A21,', 'A22 1/2,', 'on p. 5,', 'A23']
    """
    words: list[str] = []
    for word in text.split(" "):
        if words and (PART.fullmatch(word) or words[-1] == "p."):
            words[-1] += f" {word}"
        else:
            words.append(word)
    out, line = [], ""
    for word in words:
        trial = f"{line} {word}" if line else word
        if line and text_width(trial, size) > width:
            out.append(line)
            line = word
        else:
            line = trial
    return out + [line]
