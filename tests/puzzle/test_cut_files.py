"""The cut files' own rules, checked from what they draw: engraved-number warnings name the
right pieces, and the rest in the tests below."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.puzzle import files as pf


def _labels(heights) -> pf.Labels:
    n = len(heights)
    return pf.Labels(tuple(str(k + 1) for k in range(n)), np.asarray(heights, dtype=float),
                     np.zeros((n, 2)), np.zeros(n))


def test_number_warnings_name_pieces_below_the_digit_size_not_at_it():
    lines = pf.number_warnings(_labels([3.0, 0.5, 2.9, 0.0, 4.0]))
    assert lines == ["pieces 2, 3 are too small for 3 mm digits; their numbers are engraved "
                     "smaller (down to 0.5 mm)",
                     "pieces 4 are too small for 1.5 mm digits and get no number"]
    assert pf.number_warnings(_labels([3.0, 5.0])) == []


def test_number_warnings_list_twelve_pieces_and_count_the_rest():
    twelve = pf.number_warnings(_labels([1.0] * 12))[0]
    assert twelve.startswith("pieces 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12 are too small")
    fifteen = pf.number_warnings(_labels([0.0] * 15))[0]
    assert fifteen.startswith("pieces 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12 and 3 more are too "
                              "small for 1.5 mm digits")


@settings(max_examples=50, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["1", "27", "380", "", " "]),
                          st.sampled_from([0.0, 2.5, 3.0, 7.25]),
                          st.floats(-50.0, 50.0), st.floats(-50.0, 50.0),
                          st.sampled_from([0.0, 90.0, 33.3, -120.0])), max_size=8))
def test_each_labels_strokes_made_together_are_its_strokes_made_alone(rows):
    labels = pf.Labels(tuple(r[0] for r in rows), np.array([r[1] for r in rows]),
                       np.array([r[2:4] for r in rows]).reshape(-1, 2),
                       np.array([r[4] for r in rows]))
    some = np.flatnonzero(labels.heights > 0)
    each = labels.strokes_each(some)
    assert len(each) == len(some)
    for k, (coords, offsets) in zip(some.tolist(), each):
        alone_coords, alone_offsets = labels.strokes(pick=[k])
        assert coords.tobytes() == alone_coords.tobytes() and coords.shape == alone_coords.shape
        assert offsets.dtype == alone_offsets.dtype and offsets.tolist() == alone_offsets.tolist()
