"""The cut files' own rules, checked from what they draw: engraved-number warnings name the
right pieces, and the rest in the tests below."""

from __future__ import annotations

import numpy as np

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
