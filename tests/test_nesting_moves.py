"""Parts moved to their places all at once are the parts moved one by one with their own
affine matrix, to the last bit (quarter turns exact, holes and empty slots kept)."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout.nesting import moved
from weavecut.numeric import affine, transform


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 2**16), st.sampled_from([0.0, 90.0, -90.0, 180.0, 33.3,
                                                                   -0.0, 1e-9]),
                          st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.booleans()),
                max_size=6))
def test_all_at_once_as_one_by_one(specs):
    parts, angles, shifts = [], [], []
    for seed, angle, dx, dy, empty in specs:
        rng = np.random.default_rng(seed)
        ring = shapely.MultiPoint(rng.uniform(-50, 50, (5, 2))).buffer(3, quad_segs=2)
        parts.append(None if empty else shapely.difference(ring, shapely.box(-1, -1, 1, 1)))
        angles.append(angle)
        shifts.append((dx, dy))
    parts = np.array(parts, dtype=object)
    got = moved(parts, np.array(angles), np.array(shifts).reshape(-1, 2))
    for g, p, a, t in zip(got, parts, angles, shifts):
        if p is None:
            assert g is None
            continue
        want = shapely.transform(p, transform(affine(a, t)))
        assert shapely.equals_exact(g, want, tolerance=0.0)
        assert np.array_equal(shapely.get_coordinates(g), shapely.get_coordinates(want))
