"""Notches a pair of scissors can cut: a strip unfolded from a curved surface is slit where the
surface curves (:mod:`.unfold`), a V between two tiles as narrow as the curvature there. Where
that V is narrower than ``MIN_CUT`` at its mouth it is widened: each of its two sides is turned
away from the other about the V's tip, far enough that its mouth holds ``MIN_CUT``, and the
tile beside it gives up the thin wedge between its old and new side (its corner at the mouth
moves along the tile's next edge). Assembled, the two sides then leave a hairline gap instead
of meeting, which the eye does not see on the ball and the scissors no longer have to cut.
"""

from __future__ import annotations

import numpy as np
import shapely
from numpy.typing import NDArray
from shapely.geometry.polygon import orient

from ..errors import WeaveCutError

MIN_CUT = 3.0  # mm: the narrowest notch or neck scissors cut cleanly in paper
V = np.radians(60.0)  # a notch: a corner cut in from outside, its sides closer than this
STEP = np.radians(0.25)  # turns tried one after another to open a notch, then ...
TURNS = 40  # halvings of the turn that widens a notch (far below a micrometre)


class NotchError(WeaveCutError, ValueError):
    """A notch that cannot be widened without cutting through its tile; ``mouth`` its width
    (mm)."""

    def __init__(self, message: str, mouth: float):
        super().__init__(message)
        self.mouth = mouth


def _segment_distance(p, a, b) -> float:
    """Distance of point ``p`` from the segment ``a`` ``b``."""
    (dx, dy), (ex, ey) = b - a, p - a
    t = min(max((ex * dx + ey * dy) / max(dx * dx + dy * dy, 1e-300), 0.0), 1.0)
    return float(np.hypot(ex - t * dx, ey - t * dy))


def mouth(ring, k: int) -> float:
    """How wide the corner ``k`` of ``ring`` (n, 2) is for a cutter: the nearer of its two
    neighbours' distances from the other side (the width of a V's mouth; a wide corner's
    shorter side)."""
    n = len(ring)
    v, p, q = ring[k], ring[k - 1], ring[(k + 1) % n]
    return min(_segment_distance(p, v, q), _segment_distance(q, v, p))


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _turned(d, angle: float):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([c * d[0] - s * d[1], s * d[0] + c * d[1]])


def _hit(v, d, a, b):
    """Where the ray from ``v`` along ``d`` meets the segment ``a`` ``b``, or None."""
    e = b - a
    det = d[0] * -e[1] + d[1] * e[0]
    if abs(det) < 1e-12:
        return None
    r = a - v
    t = (r[0] * -e[1] + r[1] * e[0]) / det  # along the ray
    s = (d[0] * r[1] - d[1] * r[0]) / det  # along the segment
    return v + t * d if t > 0 and 0.0 <= s <= 1.0 else None


def _widen(ring, k: int, minimum: float):
    """``ring`` with the V at corner ``k`` opened until its mouth holds ``minimum``: the
    neighbours of ``k`` moved along the edges beyond them; None if a side would have to turn
    past the edge beyond its neighbour."""
    n = len(ring)
    v = ring[k]
    before, after = ring[k - 2], ring[(k + 2) % n]
    p, q = ring[k - 1], ring[(k + 1) % n]
    side = 1.0 if _cross(p - v, q - v) > 0 else -1.0  # q lies this way round from p

    def opened(turn):  # the mouth's corners with each side turned by ``turn`` away
        a = _hit(v, _turned(p - v, -side * turn), before, p)
        b = _hit(v, _turned(q - v, side * turn), q, after)
        return None if a is None or b is None else (a, b)

    def wide(points):
        a, b = points
        return min(_segment_distance(a, v, b), _segment_distance(b, v, a)) >= minimum

    high = STEP
    while True:  # a few steps, to the first turn that opens it wide enough
        points = opened(high)
        if points is None or high > np.pi / 2:
            return None  # a side reached the far end of the edge beyond it first
        if wide(points):
            break
        high += STEP
    low = high - STEP
    for _ in range(TURNS):
        mid = (low + high) / 2
        points = opened(mid)
        low, high = (mid, high) if points is None or not wide(points) else (low, mid)
    out = ring.copy()
    out[k - 1], out[(k + 1) % n] = opened(high)
    return out


def widen_notches(outline: shapely.Polygon, minimum: float = MIN_CUT) -> shapely.Polygon:
    """``outline`` with every V-shaped notch whose mouth is narrower than ``minimum`` (mm)
    opened to ``minimum`` (see the module's note).

    Raises
    ------
    NotchError if a notch cannot be opened that far within the tiles beside it
    """
    ring = np.asarray(orient(outline, 1.0).exterior.coords)[:-1]  # anticlockwise
    n = len(ring)
    changed = False
    for k in range(n):  # corners of one outline
        v, p, q = ring[k], ring[k - 1], ring[(k + 1) % n]
        u, w = p - v, q - v
        narrow = u[0] * w[0] + u[1] * w[1] > np.cos(V) * np.hypot(*u) * np.hypot(*w)
        if _cross(v - p, w) >= 0 or not narrow or mouth(ring, k) >= minimum:
            continue  # a convex corner (the ring runs anticlockwise), no V, or wide enough
        wider = _widen(ring, k, minimum)
        if wider is None:
            raise NotchError(f"a notch would be {mouth(ring, k):.1f} mm wide", mouth(ring, k))
        ring, changed = wider, True
    return shapely.Polygon(ring) if changed else outline


def notch_mouths(polygon) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """((m, 2) corners, (m,) their :func:`mouth`) of every notch of ``polygon``: a corner cut
    in from outside whose sides are less than ``V`` apart."""
    ring = np.asarray(orient(polygon, 1.0).exterior.coords)[:-1]  # anticlockwise
    u, w = np.roll(ring, 1, axis=0) - ring, np.roll(ring, -1, axis=0) - ring
    concave = u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0] > 0  # turning right, inward
    cosine = (u * w).sum(axis=1) / np.maximum(np.hypot(*u.T) * np.hypot(*w.T), 1e-300)
    corners = np.flatnonzero(concave & (cosine > np.cos(V)))
    return ring[corners], np.array([mouth(ring, int(k)) for k in corners], dtype=float)


def narrowest_notch(polygons) -> NDArray[np.float64]:
    """(N,) per polygon the narrowest :func:`mouth` of its notches (:func:`notch_mouths`), inf
    where it has none: the width of paper a blade must clear between the notch's two sides
    where the shorter one ends."""
    return np.array([notch_mouths(polygon)[1].min(initial=np.inf)
                     for polygon in np.asarray(polygons, dtype=object).tolist()], dtype=float)
