"""An oracle of what a blade cannot cut, written apart from ``papermodel.strips`` and
``papermodel.notches``: plain shapely calls and a loop over corners.

- a neck: an outline shrunk by half a width and grown back falls into two pieces;
- a sliver: the part of an outline a disc that wide cannot reach sticks out more than
  ``sliver`` mm beyond what it reaches;
- a notch: a corner cut in from outside whose two sides are less than 60 degrees apart, where
  the shorter side's far end lies nearer than the width to the other side (the paper the blade
  must clear between them);
- a gap: two outlines on one sheet nearer than the packer's gap.
"""

from __future__ import annotations

import numpy as np
import shapely


def necks(outline: shapely.Polygon, width: float) -> int:
    """How many pieces more than one the part of ``outline`` that discs ``width`` across
    inside it cover falls into (shrunk by ``width / 2``, grown back: a neck between two parts
    the discs reach; a joint as short as it is narrow reads as none, as in ``strips.holds``)."""
    core = outline.buffer(-width / 2, quad_segs=16).buffer(width / 2, quad_segs=16)
    return max(len(shapely.get_parts(core)) - 1, 0)


def sliver_reach(outline: shapely.Polygon, width: float) -> float:
    """How far (mm) the part of ``outline`` that no disc ``width`` across inside it covers
    reaches beyond the part the discs cover (every corner of the outline, measured)."""
    core = outline.buffer(-width / 2, quad_segs=16).buffer(width / 2, quad_segs=16)
    if core.is_empty:
        return np.inf
    corners = shapely.points(np.asarray(outline.exterior.coords))
    return float(shapely.distance(corners, core).max())


def notch_mouths(outline: shapely.Polygon) -> list[float]:
    """The mouth of every notch of ``outline``: per corner turning inward with sides less than
    60 degrees apart, the nearer of its neighbours' distances from the other side."""
    ring = np.asarray(outline.exterior.coords)[:-1]
    if shapely.LinearRing(ring).is_ccw is False:
        ring = ring[::-1]
    out = []
    n = len(ring)
    for k in range(n):
        v, p, q = ring[k], ring[k - 1], ring[(k + 1) % n]
        a, b = p - v, q - v
        turns_in = (v - p)[0] * (q - v)[1] - (v - p)[1] * (q - v)[0] < 0
        if turns_in and a @ b > np.cos(np.pi / 3) * np.hypot(*a) * np.hypot(*b):  # under 60
            out.append(min(shapely.Point(p).distance(shapely.LineString([v, q])),
                           shapely.Point(q).distance(shapely.LineString([v, p]))))
    return out


def problems(outlines, width: float, sliver: float, gap: float | None = None) -> list[str]:
    """What a blade cannot cut among ``outlines`` (one sheet's) at ``width``: necks, slivers,
    notches, and (with ``gap``) two outlines nearer than ``gap``."""
    out = []
    for i, o in enumerate(outlines):
        if necks(o, width):
            out.append(f"outline {i}: a neck under {width:g} mm")
        if sliver_reach(o, width) > sliver:
            out.append(f"outline {i}: a sliver under {width:g} mm")
        # a notch opened to the width by bisection (the ball's) may read a nanometre under it
        out += [f"outline {i}: a notch {m:.2f} mm wide" for m in notch_mouths(o)
                if m < width - 1e-6]
    if gap is not None and len(outlines) > 1:
        tree = shapely.STRtree(outlines)
        pairs = tree.query(outlines, predicate="dwithin", distance=gap - 1e-6)
        out += [f"outlines {i} and {j}: {outlines[i].distance(outlines[j]):.2f} mm apart"
                for i, j in pairs.T.tolist() if i < j]
    return out
