"""Numbers as the SVG and DXF writers print them, a whole array at once: each value rounded to
``places`` decimals (``np.round``, no negative zero) in the shortest decimal that reads back
(what Python's ``repr`` writes), built as bytes by numpy instead of a ``repr`` per number.

A value rounded to ``places`` is the double nearest to an integer K over 10**places. While K
has at most 15 digits, no other decimal of 15 digits or fewer reads back to that double
(doubles keep 15 decimal digits), so the shortest is K's own digits with the point put in and
the trailing zeros dropped: that is what ``shortest`` writes. Other values (larger ones, below
1e-4 where ``repr`` writes an exponent, not finite) are left to the caller (``slow``).

>>> shortest(np.array([2.5, -0.0004, 1234.5678, 3.0]), 3)[0]
['2.5', '0', '1234.568', '3']
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

LARGEST = 10**15  # K with more digits: left to ``repr``


def shortest(values: NDArray[np.float64], places: int, point_zero: bool = False
             ) -> tuple[list[str], NDArray[np.intp]]:
    """The values (any shape, flattened) rounded to ``places`` as ``repr`` writes them, a
    whole number without its ".0" unless ``point_zero``; and the indices of the values this
    does not write (their strings are placeholders)."""
    scale = 10.0 ** places
    with np.errstate(over="ignore", invalid="ignore"):  # huge or not finite: left over
        k = np.rint(np.asarray(values, dtype=float).ravel() * scale)  # as np.round rounds
    fast = np.abs(k) < LARGEST  # False when not finite
    if places > 4:  # repr writes 0 < |x| < 1e-4 with an exponent
        fast &= (k == 0) | (np.abs(k) >= 10 ** (places - 4))
    k = np.where(fast, k, 0.0).astype(np.int64)
    whole, part = np.divmod(np.abs(k), 10**places)
    digits = len(str(int(whole.max()))) if len(k) else 1
    chars = np.zeros((len(k), digits + places + 3), dtype=np.uint8)  # 0: no character
    chars[:, 0] = np.where(k < 0, ord("-"), 0)
    for d in range(digits):
        power = 10 ** (digits - 1 - d)
        chars[:, 1 + d] = np.where((whole >= power) | (power == 1), 48 + whole // power % 10, 0)
    point = digits + 1
    chars[:, point] = np.where((part > 0) | point_zero, ord("."), 0)
    for d in range(places):
        power = 10 ** (places - 1 - d)
        shown = (part % (10 * power) > 0) | (point_zero & (d == 0) & (part == 0))
        chars[:, point + 1 + d] = np.where(shown, 48 + part // power % 10, 0)
    chars[:, -1] = ord("\n")
    text = chars[chars > 0].tobytes().decode("ascii")
    return text.split("\n")[:-1], np.flatnonzero(~fast)
