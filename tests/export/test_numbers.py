"""Numbers written a whole array at once: each is what ``repr`` writes of the value rounded by
``np.round`` (no negative zero; a whole number without ".0" unless asked), for any value it
takes on; the ones it leaves (too many digits, an exponent, not finite) are named. The PDF
writer's are what reportlab's ``fp_str`` writes."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

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


@settings(max_examples=100, deadline=None)
@given(values.map(lambda xs: xs[:len(xs) // 2 * 2]), st.sampled_from([3, 6]),
       st.sampled_from([" ", ",", "\n 20\n"]))
def test_numbers_written_in_pairs_are_the_pairs_of_them_written_one_by_one(xs, places, sep):
    one, slow = shortest(np.array(xs, dtype=float), places)
    two, slow_pairs = shortest(np.array(xs, dtype=float), places, per=2, sep=sep)
    assert slow_pairs.tolist() == slow.tolist()
    assert len(two) == len(xs) // 2
    for i, text in enumerate(two):
        if not {2 * i, 2 * i + 1} & set(slow.tolist()):
            assert text == sep.join(one[2 * i:2 * i + 2])


# reportlab's fp_str: 6 decimals below 10, one fewer per digit beyond, none from 1e6; the
# values about a power of ten, at half a last decimal and at fp_str's 1e-7 zero
edges = st.integers(-7, 14).flatmap(lambda e: st.sampled_from([1.0, -1.0]).flatmap(
    lambda sign: st.sampled_from([0.0, 1e-12, -1e-12, 0.5e-6, 4e-7]).map(
        lambda d: sign * (10.0 ** e) * (1 + d))))
ties = st.tuples(st.integers(-10**7 + 1, 10**7 - 1), st.integers(0, 6)).map(
    lambda km: (km[0] + 0.5) / 10**km[1])  # about half the last of 6 digits (printf's to round)
fixed_values = st.lists(st.one_of(
    st.floats(-1e15, 1e15), st.floats(-2.0, 2.0), st.floats(-1e-5, 1e-5), edges, ties,
    st.integers(-10**6, 10**6).map(lambda k: k / 1e4),
    st.sampled_from([0.0, -0.0, 1e-7, -1e-7, 3e-7, -3e-7, 5e-7, -5e-7, 0.5, -0.5, 999999.5,
                     1e6 + 0.5, 9.9999999, 99.99999999999999, 999.9999999999999])),
    max_size=40)


@settings(max_examples=300, deadline=None)
@given(fixed_values)
def test_every_fixed_number_is_what_fp_str_writes(xs):
    # what a PDF's path operators hold: reportlab's own C fp_str, value by value, wherever
    # fixed writes one; those it leaves are near a tie or a power of ten, or huge
    from reportlab.lib.rl_accel import fp_str

    got, slow = fixed(np.array(xs, dtype=float))
    assert len(got) == len(xs)
    for i, v in enumerate(xs):
        if i in slow:
            continue
        assert got[i] == fp_str(v), v


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(st.one_of(st.floats(-1e4, 1e4), edges, ties),
                          st.one_of(st.floats(-1e4, 1e4), edges, ties)), max_size=30))
def test_pdf_points_are_fp_str_pairs(points):
    # every point a PDF page's path holds, as reportlab's moveTo and lineTo write it
    from reportlab.lib.rl_accel import fp_str

    from weavecut.export.pdf import _points

    coords = np.array(points, dtype=float).reshape(-1, 2)
    assert _points(coords) == [fp_str(x, y) for x, y in coords.tolist()]
