"""How large a label may be and where it goes, against computations of their own: the largest
scale at which a shape fits a region (``labels.largest_fit``) against bisection on shapely's
``covers`` and a hand-worked L-shaped piece; a fitted stroke label's ink (``strokefont.labels``,
as drawn) inside its piece less the margin; the centre of the largest inscribed circle
(``labels.inner_centres``) against the incircle and a tapering strip's circle worked out by
hand (#34: the layout package's survivors)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from weavecut.layout.labels import inner_centres, largest_fit
from weavecut.layout.strokefont import fit_labels, labels
from weavecut.numeric import GRID

SQUARE = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])
# an L: the square (0, 0)-(10, 10) less its upper right (4, 4)-(10, 10); (4, 4) is reflex
ELL = shapely.Polygon([(0, 0), (10, 0), (10, 4), (4, 4), (4, 10), (0, 10)])


def _fits(region, shape, centre, s) -> bool:
    return bool(region.covers(shapely.Polygon(np.asarray(centre) + s * shape)))


def bisected(region, shape, centre, top) -> tuple[float, float]:
    """(lo, hi): ``shape`` (convex, round the origin) at ``centre`` fits ``region`` scaled by lo
    and not by hi (hi = inf when it fits at ``top``), hi - lo < 1e-10; a larger scale of a
    convex shape covers the smaller, so the scales that fit are one interval from 0."""
    if _fits(region, shape, centre, top):
        return top, math.inf
    lo, hi = 0.0, top
    while hi - lo > 1e-10:
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if _fits(region, shape, centre, mid) else (lo, mid)
    return lo, hi


def test_a_square_in_an_l_shaped_piece_is_as_large_as_worked_out_by_hand():
    # centred at (2, 3) the square [2 - s, 2 + s] x [3 - s, 3 + s] meets x = 0 at s = 2, where
    # it is [0, 4] x [1, 5]: inside the L, its top right corner on the L's inner side x = 4.
    # Its upper left corner crosses the line y = 4 (the L's inner edge, extended past the
    # reflex corner into the piece) at s = 1: not a contact
    got = largest_fit([ELL], [SQUARE], [(2.0, 3.0)], 0.0, 100.0)
    assert 2.0 - 2 * GRID <= got[0] <= 2.0  # snapped down to the grid
    assert np.isnan(largest_fit([ELL], [SQUARE], [(2.0, 3.0)], 2.5, 100.0)[0])  # not at 2.5
    assert np.isnan(largest_fit([ELL], [SQUARE], [(7.0, 7.0)], 0.0, 100.0)[0])  # outside


@st.composite
def star_fits(draw):
    """A region star-shaped round the origin (corners at sorted angles, radii 2-20 mm: reflex
    corners wherever a radius dips), a turned rectangle round the origin, a centre near the
    origin, and the bounds ``low`` and ``top``."""
    n = draw(st.integers(3, 10))
    gaps = np.array(draw(st.lists(st.floats(0.2, 1.0), min_size=n, max_size=n)))
    angles = 2 * np.pi * np.cumsum(gaps) / gaps.sum()
    radii = np.array(draw(st.lists(st.floats(2.0, 20.0), min_size=n, max_size=n)))
    region = shapely.Polygon(np.column_stack([np.cos(angles), np.sin(angles)]) * radii[:, None])
    w, h, turn = draw(st.floats(0.2, 3.0)), draw(st.floats(0.2, 3.0)), draw(st.floats(0, 180))
    c, s = math.cos(math.radians(turn)), math.sin(math.radians(turn))
    shape = (SQUARE * (w, h)) @ np.array([[c, s], [-s, c]])
    centre = (draw(st.floats(-1.5, 1.5)), draw(st.floats(-1.5, 1.5)))
    low = draw(st.floats(0.0, 2.0))
    return region, shape, centre, low, low + draw(st.floats(0.0, 20.0))


@settings(deadline=None)
@given(st.lists(star_fits(), min_size=1, max_size=4))
def test_the_largest_fit_is_the_largest_scale_shapely_finds_covered(cases):
    regions, shapes, centres, lows, tops = zip(*cases)
    expect = []
    for region, shape, centre, low, top in cases:
        lo, hi = bisected(region, shape, centre, top)
        assume(abs(lo - low) > 1e-6)  # not a tie with ``low``
        expect.append((lo, hi, region.contains(shapely.Point(centre)) and lo > low))
    for low in set(lows):  # one call per low bound, each region with its own top
        at = [k for k, v in enumerate(lows) if v == low]
        got = largest_fit([regions[k] for k in at], [shapes[k] for k in at],
                          [centres[k] for k in at], low, [tops[k] for k in at])
        for k, g in zip(at, got):
            lo, hi, fits = expect[k]
            if not fits:
                assert np.isnan(g), (k, lo)
                continue
            # snapped down to the grid, never past the first scale that pokes out
            assert lo - 2 * GRID - 1e-9 * lo <= g <= min(hi, tops[k]), (k, g, lo, hi)


def _ink_outside(polygons, texts, margin, max_height, pad) -> list[float]:
    """Per text, how far its drawn strokes (points) reach into the margin or the pad: the
    largest shortfall of a stroke point's room inside ``polygon`` less ``margin`` (shapely's
    mitred inward buffer) against ``pad`` times its height, or 0."""
    heights, centres, angles = fit_labels(np.array(polygons, dtype=object), texts, margin,
                                          max_height, pad)
    coords, offsets, owner = labels(texts, centres, heights, angles)
    point_owner = np.repeat(owner, np.diff(offsets))
    out = []
    for k, polygon in enumerate(polygons):
        assert heights[k] > 0, k
        inner = polygon.buffer(-margin, join_style="mitre")
        pts = shapely.points(coords[point_owner == k])
        room = np.where(shapely.contains(inner, pts), shapely.distance(inner.exterior, pts),
                        -shapely.distance(inner, pts))
        out.append(max(0.0, float((pad * heights[k] - room).max())))
    return out


def test_a_fitted_label_keeps_its_margin_where_a_slope_cuts_its_lower_right():
    # pieces whose slanted side passes the label's lower right corner: the right triangle
    # above y = x, a square with its upper right corner cut (a label turned along its long
    # axis has the cut at its lower right)
    pieces = [shapely.Polygon([(0, 0), (0, 40), (40, 40)]),
              shapely.Polygon([(0, 0), (30, 0), (30, 12), (12, 30), (0, 30)])]
    for pad in (0.0, 0.1):
        assert _ink_outside(pieces, ["A12", "42"], 1.0, 100.0, pad) == pytest.approx(
            [0.0, 0.0], abs=1e-6)


@settings(deadline=None)
@given(st.lists(star_fits(), min_size=1, max_size=3),
       st.lists(st.sampled_from(["12", "A7", "42", "Bq", "ZZ1"]), min_size=3, max_size=3),
       st.sampled_from([0.0, 0.5]), st.sampled_from([0.0, 0.15]))
def test_fitted_labels_lie_inside_their_pieces_less_the_margin(cases, texts, margin, pad):
    pieces = [region for region, *_ in cases]
    assume(all(p.buffer(-margin - 0.5).area > 0 for p in pieces))
    got = _ink_outside(pieces, texts[:len(pieces)], margin, 30.0, pad)
    assert got == pytest.approx([0.0] * len(pieces), abs=1e-6)


def _room(region, centre) -> float:
    return float(region.exterior.distance(shapely.Point(centre)))


def test_the_inner_centre_of_a_triangle_is_its_incentre():
    a, b, c = np.array([0.0, 0.0]), np.array([40.0, 0.0]), np.array([10.0, 25.0])
    la, lb, lc = (float(np.hypot(*v)) for v in (b - c, c - a, a - b))
    incentre = (la * a + lb * b + lc * c) / (la + lb + lc)
    area = 40.0 * 25.0 / 2
    radius = 2 * area / (la + lb + lc)
    got, = inner_centres([shapely.Polygon([a, b, c])])
    tolerance = math.sqrt(area) / 100
    assert radius - tolerance <= _room(shapely.Polygon([a, b, c]), got) <= radius
    assert float(np.hypot(*(got - incentre))) < 5 * tolerance


def test_a_long_tapering_strips_centre_has_room_to_within_a_hundredth_of_its_size():
    # 353.7 mm long, 0.6 mm wide at its left end, 0.7 at x = 217.4 and 1 at its right end:
    # the largest circle touches the bottom y = 0, the right end and the top's last edge,
    # slope m: its radius r solves 1 - m r - r = r sqrt(1 + m^2). Within a hundredth of the
    # square root of the strip's area (not of its length: shapely's default, a thousandth of
    # the longest side, leaves the centre 1.24 of that from the best)
    strip = shapely.Polygon([(0, 0), (353.7, 0), (353.7, 1.0), (217.4, 0.7), (0, 0.6)])
    m = 0.3 / 136.3
    radius = 1.0 / (1.0 + m + math.sqrt(1.0 + m * m))
    tolerance = math.sqrt(strip.area) / 100
    got, = inner_centres([strip])
    assert radius - tolerance <= _room(strip, got) <= radius + 1e-9
    assert inner_centres([strip, strip]).tolist() == [got.tolist()] * 2
