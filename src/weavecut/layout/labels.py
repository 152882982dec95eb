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

from functools import lru_cache

import numpy as np
import shapely
from reportlab.pdfbase.pdfmetrics import stringWidth

from ..numeric import affine, transform
from .drawing import Text

MIN_CAP = 2.5
"""The smallest cap height (mm) a printed label may have."""
CAP_RATIO = 0.72  # Helvetica cap height per em (the PDF writer sets size / 0.72)
WIDEN = 1.1  # margin for the SVG writer's DejaVu Sans, a little wider than Helvetica
DESCENT = 0.3  # share of the cap height below the baseline for texts with descenders
DESCENDERS = frozenset("gjpqy,;()[]{}/|_")


def text_width(text: str, size: float) -> float:
    """Width in mm of ``text`` at cap height ``size`` (the wider of the two writers' fonts)."""
    return stringWidth(text, "Helvetica", size / CAP_RATIO) * WIDEN


def _box_in_frame(text: str, size: float, anchor: str) -> tuple[float, float, float, float]:
    w = text_width(text, size)
    x0 = {"start": 0.0, "middle": -w / 2, "end": -w}[anchor]
    below = DESCENT if DESCENDERS.intersection(text) else 0.05
    return (x0, -below * size, x0 + w, size)


def _turn(xy, angle_deg: float, origin) -> np.ndarray:
    return transform(affine(angle_deg, np.asarray(origin, dtype=float)))(xy)


def text_box(t: Text) -> shapely.Polygon:
    """The rectangle ``t`` covers on the sheet (mm), turned with it."""
    x0, y0, x1, y1 = _box_in_frame(t.text, t.size, t.anchor)
    corners = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
    return shapely.Polygon(_turn(corners, t.angle, (t.x, t.y)))


@lru_cache(maxsize=4096)
def unit_box(text: str, angle: float) -> shapely.Polygon:
    """``text``'s box at cap height 1, centred on the origin, turned by ``angle`` degrees (kept:
    labels ask for the same few boxes many times)."""
    x0, y0, x1, y1 = _box_in_frame(text, 1.0, "middle")
    mid = (y0 + y1) / 2
    corners = np.array([[x0, y0 - mid], [x1, y0 - mid], [x1, y1 - mid], [x0, y1 - mid]])
    return shapely.Polygon(_turn(corners, angle, (0.0, 0.0)))


def centred_text(centre, text: str, size: float, angle: float = 0.0,
                 fill: str = "#000000") -> Text:
    """A ``Text`` whose box is centred on ``centre``, turned by ``angle`` degrees."""
    x0, y0, x1, y1 = _box_in_frame(text, size, "middle")
    base = _turn([[0.0, -(y0 + y1) / 2]], angle, centre)[0]
    return Text(float(base[0]), float(base[1]), text, size, "middle", float(angle), fill)


def upright(t: Text) -> Text:
    """``t`` turned by 180 degrees about its box centre if it would read upside down, so that its
    angle lies in (-90, 90]; the box covers the same rectangle either way (a turned text is
    anchored at its middle)."""
    angle = (t.angle + 180.0) % 360.0 - 180.0
    if -90.0 < angle <= 90.0 + 1e-9:
        return Text(t.x, t.y, t.text, t.size, t.anchor, angle, t.fill)
    centre = text_box(t).centroid
    return centred_text((centre.x, centre.y), t.text, t.size, angle % 360.0 - 180.0, t.fill)


def largest_fit(regions, shapes, centres, low: float, high, steps: int = 12) -> np.ndarray:
    """(n,) the largest scale in [low, high] (``high`` a number or one per shape) at which ``shapes[i]`` (unit shapes centred on the
    origin), scaled and moved to ``centres[i]``, lies inside ``regions[i]``; NaN where it does
    not fit even at ``low``. All n are bisected at once."""
    regions = np.asarray(regions, dtype=object)
    shapes = np.asarray(shapes, dtype=object)
    centres = np.asarray(centres, dtype=float).reshape(-1, 2)
    n = len(regions)
    if n == 0:
        return np.zeros(0)
    shapely.prepare(regions)
    owner = np.repeat(np.arange(n), shapely.get_num_coordinates(shapes))

    def fits(scale):
        placed = shapely.transform(shapes, lambda xy: xy * scale[owner, None] + centres[owner])
        return shapely.contains(regions, placed)

    top = np.broadcast_to(np.asarray(high, dtype=float), (n,))
    lo = np.full(n, float(low))
    hi = top.copy()
    ok_hi = fits(hi)
    ok_lo = fits(lo)
    for _ in range(steps):  # bisection steps, all labels at once
        mid = (lo + hi) / 2
        ok = fits(mid)
        lo = np.where(ok, mid, lo)
        hi = np.where(ok, hi, mid)
    return np.where(ok_hi, top, np.where(ok_lo, lo, np.nan))


def inner_centres(regions) -> np.ndarray:
    """(n, 2) the centre of the largest circle inside every region (where a label has most
    room); empty regions give the origin."""
    regions = np.asarray(regions, dtype=object)
    if len(regions) == 0:
        return np.zeros((0, 2))
    tolerance = np.maximum(np.sqrt(shapely.area(regions)) * 0.01, 1e-3)
    ok = ~shapely.is_empty(regions)
    out = np.zeros((len(regions), 2))
    if ok.any():
        lines = shapely.maximum_inscribed_circle(regions[ok], tolerance[ok])
        out[ok] = shapely.get_coordinates(shapely.get_point(lines, 0))
    return out


def wrap(text: str, width: float, size: float) -> list[str]:
    """``text`` broken at spaces into lines no wider than ``width`` mm at cap height ``size``."""
    out, line = [], ""
    for word in text.split(" "):
        trial = f"{line} {word}" if line else word
        if line and text_width(trial, size) > width:
            out.append(line)
            line = word
        else:
            line = trial
    return out + [line]
