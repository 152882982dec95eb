"""The poles of polygons (``layout/poles.py``) against GEOS's grid search: the exact centre's
circle is never smaller than the one GEOS finds and at most its tolerance larger, on random
star-shaped polygons (reflex corners included) of every size solved exactly; a tie is broken
by the rule, not by the order of the corners."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout.poles import MOST, TOLERANCE, poles

FINE = 1e-4  # mm: GEOS's search here, finer than the tolerance the kits use


def _radius(polygons, centres) -> np.ndarray:
    """The distance from every centre to its polygon's boundary (0 where outside)."""
    inside = shapely.contains_xy(polygons, centres[:, 0], centres[:, 1])
    return np.where(inside, shapely.distance(shapely.points(centres),
                                             shapely.boundary(polygons)), 0.0)


@st.composite
def star(draw) -> shapely.Polygon:
    """A star-shaped polygon of 3..MOST corners round a random centre, some of them reflex."""
    k = draw(st.integers(3, MOST))
    turns = np.sort(draw(st.lists(st.floats(0, 1, exclude_max=True), min_size=k, max_size=k,
                                  unique_by=lambda t: round(t, 3))))
    radii = np.array(draw(st.lists(st.floats(1, 30), min_size=k, max_size=k)))
    centre = draw(st.tuples(st.floats(-200, 200), st.floats(-200, 200)))
    angle = 2 * np.pi * turns
    polygon = shapely.Polygon(np.column_stack([np.cos(angle), np.sin(angle)]) * radii[:, None]
                              + centre)
    if draw(st.booleans()):
        polygon = polygon.reverse()  # clockwise too
    return polygon


@settings(max_examples=150, deadline=None)
@given(st.lists(star(), min_size=1, max_size=6))
def test_the_pole_is_the_largest_circle_geos_finds_within_its_tolerance(polygons):
    polygons = np.array([p for p in polygons if p.is_valid and p.area > 1.0], dtype=object)
    if not len(polygons):
        return
    geos = shapely.maximum_inscribed_circle(polygons, tolerance=FINE)
    r_geos = shapely.length(geos)  # GEOS's centre's true distance: at most the largest
    r = _radius(polygons, poles(polygons))
    assert (r >= r_geos - 1e-9).all()
    assert (r <= r_geos + FINE + 1e-9).all()


def test_a_circle_held_by_reflex_corners():
    """A cross: the largest circle sits at its middle, held by the four reflex corners alone
    (no edge touches it), radius sqrt(2)."""
    arm = [(1, -1), (3, -1), (3, 1), (1, 1), (1, 3), (-1, 3), (-1, 1), (-3, 1), (-3, -1),
           (-1, -1), (-1, -3), (1, -3)]
    cross = shapely.Polygon(arm)
    centre = poles(np.array([cross]))[0]
    assert np.allclose(centre, [0, 0], atol=1e-12)
    assert np.isclose(_radius(np.array([cross]), centre[None])[0], np.sqrt(2), atol=1e-12)


def test_a_tie_goes_to_the_least_x_then_y_whatever_the_corners_order():
    """A 4 x 2 rectangle's largest circles have their centres on a whole segment,
    (1, 1)-(3, 1); a 2 x 4 one's on (1, 1)-(1, 3). The first by x, then y, in any order and
    direction of the corners."""
    wide = [(0, 0), (4, 0), (4, 2), (0, 2)]
    tall = [(0, 0), (2, 0), (2, 4), (0, 4)]
    for corners, want in ((wide, [1.0, 1.0]), (tall, [1.0, 1.0])):
        for turn in range(4):
            ring = corners[turn:] + corners[:turn]
            for ring in (ring, ring[::-1]):
                assert poles(np.array([shapely.Polygon(ring)])).tolist() == [want]
    square = shapely.Polygon([(10, 10), (12, 10), (12, 12), (10, 12)])
    assert poles(np.array([square])).tolist() == [[11.0, 11.0]]


def test_others_go_to_geos():
    """Past ``MOST`` corners, with a hole or in parts, a polygon's pole is GEOS's (to
    ``TOLERANCE``)."""
    others = np.array([shapely.Point(0, 0).buffer(5),  # 64 corners
                       shapely.Point(0, 0).buffer(5).difference(shapely.Point(1, 0).buffer(1)),
                       shapely.MultiPolygon([shapely.box(0, 0, 1, 1), shapely.box(3, 0, 6, 3)])],
                      dtype=object)
    geos = shapely.maximum_inscribed_circle(others, tolerance=TOLERANCE)
    assert np.array_equal(poles(others), shapely.get_coordinates(shapely.get_point(geos, 0)))
