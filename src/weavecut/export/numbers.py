"""Numbers as the writers print them, a whole array at once, built as bytes by numpy instead of
one string call per number (a drawing holds a few hundred thousand).

``shortest``: each value rounded to ``places`` decimals (``np.round``, no negative zero) in the
shortest decimal that reads back, as Python's ``repr`` writes it (SVG, DXF). A value rounded
to ``places`` is the double nearest to an integer K over 10**places. While K has at most 15
digits, no other decimal of 15 digits or fewer reads back to that double (doubles keep 15
decimal digits), so the shortest is K's own digits with the point put in and the trailing
zeros dropped. Other values (larger ones, below 1e-4 where ``repr`` writes an exponent, not
finite) are left to the caller.

``fixed``: each value as ReportLab's ``fp_str`` writes it in PDF paths: 6 significant decimals
("%.6f" below 1, one decimal fewer per digit before the point, none from a million), trailing
zeros and a positive number's leading "0" dropped, 0 within 1e-7. "%.Nf" rounds the exact
binary value half to even; x 10**N as a double is within 2e-9 of it below a million, so
``np.rint`` of it rounds the same except within that of a half, where "%.Nf" itself is asked.

>>> shortest(np.array([2.5, -0.0004, 1234.5678, 3.0]), 3)[0]
['2.5', '0', '1234.568', '3']
>>> fixed(np.array([0.05, -0.5, 123.456789, 1e-8, -4e-7, 99.9999999]))[0]
['.05', '-0.5', '123.4568', '0', '-0', '100']
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

LARGEST = 10**15  # K with more digits: left to ``repr``
FIXED_LARGEST = 1e6  # from here "%.0f": integers, left to ``fp_str`` itself


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
    text = _decimals(k < 0, np.abs(k), np.full(len(k), places), point_zero=point_zero)
    return text, np.flatnonzero(~fast)


def fixed(values: NDArray[np.float64]) -> tuple[list[str], NDArray[np.intp]]:
    """The values (any shape, flattened) as ReportLab's ``fp_str`` writes each; and the
    indices of the values this does not write (a million and up, not finite, or within 2e-9
    of a rounding tie; their strings are placeholders)."""
    x = np.asarray(values, dtype=float).ravel()
    size = np.abs(x)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        places = np.where(size <= 1, 6, np.clip(6 - np.floor(np.log10(size)), 0, 6))
        places = np.nan_to_num(places, nan=0.0).astype(np.int64)
        scaled = x * 10.0 ** places
        k = np.rint(scaled)
    fast = (size < FIXED_LARGEST) & (np.abs(np.abs(scaled - np.floor(scaled)) - 0.5) > 2e-9)
    zero = size <= 1e-7
    k = np.where(fast & ~zero, np.abs(k), 0.0).astype(np.int64)
    text = _decimals((x < 0) & ~zero, k, np.where(zero, 0, places), positive_lead=False)
    return text, np.flatnonzero(~fast & ~zero)


def _decimals(negative: NDArray[np.bool_], k: NDArray[np.int64], places: NDArray[np.int64],
              point_zero: bool = False, positive_lead: bool = True) -> list[str]:
    """The numbers k / 10**places (k >= 0, a sign where ``negative``) with their trailing
    zeros dropped (".0" kept for a whole number if ``point_zero``; without the "0" before the
    point of a positive number below 1 unless ``positive_lead``)."""
    most = int(places.max()) if len(k) else 0
    whole, part = np.divmod(k, 10**places)
    digits = len(str(int(whole.max()))) if len(k) else 1
    chars = np.zeros((len(k), digits + most + 3), dtype=np.uint8)  # 0: no character
    chars[:, 0] = np.where(negative, ord("-"), 0)
    for d in range(digits):
        power = 10 ** (digits - 1 - d)
        shown = whole >= power
        if power == 1:  # the units: written, but for ".5"
            shown |= positive_lead | negative | (part == 0)
        chars[:, 1 + d] = np.where(shown, 48 + whole // power % 10, 0)
    point = digits + 1
    chars[:, point] = np.where((part > 0) | point_zero, ord("."), 0)
    for d in range(most):
        power = 10 ** np.maximum(places - 1 - d, 0)
        shown = (d < places) & (part % (10 * power) > 0)
        if point_zero and d == 0:
            shown |= part == 0
        chars[:, point + 1 + d] = np.where(shown, 48 + part // power % 10, 0)
    chars[:, -1] = ord("\n")
    return chars[chars > 0].tobytes().decode("ascii").split("\n")[:-1]
