"""Numbers written a whole array at once: each is what ``repr`` writes of the value rounded by
``np.round`` (no negative zero; a whole number without ".0" unless asked), for any value it
takes on; the ones it leaves (too many digits, an exponent, not finite) are named."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.export.numbers import shortest

values = st.lists(st.one_of(
    st.floats(allow_nan=True, allow_infinity=True), st.floats(-1e4, 1e4),
    st.integers(-10**6, 10**6).map(float),
    st.integers(-10**15, 10**15).map(lambda k: k / 1000), st.integers(-10**9, 10**9).map(
        lambda k: k / 1e6), st.sampled_from([0.0, -0.0, 5e-5, -1e-4, 0.00015, 999999999999.9995,
                                             1e12, 0.0005, -0.0005, 2.5, 0.125])), max_size=30)


@settings(max_examples=300, deadline=None)
@given(values, st.sampled_from([3, 6]), st.booleans())
def test_every_number_is_the_repr_of_its_rounded_value(xs, places, point_zero):
    got, slow = shortest(np.array(xs, dtype=float), places, point_zero)
    assert len(got) == len(xs)
    with np.errstate(over="ignore", invalid="ignore"):
        rounded = np.round(np.array(xs, dtype=float), places) + 0.0
    for i, v in enumerate(rounded.tolist()):
        text = repr(v)
        if i in slow:
            assert not np.isfinite(v) or "e" in text or abs(v) >= 1e9
            continue
        assert got[i] == (text if point_zero else text.removesuffix(".0"))
