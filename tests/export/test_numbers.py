"""Numbers written a whole array at once: each is what ``repr`` writes of the value rounded by
``np.round`` (no negative zero; a whole number without ".0" unless asked), or what ReportLab's
``fp_str`` writes of it, for any value it takes on; the ones it leaves (too many digits, an
exponent, not finite, a rounding tie) are named."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from reportlab.lib.rl_accel import fp_str

from weavecut.export.numbers import fixed, shortest

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


page = st.lists(st.one_of(
    st.floats(-1e7, 1e7), st.floats(-2, 2), st.integers(-10**6, 10**6).map(float),
    st.integers(-10**9, 10**9).map(lambda k: k / 1000),  # 3 decimals: "%.4f" meets ties
    st.integers(-10**7, 10**7).map(lambda k: k / 2**7),  # exact binary ties
    st.sampled_from([1e-7, -1e-7, 1.5e-7, -4e-7, 0.0, -0.0, 10.0, 100.0, 1000.0, 999999.5,
                     0.9999995, 9.9999995, 1e6, 1e-6])), max_size=30)


@settings(max_examples=300, deadline=None)
@given(page)
def test_every_number_is_what_reportlab_writes(xs):
    got, slow = fixed(np.array(xs, dtype=float))
    assert len(got) == len(xs)
    for i, x in enumerate(xs):
        if i in slow:  # left to fp_str: never a zero
            assert abs(x) > 1e-7
            continue
        assert got[i] == fp_str(x), x
