"""Clipping a printed page's window: what tiling keeps of every line is what GEOS's
intersection with the window gives, to the last bit, whether GEOS is asked (lines across the
edge, lines that touch or cross themselves, closed ones, ones with a point twice in a row)
or the line is kept as it is (simple, open, strictly inside)."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout.tiling import _clip

inside = st.sampled_from([1.0, 2.0, 3.0, 5.5, 9.5])  # a coarse grid: repeats and crossings
point = st.one_of(st.tuples(inside, inside), st.tuples(
    st.sampled_from([0.0, -0.0, 10.0, 11.0, 2.0]), st.floats(-1.0, 11.0)))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.lists(point, min_size=2, max_size=6), max_size=8), st.booleans())
def test_lines_kept_as_geos_clips_them(lines, close):
    geoms = np.array([shapely.LineString(line + line[:1] if close else line) for line in lines],
                     dtype=object)
    window = shapely.box(0.0, 0.0, 10.0, 10.0)
    got = _clip(geoms, shapely.bounds(geoms).reshape(-1, 4), window, True)
    want = shapely.intersection(geoms, window)
    for g, w in zip(got, want):
        assert shapely.get_type_id(g) == shapely.get_type_id(w)
        assert np.array_equal(shapely.get_coordinates(g), shapely.get_coordinates(w))
        assert shapely.equals_exact(g, w, tolerance=0.0) or (g.is_empty and w.is_empty)
