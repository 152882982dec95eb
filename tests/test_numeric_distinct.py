"""numeric.distinct is np.unique (values and dtype; rows with axis=0) for the arrays the puzzle
asks it of: integers, colour strings as objects or unicode, and without importing numpy.ma."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.numeric import distinct

from tests.fresh import modules_after

colours = st.sampled_from(["#000000", "#12ab9f", "#ff0000", "none"])


@settings(max_examples=100, deadline=None)
@given(st.lists(st.integers(-5, 5), max_size=20), st.lists(colours, max_size=20),
       st.lists(st.tuples(colours, colours), max_size=10))
def test_the_same_as_np_unique(ints, names, pairs):
    for values, axis in ((np.array(ints, dtype=np.int64), None),
                         (np.array(names, dtype=object), None),
                         (np.array(pairs, dtype=str).reshape(-1, 2), 0),
                         (np.array(ints[: len(ints) // 2 * 2], dtype=np.int64).reshape(-1, 2), 0)):
        got, want = distinct(values, axis=axis), np.unique(values, axis=axis)
        assert got.dtype == want.dtype and got.shape == want.shape
        assert got.tolist() == want.tolist()


def test_numpy_ma_is_not_imported():
    assert "numpy.ma" not in modules_after(
        "import numpy as np\nfrom weavecut.numeric import distinct\n"
        "distinct(np.array([3, 1, 3])); distinct(np.array([[1, 2], [1, 2]]), axis=0)")


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.integers(-3, 3), st.integers(-2**62, 2**62), st.integers(0, 2)),
                max_size=40))
def test_unique_rows_is_np_uniques_first_and_inverse(rows):
    """numeric.unique_rows against np.unique(axis=0): the first of each distinct row, in the
    rows' order, and which each row is (large and negative values, repeats, no rows)."""
    from weavecut.numeric import unique_rows

    keys = np.array(rows, dtype=np.int64).reshape(-1, 3)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    got_first, got_inverse = unique_rows(keys)
    assert got_first.tolist() == first.tolist()
    assert got_inverse.tolist() == inverse.reshape(-1).tolist()


@settings(max_examples=200, deadline=None)
@given(st.lists(st.integers(-6, 6), max_size=30), st.lists(st.integers(-4, 4), max_size=10))
def test_among_is_np_isin_for_distinct_keys(values, keys):
    """numeric.among against np.isin, for the sorted distinct keys it is given (no keys, values
    below, between and above them)."""
    from weavecut.numeric import among

    want = np.isin(np.array(values, dtype=np.int64), np.array(keys, dtype=np.int64))
    got = among(np.array(values, dtype=np.int64), distinct(np.array(keys, dtype=np.int64)))
    assert got.tolist() == want.tolist()


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(-1e6, 1e6, allow_nan=False), min_size=1, max_size=25))
def test_median_is_np_median(values):
    """numeric.median against np.median, bit for bit (odd and even counts, repeats)."""
    from weavecut.numeric import median

    assert median(values) == float(np.median(np.array(values)))
