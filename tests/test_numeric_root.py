"""numeric.root against scipy's brentq (the oracle it replaces): the same float, step for step."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import brentq

from weavecut.numeric import root

MONOTONE = {
    "cubic": lambda x, c: x ** 3 + x - c,
    "exp": lambda x, c: math.exp(x / 4) - math.exp(c / 4),
    "atan": lambda x, c: math.atan(50 * (x - c)),  # flat far off, steep at the root
    "sqrt": lambda x, c: math.copysign(math.sqrt(abs(x)), x) - math.copysign(math.sqrt(abs(c)), c),
    "step-ish": lambda x, c: math.tanh(1e3 * (x - c)) + 1e-9 * x,
}


@given(st.sampled_from(sorted(MONOTONE)), st.floats(-5, 5), st.floats(5.5, 1e3),
       st.floats(1e-15, 1e-3), st.floats(1e-14, 1e-6))
def test_the_same_root_as_brentq(name, c, width, xtol, rtol):
    f = MONOTONE[name]
    low, high = -width, width * 0.7 + 6
    assert root(lambda x: f(x, c), low, high, xtol, rtol) == brentq(
        lambda x: f(x, c), low, high, xtol=xtol, rtol=rtol)


def test_a_root_at_an_end_and_no_bracket():
    assert root(lambda x: x - 1.0, 1.0, 3.0, 1e-12, 1e-14) == 1.0
    assert root(lambda x: x - 3.0, 1.0, 3.0, 1e-12, 1e-14) == 3.0
    with pytest.raises(ValueError):
        root(lambda x: x * x + 1.0, -1.0, 1.0, 1e-12, 1e-14)
