"""The puzzle frame's outer outline, and the scale that gives it the asked size.

The frame of the paper's pentagon (``measure="diagonal"``) is the input outline offset
outward (mitred; bevelled at corners under 60 degrees) to ``frame_width`` beyond the ring's
outermost point, minus the union of the pieces (the hole): the surrounding pentagon. Any
other shape's frame is the ring's outer boundary (pieces and ring cells) offset by
``frame_width`` with round joins, its notches closed by a radius of ``frame_width``, so the
band beyond the ring is even all round and its outline follows the drawn shape (an offset
of the outline would be as wide as the ring's deepest point everywhere, and a drawn curve's
ring wanders off its straight runs). ``size`` is the frame's diagonal
(the largest distance between two corners of its outer outline): "the diagonal of the
surrounding pentagon measures 50 cm" (paper, section 6), or with ``measure="width"`` (every
other shape: a heart, a star) the finished piece's width. The model is scaled to make it so.
``pieces`` builds the puzzle (and the hole) with these.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..errors import WeaveCutError
from ..numeric import root


MEASURES = ("diagonal", "width")  # what --size measures of the frame's outer outline
MITRE_LIMIT = 2.0  # the frame's corners: mitre length / offset, beyond which they are bevelled


def diameter(polygon: shapely.Polygon) -> float:
    """The largest distance between two corners of a polygon's outline (its diagonal)."""
    xy = np.asarray(polygon.exterior.coords)
    return float(np.max(np.linalg.norm(xy[:, None] - xy[None], axis=2)))


def extent(polygon: shapely.Polygon, measure: str = "diagonal") -> float:
    """What ``size`` measures: the polygon's ``diameter``, or its width (x extent)."""
    if measure == "width":
        x0, _, x1, _ = polygon.bounds
        return float(x1 - x0)
    return diameter(polygon)


def frame_outline(outline: shapely.Polygon, depth: float, frame_width: float,
                  scale: float) -> shapely.Polygon:
    """The outline at ``scale`` offset by the ring's depth plus the frame width: mitred, and
    bevelled where a mitre would reach more than twice that far (corners under 60 degrees, a
    star's tips; the pentagon's and a square's corners keep their mitres)."""
    scaled = shapely.transform(outline, lambda xy: xy * scale)
    return shapely.buffer(scaled, depth * scale + frame_width, join_style="mitre",
                          mitre_limit=MITRE_LIMIT)


def ring_offset(envelope: shapely.Polygon, frame_width: float,
                scale: float) -> shapely.Polygon:
    """The ring's outer boundary at ``scale`` offset by ``frame_width`` (round), its notches
    closed with a radius of ``frame_width``: an even band that follows the ring."""
    scaled = shapely.transform(envelope, lambda xy: xy * scale)
    grown = shapely.buffer(shapely.buffer(scaled, 2.0 * frame_width, quad_segs=16),
                           -frame_width, quad_segs=16)
    # the band of a connected outline is connected; GEOS can leave a speck beside it when the
    # outline is scaled nearly to a point (the scale search's lower bracket)
    return shapely.Polygon(max(getattr(grown, "geoms", [grown]), key=shapely.area).exterior)


def frame_scale(base: shapely.Polygon, grow, size: float, measure: str = "diagonal",
                frame_width: float = 20.0) -> float:
    """mm per model unit that makes the frame's diagonal (or width: ``measure``) ``size`` mm.

    ``grow(scale)`` is the frame's outer outline: ``base`` (centred model units) scaled, then
    offset by the fixed frame width (and, for the pentagon, the scaled ring depth); its
    diagonal and width grow monotonically with the scale, so a bracketing root search finds
    it to far below 0.01 mm."""
    def excess(scale: float) -> float:
        return extent(grow(scale), measure) - size

    high = size / extent(base, measure)  # the base alone already spans ``size``
    low = high * 1e-9
    if excess(low) >= 0:
        raise WeaveCutError(f"a frame of {size:g} mm {measure} leaves no room for the pieces "
                            f"inside a {frame_width:g} mm frame; use a larger --size or a "
                            "narrower --frame")
    return root(excess, low, high, xtol=1e-12 * high, rtol=1e-14)
