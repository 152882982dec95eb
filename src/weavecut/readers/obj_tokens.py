"""The tokens of an OBJ text, found and converted with numpy (no Python loop over lines):
byte offsets of every token grouped into lines, statements as 8-byte keys, integers read
eight digits at a time (SWAR), decimals exactly (an x87 long double where there is one).
``obj`` reads a file with it, a piece of whole lines at a time."""

from __future__ import annotations

import sys

import numpy as np

_CONTROLS = np.array([c if c in (10, 13) or c > 31 else 32 if c in (9, 11, 12) else 127
                      for c in range(256)], dtype=np.uint8)  # see _normalise_controls
MAX_TOKEN = 40  # longer numbers are parsed one by one
_ZEROS = np.uint64(0x3030303030303030)  # "00000000"
_HIGH_NIBBLES = np.uint64(0xF0F0F0F0F0F0F0F0)
_LOW_BYTES = np.array([(1 << 8 * k) - 1 for k in range(9)], dtype=np.uint64)
MAX_DIGITS = 19  # a decimal of up to 19 digits is an exact uint64 (10**19 < 2**64)
_POWERS = np.array([10**k for k in range(MAX_DIGITS + 1)], dtype=np.uint64)
_POWERS_F8, _POWERS_LD = _POWERS.astype(np.float64), _POWERS.astype(np.longdouble)
# long double is the x87 80-bit number (64-bit significand first, little-endian) on x86
_X87 = np.finfo(np.longdouble).nmant == 63 and sys.byteorder == "little"



def statement_key(tag: bytes) -> np.uint64:
    return np.frombuffer(tag.ljust(8, b"\0"), dtype=np.uint64)[0]



class Tokens:
    """The whitespace-separated tokens of an OBJ text, as byte offsets, grouped into lines.

    Comments and carriage returns are removed first, so line ``n`` is the n-th line of the
    text, counted on from ``lines_before``. Only non-empty lines are kept: ``line`` (1-based
    number), ``first`` (its first token, the statement) and ``count`` (tokens on it, the
    statement included); ``n_lines`` counts the text's line ends.
    """

    def __init__(self, data, lines_before: int = 0, comments: bool = True) -> None:
        pad = b" " * MAX_TOKEN  # room for windows of bytes before and after every token
        ends = data[-1:] == b"\n"
        self.buf = np.frombuffer(bytearray().join([pad, data, b"" if ends else b"\n", pad]),
                                 dtype=np.uint8)
        text = self.buf[:-MAX_TOKEN]
        gap = self._gaps(text)
        newline = text[gap] == 10
        n_newlines = int(np.count_nonzero(newline))
        if n_newlines + np.count_nonzero(text[gap] == 32) < len(gap):  # other control bytes
            _normalise_controls(text)
            gap = self._gaps(text)
            newline = text[gap] == 10
            n_newlines = int(np.count_nonzero(newline))
        self.n_lines = n_newlines - (not ends)
        if comments:
            _blank_comments(text, gap[newline])
            gap = self._gaps(text)
            newline = text[gap] == 10
        # a token lies between two gaps that are not next to each other
        self.start, self.end = gap[:-1] + 1, gap[1:]
        newline[0] = True  # the pad: the text starts a line
        if (self.end > self.start).all():  # no blank line, no run of spaces
            self.first = np.flatnonzero(newline[:-1])
            self.line = np.arange(1 + lines_before, 1 + lines_before + len(self.first))
        else:
            newline[0] = False
            line = np.cumsum(newline[:-1])  # of the space after each gap, 0-based
            token = np.flatnonzero(self.end > self.start)
            self.start, self.end, line = self.start[token], self.end[token], line[token]
            self.first = np.flatnonzero(np.diff(line, prepend=-1))
            self.line = line[self.first] + 1 + lines_before
        self.count = np.diff(self.first, append=len(self.start))

    @staticmethod
    def _gaps(text: np.ndarray) -> np.ndarray:
        """Positions of the bytes below 33 (spaces, line ends, control characters) from the
        pad byte just before the text on."""
        return np.flatnonzero(text[MAX_TOKEN - 1:] <= 32) + (MAX_TOKEN - 1)

    def text(self, token: int) -> str:
        """Token ``token`` as text (its first few hundred characters)."""
        a, b = int(self.start[token]), int(self.end[token])
        return self.buf[a:min(b, a + 800)].tobytes().decode("utf-8", errors="ignore")

    def keys(self, tokens) -> np.ndarray:
        """A uint64 key for each token of up to 8 bytes (0 for longer ones)."""
        length = self.end[tokens] - self.start[tokens]
        keys = self._items(8, "<u8")[self.start[tokens]]
        keys &= _LOW_BYTES[np.minimum(length, 8)]
        keys[length > 8] = 0
        return keys

    def _items(self, width: int, dtype) -> np.ndarray:
        """Item i is bytes i .. i + width - 1 of the text (overlapping, no copy)."""
        return np.ndarray(len(self.buf) - width + 1, dtype, self.buf, strides=(1,))

    def floats(self, tokens) -> tuple[np.ndarray, int | None]:
        """The tokens as float64 (Python's float syntax) and the position of the first one
        that is no number (or None): plain decimals here, the others by numpy."""
        start, end = self.start[tokens], self.end[tokens]
        values, plain = self._decimals(start, end)
        other = np.flatnonzero(~plain)
        if not len(other):
            return values, None
        values[other], bad = self._any_floats(start[other], end[other])
        return values, None if bad is None else int(other[bad])

    def _decimals(self, start, end) -> tuple[np.ndarray, np.ndarray]:
        """Correctly rounded values of the tokens that are plain decimals, ``[+-]digits[.digits]``
        with 1 to 19 digits, at most 7 before the point, and the mask of those converted (the
        other values are arbitrary).

        The digits make an integer m < 10**19 < 2**64 and the value is m / 10**k. Up to 2**53
        both are exact doubles and one division rounds correctly; above, the quotient is
        taken in x87 long double (64-bit significand) and rounded again to double, which is
        correct unless the long double lies halfway between two doubles (those few are
        left out, as is every m > 2**53 where long double is no x87 number).
        """
        first = self.buf[start]
        negative = first == ord("-")
        start = start + (negative | (first == ord("+")))
        head = self._items(8, "<u8")[start]  # the first 8 bytes, where the point must be
        length = end - start
        n_whole = np.minimum(_first_byte(head, ord(".")), length)  # 8: no point in the head
        n_part = np.maximum(length - n_whole - 1, 0)
        whole, plain = _swar_digits(_right_aligned(head, n_whole))
        part, part_ok = self._digits(end, np.minimum(n_part, MAX_DIGITS))
        plain &= part_ok & (n_whole < 8) & (0 < n_whole + n_part) & (n_whole + n_part <= MAX_DIGITS)
        n_part = np.minimum(n_part, MAX_DIGITS)
        m = whole * _POWERS[n_part] + part  # wraps around only for tokens left out
        values = m.astype(np.float64) / _POWERS_F8[n_part]
        big = np.flatnonzero(m > 2**53)
        if len(big) and _X87:
            wide = m[big].astype(np.longdouble) / _POWERS_LD[n_part[big]]
            values[big] = wide.astype(np.float64)
            significand = np.ndarray(len(wide), np.uint64, wide, strides=(wide.itemsize,))
            plain[big] &= (significand & np.uint64(0x7FF)) != 0x400  # not halfway
        else:
            plain[big] = False
        np.negative(values, out=values, where=negative)
        return values, plain

    def _any_floats(self, start, end) -> tuple[np.ndarray, int | None]:
        """The tokens as float64 by numpy's conversion (Python's syntax: exponents, ``nan``,
        ``1_0``) and the position of the first that is no number (or None)."""
        length = end - start
        width = int(min(length.max(initial=1), MAX_TOKEN))
        strings = self._items(width, f"S{width}")[start]
        window = strings.view(np.uint8).reshape(-1, width)
        window *= np.arange(width) < length[:, None]  # NUL after each number
        long = np.flatnonzero(length > width)
        window[long] = ord("0")  # decided one by one below
        try:
            values, bad = strings.astype(np.float64), []
        except ValueError:
            first_bad = _first_unconvertible(strings)
            values = np.full(len(strings), np.nan)
            values[:first_bad] = strings[:first_bad].astype(np.float64)
            bad = [first_bad]
        for i in long.tolist():
            try:
                values[i] = float(self.buf[start[i]:end[i]].tobytes())
            except ValueError:
                bad.append(i)
        return values, min(bad, default=None)

    def ints(self, start, end) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Whole numbers ``[+-]digits`` in the given bytes: (int64 values, not-a-number mask,
        mask of those with more than 16 digits, whose value is not computed)."""
        first = self.buf[start]
        sign = (end > start) & ((first == ord("+")) | (first == ord("-")))
        length = end - start - sign
        values, ok = self._digits(end, np.minimum(length, 16))
        values = values.astype(np.int64)
        bad = (length == 0) | ~ok
        long = np.flatnonzero(length > 16)
        if len(long):  # check the rest of their digits, eight at a time
            chunks = (length[long] - 9) // 8
            rest = np.repeat(length[long] - 16, chunks)
            step = 8 * (np.arange(len(rest)) - np.repeat(np.cumsum(chunks) - chunks, chunks))
            ok = self._eight_digits(np.repeat(end[long] - 16, chunks) - step,
                                    np.minimum(rest - step, 8))[1]
            bad[long] |= ~np.logical_and.reduceat(ok, np.cumsum(chunks) - chunks)
        too_long = np.zeros(len(start), dtype=bool)
        too_long[long] = ~bad[long]
        return np.where(sign & (first == ord("-")), -values, values), bad, too_long

    def _digits(self, end, length) -> tuple[np.ndarray, np.ndarray]:
        """The number (uint64) of the ``length`` (0..19) digits before each ``end``, and
        whether they are all digits."""
        value, ok = self._eight_digits(end, np.minimum(length, 8))
        for k in (8, 16):
            longer = np.flatnonzero(length > k)
            if not len(longer):
                break
            high, high_ok = self._eight_digits(end[longer] - k, np.minimum(length[longer] - k, 8))
            value[longer] += high * _POWERS[k]
            ok[longer] &= high_ok
        return value, ok

    def _eight_digits(self, end, length) -> tuple[np.ndarray, np.ndarray]:
        """The number of the ``length`` (0..8) digits before each ``end``, and whether they
        are all digits."""
        return _swar_digits(_right_aligned(self._items(8, "<u8")[end - 8], length, ends=True))



def _right_aligned(words, length, ends: bool = False) -> np.ndarray:
    """In place: the eight bytes of ``words`` with the ``length`` bytes of a number at their
    end (``ends``) or start moved to the end, the bytes before it "0"."""
    if not ends:
        words <<= (8 * (8 - length)).astype(np.uint64)  # shifts of 64 give 0
    pad = _LOW_BYTES[8 - length]
    words |= pad
    words ^= pad & ~_ZEROS
    return words


def _swar_digits(d) -> tuple[np.ndarray, np.ndarray]:
    """In place: the numbers that the eight ASCII digits in each uint64 spell (the first in
    the lowest byte), and whether they are all digits (SWAR: eight bytes at a time)."""
    ok = (d & _HIGH_NIBBLES) == _ZEROS
    ok &= ((d + np.uint64(0x0606060606060606)) & _HIGH_NIBBLES) == _ZEROS
    d &= np.uint64(0x0F0F0F0F0F0F0F0F)  # a digit 0..9 in each byte
    for shift, mask, scale in ((8, 0x00FF00FF00FF00FF, 2561), (16, 0x0000FFFF0000FFFF, 6553601),
                               (32, 0xFFFFFFFF, 42949672960001)):
        d *= np.uint64(scale)  # pairs of digits, then fours, then eight: 10 * a + b ...
        d >>= np.uint64(shift)
        d &= np.uint64(mask)
    return d, ok


def _first_byte(words, byte: int) -> np.ndarray:
    """Position (0..7) of the first ``byte`` in each uint64's eight bytes, 8 if none."""
    x = words ^ np.uint64(byte * 0x0101010101010101)
    found = ~(((x & np.uint64(0x7F7F7F7F7F7F7F7F)) + np.uint64(0x7F7F7F7F7F7F7F7F)) | x)
    found &= np.uint64(0x8080808080808080)  # the high bit of each byte that was ``byte``
    lowest = (found & (~found + np.uint64(1))) >> np.uint64(7)  # 1 << 8 * position, or 0
    lowest *= np.uint64(0x0807060504030201)  # its top byte: 8 - position
    return 8 - (lowest >> np.uint64(56)).astype(np.int64)


def _normalise_controls(text: np.ndarray) -> None:
    """In place: CR LF and a lone CR end a line like LF; tab, vertical tab and form feed are
    spaces; other control characters become DEL, which no number or statement contains."""
    cr = np.flatnonzero(text == 13)
    text[cr] = np.where(text[cr + 1] == 10, 32, 10)
    text[:] = _CONTROLS[text]


def _blank_comments(text: np.ndarray, line_end: np.ndarray) -> None:
    """In place: spaces from every ``#`` to the end of its line."""
    hashes = np.flatnonzero(text == ord("#"))
    end = line_end[np.searchsorted(line_end, hashes)]
    first = np.flatnonzero(np.diff(end, prepend=-1))  # the first # of each line
    start, length = hashes[first], end[first] - hashes[first]
    text[np.repeat(start - np.cumsum(length) + length, length) + np.arange(length.sum())] = 32


def _first_unconvertible(strings: np.ndarray) -> int:
    """Position of the first entry that does not convert to float (one is known to exist)."""
    lo, hi = 0, len(strings)
    while hi - lo > 1:  # bisect, converting halves in C
        mid = (lo + hi) // 2
        try:
            strings[lo:mid].astype(np.float64)
            lo = mid
        except ValueError:
            hi = mid
    return lo

