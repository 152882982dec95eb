"""Lengths with units ("50cm", "0.15mm", "2in") to millimetres, and paper sizes.

A length a person gives (an option, a recipe or preset value, a page size) carries its unit
(``length``): '300' could be 300 mm or 300 cm, and the two tools a maker has open at once (a
laser program in mm, a cutter's in inches) do not agree on a default. Zero alone is taken, as
it is zero in every unit.
"""

from __future__ import annotations

import math
import re

from .text import nearest

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
        if m and m.group(2) and m.group(2) not in UNITS:
            raise ValueError(f"{value!r} is not a length: unknown unit {m.group(2)!r}; use "
                             f"{', '.join(UNITS)}")  # six: the list says more than a guess
        if not m:
            raise ValueError(f"{value!r} is not a length like '3mm', '2.5cm' or '1in'")
        mm = float(m.group(1)) * UNITS.get(m.group(2) or "mm")
    if not math.isfinite(mm):
        raise ValueError(f"{value!r} is not a finite length")
    return mm


def length(value: str | float) -> float:
    """A length a person gave, with its unit, in millimetres (``to_mm``); a bare number other
    than zero is a ValueError that shows the number with units.

    Examples
    --------
    >>> length("2.5cm"), length("0"), length(0)
    (25.0, 0.0, 0.0)
    >>> length("300")
    Traceback (most recent call last):
    ...
    ValueError: '300' has no unit: write it like '300mm', '300cm' or '300in'
    """
    if isinstance(value, bool):
        raise ValueError(f"{value!r} is not a length")
    bare = value if isinstance(value, (int, float)) else None
    m = _LENGTH.match(value.lower()) if isinstance(value, str) else None
    if m and not m.group(2):
        bare = m.group(1)
    if bare is not None and float(bare) != 0 and math.isfinite(float(bare)):
        number = str(value).strip()
        raise ValueError(f"{number!r} has no unit: write it like '{number}mm', '{number}cm' "
                         f"or '{number}in'")
    return to_mm(value)


def page_size(value: str) -> tuple[float, float]:
    """A paper name (a4, a3, letter) or ``WxH`` with a unit (on both, or on the height for
    both) -> (width, height) in mm (page presets: ``presets.page_size``).

    Examples
    --------
    >>> page_size("letter"), page_size("100x50mm"), page_size("96x192px")
    ((215.9, 279.4), (100.0, 50.0), (25.4, 50.8))
    """
    key = value.strip().lower()
    if key in PAPER_SIZES:
        return PAPER_SIZES[key]
    # split at the x between the sides, not at the x of "px"; spaces around it ("100 x 50mm")
    # belong to neither side
    parts = [p.replace("\0", "px").strip() for p in key.replace("px", "\0").split("x")]
    if len(parts) != 2:
        raise ValueError(f"{value!r} is not a page size: use a4, a3, letter, a preset or WxH "
                         f"like 200x300mm{nearest(key, PAPER_SIZES)}")
    unit = re.sub(r"^[-+0-9.e]*", "", parts[1])
    if not unit and float(parts[1] or 0) != 0 and _LENGTH.match(parts[1]):
        raise ValueError(f"{value!r} has no unit: write it like '{value.strip()}mm'")
    w = length(parts[0] if re.search(r"[a-z]$", parts[0]) else parts[0] + unit)
    h = length(parts[1])
    if w <= 0 or h <= 0:
        raise ValueError(f"page size {value!r} must be positive")
    if max(w, h) > LARGEST_PAGE:
        raise ValueError(f"page size {value!r} is larger than {LARGEST_PAGE / 1000:g} m")
    return (w, h)
