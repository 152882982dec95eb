"""Label tabs: a strip whose ID no own tile holds carries it on a small rectangle cut with the
strip at one of its end edges (cut off after weaving)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import shapely

from ..numeric import dot
from ..layout.contrast import text_colour_on
from ..layout.drawing import Text
from ..layout.labels import MIN_CAP, centred_text, unit_corners
from .strips import Strip


FLAP_MARGIN = 0.6  # mm between a label tab's text and its edges
FLAP_STEP = 1.5  # mm, the least step between a label tab's corner and its edge's end
FLAP_CHAMFER = 1.0  # the least rise per overhang of a label tab's chamfer (tan 45 degrees)
FLAP_LIFT = 2.0  # a tab's chamfers may lift its text box at most this share of its depth
FLAP_REACH = 1.5  # a label tab's base may reach past its edge (along its line) up to this share
END_FACING = 0.9  # cosine: a strand's end edge faces the way the strand leaves its last tile


def label_flap(strip: Strip, text: str) -> tuple[Strip, Text] | None:
    """(``strip`` with a label tab, the tab's ``text`` at ``MIN_CAP``), or None where no end
    edge takes one. The tab is a rectangle on a free end edge of the strip's first or last tile
    (the edge the strand leaves by, shared with no other tile of the strip; not a glue band's),
    just large enough for the text along or across the edge plus ``FLAP_MARGIN``, outside every
    tile of the strip; the smallest tab that fits wins."""
    along, high = (np.ptp(unit_corners([text])[0], axis=0) * MIN_CAP).tolist()
    n = len(strip.tiles)
    ends = [i for i in sorted({0, n - 1}) if not (strip.glue is not None and i == n - 1)]
    body = shapely.union_all(strip.tiles)
    best = None
    for i in ends:  # two ends
        tile = strip.tiles[i]
        if tile.geom_type != "Polygon":
            continue
        ring = np.asarray(tile.exterior.coords)
        a, b = ring[:-1], ring[1:]
        before, after = np.roll(a, 1, axis=0), np.roll(b, -1, axis=0)  # beyond each edge's ends
        mid = (a + b) / 2
        length = np.hypot(*(b - a).T)
        unit = (b - a) / np.maximum(length, 1e-12)[:, None]
        normal = np.column_stack([unit[:, 1], -unit[:, 0]])
        centre = np.asarray(tile.centroid.coords[0])
        normal *= np.sign(dot(normal, mid - centre))[:, None]
        others = shapely.union_all(np.delete(strip.tiles, i))
        free = shapely.distance(shapely.points(mid), others) > 1e-6 * max(strip.length, 1.0) \
            if n > 1 else np.ones(len(mid), dtype=bool)
        if n > 1:
            nb = np.asarray(strip.tiles[1 if i == 0 else n - 2].centroid.coords[0])
            away = (centre - nb) / max(float(np.hypot(*(centre - nb))), 1e-12)
            facing = dot(normal, away) >= END_FACING
        else:
            facing = np.ones(len(mid), dtype=bool)
        for e in np.flatnonzero(free & facing).tolist():  # an edge or two
            # text along the edge, or across it: (base on the edge, depth, text angle)
            for base, depth, direction in ((along, high, unit[e]), (high, along, normal[e])):
                base, depth = base + 2 * FLAP_MARGIN, depth + 2 * FLAP_MARGIN
                if base > FLAP_REACH * length[e]:
                    continue
                flap, lift, edge = _tab(a[e], b[e], normal[e], base, depth,
                                        before[e], after[e])
                if flap is None or shapely.intersection(flap, body).area > 1e-6 * flap.area:
                    continue
                if best is None or flap.area < best[0].area - 1e-9:
                    angle = float(np.degrees(np.arctan2(direction[1], direction[0])))
                    best = (flap, edge, mid[e] + normal[e] * (lift + depth / 2), angle)
    if best is None:
        return None
    flap, edge, centre, angle = best
    fill = tab_fill(strip)
    label = centred_text(centre, text, MIN_CAP, angle, text_colour_on(fill))
    return replace(strip, flap=flap, flap_edge=edge, flap_fill=fill), label


def tab_fill(strip: Strip) -> str:
    """A label tab's fill: the strip's colour (its first own tile's)."""
    return next((f for f, o in zip(strip.fills, strip.over.tolist()) if o), "#ffffff")


def _tab(a, b, normal, base, depth, before, after):
    """(tab, lift, line where it meets its tile) on the tile edge from ``a`` to ``b`` (its
    outside towards ``normal``; ``before`` and ``after`` the tile's corners beyond ``a`` and
    ``b``) holding a ``base`` x ``depth`` box for its text, ``lift`` mm out from the edge; tab
    None where it cannot be made. A box no wider than the edge stands on it, its corners on
    the edge's ends or at least ``FLAP_STEP`` from them (no step a knife tears at). A wider box
    (at least ``FLAP_STEP`` past each end: room for a laser's engraving margin) is lifted off
    the edge and joined to the edge's ends by chamfers (a six-sided tab): a
    rectangle overhanging the edge would leave a V between its shoulder and the tile's next
    edge, a notch a blade cannot clear. Each chamfer rises at ``FLAP_CHAMFER`` (45 degrees)
    or more, and stands square to the tile's next edge or farther from it: the corner at the
    edge's end is then no notch (its sides 90 degrees apart or more; a notch is under
    ``notches.V``, 60)."""
    edge = float(np.hypot(*(b - a)))
    unit = (b - a) / max(edge, 1e-12)
    mid = (a + b) / 2
    if base <= edge:
        base = edge if base > edge - 2 * FLAP_STEP else base
        p, q = mid - unit * base / 2, mid + unit * base / 2
        tab = shapely.Polygon([p, q, q + normal * depth, p + normal * depth])
        return tab, 0.0, shapely.LineString([p, q])
    base = max(base, edge + 2 * FLAP_STEP)  # room round the text to engrave it on card too
    over = (base - edge) / 2
    rise = [FLAP_CHAMFER]
    for corner, end, out in ((before, a, -unit), (after, b, unit)):  # the edge's two ends
        side = corner - end
        across = -float(dot(side, normal))  # the tile lies on the side away from ``normal``
        if across <= 1e-9 * edge:
            return None, 0.0, None  # a straight or reflex corner: no chamfer squares with it
        rise.append(float(dot(side, out)) / across)  # the chamfer square to the tile's next edge
    lift = max(over * max(rise) * (1 + 1e-6), FLAP_STEP)  # square and a hair (no notch by
    # rounding); no chamfer shorter than a step
    if lift > FLAP_LIFT * depth:
        return None, 0.0, None
    tab = shapely.Polygon([a, b, b + unit * over + normal * lift,
                           b + unit * over + normal * (lift + depth),
                           a - unit * over + normal * (lift + depth),
                           a - unit * over + normal * lift])
    return tab, lift, shapely.LineString([a, b])
