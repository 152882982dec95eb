"""numeric.snap: the integer key of every finite value that has one, as Python's own round()
gives it (half to even, like np.rint); a NaN, an infinity or a value beyond int64 is refused
loudly, naming the value, where it sits and the function that asked (numpy's cast would
return the most negative int64 on x86 and 0 on ARM, so a decision on it would differ between
machines)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.numeric import GRID, SnapError, snap

finite = st.floats(min_value=-1e12, max_value=1e12, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(st.lists(finite, min_size=1, max_size=20), st.sampled_from([GRID, 0.25, 1.0, 1e-3]))
def test_a_finite_value_gets_pythons_rounding_of_it(values, grid):
    assert snap(values, grid).tolist() == [round(v / grid) for v in values]
    assert snap(values, grid).dtype == np.int64


def _a_caller(values):
    return snap(values)


@pytest.mark.parametrize("bad, shown", [(math.nan, "nan"), (math.inf, "inf"),
                                        (-math.inf, "-inf"), (1e14, "1e+14")])
def test_a_value_without_an_integer_key_is_refused_naming_it_and_its_caller(bad, shown):
    with pytest.raises(SnapError) as refused:
        _a_caller([0.0, 1.0, bad, 2.0, bad])
    said = str(refused.value)
    assert said.startswith(f"snap() got {shown} at index 2 (2 of 5 values have no integer key)")
    assert f"asked by _a_caller() in {Path(__file__).name}:" in said
    assert isinstance(refused.value, FloatingPointError)  # an internal error, not a refusal


def test_a_grid_key_at_the_edge_of_int64_is_refused_and_a_scalar_has_no_index():
    assert snap(9.2e12).tolist() == round(9.2e12 / GRID)  # below 2**63 keys: kept
    with pytest.raises(SnapError, match=r"^snap\(\) got 9\.3e\+12 \(1 of 1 "):
        snap(9.3e12)
    with pytest.raises(SnapError, match=r"at index \(1, 0\)"):
        snap([[1.0, 2.0], [math.nan, 3.0]])


def test_no_values_have_no_keys():
    assert snap(np.zeros(0)).tolist() == [] and snap(np.zeros((0, 2))).shape == (0, 2)
