"""Numbers as the writers print them, a whole array at once, built as bytes by numpy instead
of a ``repr`` or a ``printf`` per number: the SVG and DXF writers' (``shortest``) and the PDF
writer's, as reportlab's ``fp_str`` writes them (``fixed``).

A value rounded to ``places`` is the double nearest to an integer K over 10**places. While K
has at most 15 digits, no other decimal of 15 digits or fewer reads back to that double
(doubles keep 15 decimal digits), so the shortest is K's own digits with the point put in and
the trailing zeros dropped: that is what ``shortest`` writes. Other values (larger ones, below
1e-4 where ``repr`` writes an exponent, not finite) are left to the caller (``slow``).

>>> shortest(np.array([2.5, -0.0004, 1234.5678, 3.0]), 3)[0]
['2.5', '0', '1234.568', '3']
>>> fixed(np.array([0.5, -0.25, 123.456789, 5.0, 1e-8, -3e-7]))[0]
['.5', '-0.25', '123.4568', '5', '0', '-0']
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

LARGEST = 10**15  # K with more digits: left to ``repr``


def shortest(values: NDArray[np.float64], places: int, point_zero: bool = False, per: int = 1,
             sep: str = " ") -> tuple[list[str], NDArray[np.intp]]:
    """The values (any shape, flattened; ``per`` of them to a string, ``sep`` between) rounded
    to ``places`` as ``repr`` writes them, a whole number without its ".0" unless
    ``point_zero``; and the indices of the values this does not write (their strings are
    placeholders; their strings hold ``per`` of them)."""
    scale = 10.0 ** places
    with np.errstate(over="ignore", invalid="ignore"):  # huge or not finite: left over
        k = np.rint(np.asarray(values, dtype=float).ravel() * scale)  # as np.round rounds
    fast = np.abs(k) < LARGEST  # False when not finite
    if places > 4:  # repr writes 0 < |x| < 1e-4 with an exponent
        fast &= (k == 0) | (np.abs(k) >= 10 ** (places - 4))
    k = np.where(fast, k, 0.0).astype(np.int64)
    whole, part = np.divmod(np.abs(k), 10**places)
    return (_written(k < 0, whole, part, places, True, point_zero, per, sep),
            np.flatnonzero(~fast))


FIXED = 6  # fp_str's most decimals: 6 below 10, one fewer per digit before the point
ZERO = 1e-7  # fp_str writes a value this small (or smaller) as 0


def fixed(values: NDArray[np.float64], per: int = 1) -> tuple[list[str], NDArray[np.intp]]:
    """The values (any shape, flattened; ``per`` of them to a string, with a space between)
    as reportlab's ``fp_str`` writes them: ``%.Nf`` with
    N = 6 up to 10 and one fewer per digit before the point beyond (none from 1e6), trailing
    zeros and a bare point dropped, a leading "0." as "." (not "-0."), and 0 for a value of
    at most 1e-7; and the indices of the values this does not write (their strings are
    placeholders; their strings hold ``per`` of them): at half a last decimal (times 10**N),
    near a power of ten (where fp_str's log10 decides the decimals), 1e15 and up, not
    finite."""
    x = np.asarray(values, dtype=float).ravel()
    size = np.abs(x)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        exponent = np.log10(size)
        digits = np.where(size > 1.0, np.floor(exponent), 0.0)
        places = np.clip(FIXED - digits, 0, FIXED)
        scaled = size * 10.0 ** places
        k = np.rint(scaled)
        # printf rounds the exact value times 10**places, rint the double nearest it: they
        # agree but where that double is half a unit (rounding keeps order, so the exact
        # value is then on the same side of the half as the double, or on it)
        fast = (size < LARGEST) & (scaled - np.floor(scaled) != 0.5) & (
            (size <= 1.0) | (np.abs(exponent - np.rint(exponent)) > 1e-9))
    zero = size <= ZERO
    k = np.where(fast & ~zero, k, 0.0).astype(np.int64)
    places = places.astype(np.int64)
    whole, part = np.divmod(k, 10 ** places)
    part *= 10 ** (FIXED - places)  # FIXED decimals for all: the trailing zeros are dropped
    negative = (x < 0) & ~zero
    return (_written(negative, whole, part, FIXED, negative | (part == 0), False, per),
            np.flatnonzero(~fast & ~zero))


END, SEP = "\x1e", "\x1f"  # what ends a string and parts its numbers as written (control
# characters, in no number), then split at and replaced by the separator


def _written(negative, whole, part, places: int, lead, point_zero: bool, per: int = 1,
             sep: str = " ") -> list[str]:
    """Each number from its sign, whole part and decimals (``part``, ``places`` digits): the
    whole part's 0 written where ``lead``, the decimals' trailing zeros dropped (all of them
    with the point, unless ``point_zero``: then ".0"); ``per`` numbers to a string, ``sep``
    between them."""
    digits = len(str(int(whole.max()))) if len(whole) else 1
    chars = np.zeros((len(whole), digits + places + 3), dtype=np.uint8)  # 0: no character
    chars[:, 0] = np.where(negative, ord("-"), 0)
    # the digits from the last: one divmod a column
    rest = whole
    for d in reversed(range(digits)):
        power = 10 ** (digits - 1 - d)
        rest, digit = np.divmod(rest, 10)
        chars[:, 1 + d] = np.where((whole >= power) | ((power == 1) & lead), 48 + digit, 0)
    point = digits + 1
    chars[:, point] = np.where((part > 0) | point_zero, ord("."), 0)
    later = np.zeros(len(part), dtype=bool)  # this digit or one after it is not 0
    for d in reversed(range(places)):
        part, digit = np.divmod(part, 10)
        later |= digit > 0
        shown = later | (point_zero & (d == 0))
        chars[:, point + 1 + d] = np.where(shown, 48 + digit, 0)
    chars[:, -1] = ord(END)
    chars[np.arange(len(chars)) % per < per - 1, -1] = ord(SEP)
    return chars[chars > 0].tobytes().decode("ascii").replace(SEP, sep).split(END)[:-1]
