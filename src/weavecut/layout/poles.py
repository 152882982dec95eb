"""The centre of the largest circle inside a polygon (its pole of inaccessibility), exactly.

Inside a polygon the distance to its boundary is largest where three *sites* are nearest: three
edges, or edges and reflex corners (a convex corner is never the only nearest point of an
inside point). So the pole is among the centres of the circles tangent to three sites, each
found in closed form: three edges' lines give a linear system; with a corner the centre runs
on a line (two planes in (x, y, r)) and meets the corner's cone in a quadratic. Every such
centre is measured against the whole boundary and the farthest inside wins, the first of equal
ones (to ``GRID``) by x, then y: a rule that does not rest on the last bits of a float. For
the small polygons labels go in (up to ``MOST`` corners, no holes) this is a few hundred
candidates, all polygons at once; anything else is GEOS's grid search to ``TOLERANCE``.

>>> poles(shapely.polygons([[[0, 0], [4, 0], [4, 2], [0, 2]]])).tolist()  # a whole segment
[[1.0, 1.0]]
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np
import shapely
from numpy.typing import NDArray

from ..numeric import distinct, snap

MOST = 12  # corners of a polygon solved exactly (its candidates grow as their cube)
TOLERANCE = 0.01  # mm: GEOS's search for the others
REFLEX = 1e-6  # a corner turning left by less than this sine counts as reflex (straight ones
# too: a site too many only adds candidates, one too few could lose the pole)


def poles(polygons: NDArray[np.object_]) -> NDArray[np.float64]:
    """(N, 2) the centre of every polygon's largest inscribed circle.

    Parameters
    ----------
    polygons : (N,) shapely polygons
    """
    polygons = np.asarray(polygons, dtype=object).ravel()
    out = np.full((len(polygons), 2), np.nan)
    rings = shapely.get_exterior_ring(polygons)
    corners = shapely.get_num_coordinates(rings) - 1
    small = ((shapely.get_type_id(polygons) == 3) & (shapely.get_num_interior_rings(polygons) == 0)
             & (corners >= 3) & (corners <= MOST))
    for k in distinct(corners[small]).tolist():
        which = np.flatnonzero(small & (corners == k))
        xy = shapely.get_coordinates(rings[which]).reshape(len(which), k + 1, 2)[:, :k]
        out[which] = _exact(xy)
    rest = np.isnan(out[:, 0])
    if rest.any():
        circles = shapely.maximum_inscribed_circle(polygons[rest], tolerance=TOLERANCE)
        out[rest] = shapely.get_coordinates(shapely.get_point(circles, 0))
    return out


def _exact(xy: NDArray[np.float64]) -> NDArray[np.float64]:
    """(P, 2) the poles of P polygons of k corners ``xy`` (P, k, 2); NaN for one with an edge
    of no length (or no candidate inside)."""
    origin = xy[:, :1]
    xy = xy - origin  # near the origin: fewer digits lost in the planes' offsets
    x, y = xy[..., 0], xy[..., 1]
    area = (x * np.roll(y, -1, 1) - np.roll(x, -1, 1) * y).sum(axis=1) / 2
    xy = np.where((area < 0)[:, None, None], xy[:, ::-1], xy)  # counter-clockwise
    ax, ay = xy[..., 0], xy[..., 1]
    dx, dy = np.roll(ax, -1, 1) - ax, np.roll(ay, -1, 1) - ay
    length = np.hypot(dx, dy)
    turn = np.roll(dx, 1, 1) * dy - np.roll(dy, 1, 1) * dx
    reflex = turn < REFLEX * np.roll(length, 1, 1) * length
    out = np.full((len(xy), 2), np.nan)
    usable = (length > 0).all(axis=1)
    for m in distinct(reflex[usable].sum(axis=1)).tolist():  # a group per reflex count
        rows = np.flatnonzero(usable & (reflex.sum(axis=1) == m))
        at = np.nonzero(reflex[rows])[1].reshape(len(rows), m)
        sites = Sites.of(*(v[rows] for v in (ax, ay, dx, dy)), at)
        x, y, r, touched = _candidates(sites, m)
        most = np.sqrt(np.abs(area[rows]) / np.pi)  # the circle of the polygon's area
        out[rows] = _farthest(sites, xy.shape[1], x, y, r, touched, most)
    return out + origin[:, 0]


@dataclass(frozen=True)
class Sites:
    """What a pole's circle can touch, (P, k + m) arrays: a polygon's k edges, then its m
    reflex corners. Site s is nearest its points x with (x - p).u >= 0 and (x - q).v <= 0:
    an edge from p by u (= v) to q, a corner p (= q) between its edges u in and v out."""

    px: NDArray[np.float64]
    py: NDArray[np.float64]
    ux: NDArray[np.float64]
    uy: NDArray[np.float64]
    qx: NDArray[np.float64]
    qy: NDArray[np.float64]
    vx: NDArray[np.float64]
    vy: NDArray[np.float64]

    @classmethod
    def of(cls, ax, ay, dx, dy, at) -> Sites:
        """The sites of polygons with edges from (ax, ay) by (dx, dy) (P, k each), counter-
        clockwise, and reflex corners ``at`` (P, m)."""
        cx, cy = np.take_along_axis(ax, at, 1), np.take_along_axis(ay, at, 1)
        before = (at - 1) % ax.shape[1]
        return cls(*(np.concatenate(v, 1) for v in (
            (ax, cx), (ay, cy), (dx, np.take_along_axis(dx, before, 1)),
            (dy, np.take_along_axis(dy, before, 1)), (ax + dx, cx), (ay + dy, cy),
            (dx, np.take_along_axis(dx, at, 1)), (dy, np.take_along_axis(dy, at, 1)))))

    def near(self, x, y, at, slack: float = 1e-9) -> NDArray[np.bool_]:
        """(S,) whether the points (x, y) (S,) are nearest their sites, ``at`` (S,) into the
        flattened arrays (to ``slack`` of the sites' edge lengths)."""
        ux, uy, vx, vy = (v.ravel()[at] for v in (self.ux, self.uy, self.vx, self.vy))
        return (((x - self.px.ravel()[at]) * ux + (y - self.py.ravel()[at]) * uy
                 >= -slack * (ux * ux + uy * uy))
                & ((x - self.qx.ravel()[at]) * vx + (y - self.qy.ravel()[at]) * vy
                   <= slack * (vx * vx + vy * vy)))


def _candidates(sites: Sites, m: int) -> tuple:
    """x, y, r (P, C each): the circles tangent to three sites of each polygon (its edges'
    lines, its m reflex corners); NaN where none. touched (C, 3): their sites."""
    k = sites.px.shape[1] - m
    ax, ay, dx, dy = sites.px[:, :k], sites.py[:, :k], sites.ux[:, :k], sites.uy[:, :k]
    px, py = sites.px[:, k:], sites.py[:, k:]
    length = np.hypot(dx, dy)
    nx, ny = -dy / length, dx / length  # inward
    # planes A x + B y + C r = D in (x, y, r): an edge's line n.x - r = n.a (its points at
    # distance r inside), two corners' bisector 2 (q - p).x = |q|^2 - |p|^2 (r free); a
    # corner p is the cone |x - p| = r
    pairs = list(combinations(range(m), 2))
    i, j = [p for p, _ in pairs], [q for _, q in pairs]
    planes = [np.concatenate(v, 1) for v in (
        (nx, 2 * (px[:, j] - px[:, i])), (ny, 2 * (py[:, j] - py[:, i])),
        (-np.ones_like(ax), np.zeros((len(px), len(pairs)))),
        (nx * ax + ny * ay, px[:, j] ** 2 + py[:, j] ** 2 - px[:, i] ** 2 - py[:, i] ** 2))]
    bisector = {pair: k + n for n, pair in enumerate(pairs)}
    three = list(combinations(range(k), 3))
    # (plane, plane, corner) and the sites they touch
    cone = [((a, b, c), (a, b, k + c)) for a, b in combinations(range(k), 2) for c in range(m)]
    cone += [((a, bisector[c, d], c), (a, k + c, k + d)) for a in range(k) for c, d in pairs]
    cone += [((bisector[c, d], bisector[c, e], c), (k + c, k + d, k + e))
             for c, d, e in combinations(range(m), 3)]
    three = np.array(three, dtype=np.int64).reshape(-1, 3)
    cone, touched = (np.array([c[n] for c in cone], dtype=np.int64).reshape(-1, 3)
                     for n in (0, 1))
    x, y, r = _solve3(*(p[:, three[:, n]] for n in range(3) for p in planes))
    u, w = ([p[:, cone[:, n]] for p in planes] for n in (0, 1))
    on = _on_cone(u, w, px[:, cone[:, 2]], py[:, cone[:, 2]])
    return (*(np.concatenate([v, *(o[n] for o in on)], 1) for n, v in enumerate((x, y, r))),
            np.concatenate([three, touched, touched]))


def _det(a1, b1, c1, a2, b2, c2, a3, b3, c3) -> NDArray[np.float64]:
    """The determinant of the rows (a1, b1, c1), (a2, ...), (a3, ...), elementwise."""
    return a1 * (b2 * c3 - c2 * b3) - b1 * (a2 * c3 - c2 * a3) + c1 * (a2 * b3 - b2 * a3)


def _solve3(a1, b1, c1, d1, a2, b2, c2, d2, a3, b3, c3, d3) -> tuple:
    """x, y, r: the point of three planes a x + b y + c r = d, by Cramer's rule (elementwise,
    no LAPACK); NaN where they are dependent."""
    full = _det(a1, b1, c1, a2, b2, c2, a3, b3, c3)
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.where(full != 0, 1 / full, np.nan)
    return (_det(d1, b1, c1, d2, b2, c2, d3, b3, c3) * scale,
            _det(a1, d1, c1, a2, d2, c2, a3, d3, c3) * scale,
            _det(a1, b1, d1, a2, b2, d2, a3, b3, d3) * scale)


def _on_cone(u, w, px, py) -> tuple:
    """Twice (x, y, r): where the line of the planes ``u`` and ``w`` (four arrays each, A, B,
    C, D), (x, y, r) = q + t v, meets the cone |(x, y) - p| = r; NaN where it does not."""
    v = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    q = _solve3(*u, *w, *v, np.zeros_like(v[0]))
    ex, ey = q[0] - px, q[1] - py
    a = v[0] * v[0] + v[1] * v[1] - v[2] * v[2]
    b = v[0] * ex + v[1] * ey - v[2] * q[2]
    c = ex * ex + ey * ey - q[2] * q[2]
    disc = b * b - a * c
    real = disc >= -1e-12 * (b * b + np.abs(a * c))  # a tangent line's double root kept
    root = np.sqrt(np.maximum(disc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        big = np.where(real, -b - np.where(b < 0, -root, root), np.nan)  # without cancelling
        return tuple(tuple(qn + t * vn for qn, vn in zip(q, v)) for t in (big / a, c / big))


def _farthest(sites: Sites, k: int, x, y, r, touched, most) -> NDArray[np.float64]:
    """(P, 2) of each polygon (its k edges the first ``sites``) the candidate (x, y, r, P x C
    each, tangent to the sites ``touched`` (C, 3)) farthest inside it, the first of equal ones
    by x, then y; NaN where none is. Only a candidate with its radius at most ``most`` and
    nearest the sites it touches can win (the pole's circle is both), so only those are
    measured."""
    poly, col = np.nonzero(np.isfinite(r) & (r > 0) & (r <= most[:, None] * (1 + 1e-9)))
    cx, cy = x[poly, col], y[poly, col]
    for n in range(3):
        near = sites.near(cx, cy, poly * sites.px.shape[1] + touched[col, n])
        poly, col, cx, cy = poly[near], col[near], cx[near], cy[near]
    cx, cy = cx[:, None], cy[:, None]  # (S, 1) each
    ax, ay, dx, dy = (v[poly, :k] for v in (sites.px, sites.py, sites.ux, sites.uy))
    t = np.clip(((cx - ax) * dx + (cy - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0)  # (S, k)
    gx, gy = cx - ax - t * dx, cy - ay - t * dy
    far = np.sqrt((gx * gx + gy * gy).min(axis=1))
    # inside: an odd number of edges crossing the ray to the right of the centre
    with np.errstate(divide="ignore", invalid="ignore"):
        crossed = ((ay > cy) != (ay + dy > cy)) & (ax + (cy - ay) * dx / dy > cx)
    inside = np.count_nonzero(crossed, axis=1) % 2 == 1
    poly, cx, cy, far = poly[inside], cx[inside, 0], cy[inside, 0], far[inside]
    order = np.lexsort((snap(cy), snap(cx), -snap(far), poly))
    first = order[np.r_[True, poly[order][1:] != poly[order][:-1]]] if len(order) else order
    out = np.full((len(x), 2), np.nan)
    out[poly[first]] = np.column_stack([cx, cy])[first]
    return out
