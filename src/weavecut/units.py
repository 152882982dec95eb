"""Lengths with units ("50cm", "0.15mm", "2in") to millimetres, and paper sizes."""

from __future__ import annotations

import math
import re

UNITS = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4, "pt": 25.4 / 72, "px": 25.4 / 96}

LARGEST_PAGE = 10_000.0  # mm: no sheet or page is larger than 10 m

PAPER_SIZES = {"a4": (210.0, 297.0), "a3": (297.0, 420.0), "letter": (215.9, 279.4)}

_LENGTH = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([a-z]*)\s*$")


def to_mm(value: str | float) -> float:
    """Convert a length to millimetres; a bare number is millimetres. A length that is not
    finite (``nan``, ``1e400``) is a ValueError.

    Examples
    --------
    >>> to_mm("2.5cm"), to_mm("1in"), to_mm(3)
    (25.0, 25.4, 3.0)
    """
    if isinstance(value, (int, float)):
        mm = float(value)
    else:
        m = _LENGTH.match(value.lower())
        if not m or m.group(2) not in UNITS and m.group(2) != "":
            raise ValueError(f"{value!r} is not a length like '3mm', '2.5cm' or '1in'")
        mm = float(m.group(1)) * UNITS.get(m.group(2) or "mm")
    if not math.isfinite(mm):
        raise ValueError(f"{value!r} is not a finite length")
    return mm


def page_size(value: str) -> tuple[float, float]:
    """A paper name (a4, a3, letter) or ``WxH`` with units -> (width, height) in mm (page
    presets: ``presets.page_size``).

    Examples
    --------
    >>> page_size("letter"), page_size("100x50mm")
    ((215.9, 279.4), (100.0, 50.0))
    """
    key = value.strip().lower()
    if key in PAPER_SIZES:
        return PAPER_SIZES[key]
    parts = key.split("x")
    if len(parts) != 2:
        raise ValueError(f"{value!r} is not a page size: use a4, a3, letter, a preset or WxH "
                         "like 200x300mm")
    unit = re.sub(r"^[-+0-9.e]*", "", parts[1])
    w = to_mm(parts[0] if re.search(r"[a-z]$", parts[0]) else parts[0] + unit)
    h = to_mm(parts[1])
    if w <= 0 or h <= 0:
        raise ValueError(f"page size {value!r} must be positive")
    if max(w, h) > LARGEST_PAGE:
        raise ValueError(f"page size {value!r} is larger than {LARGEST_PAGE / 1000:g} m")
    return (w, h)
