"""Readable text on coloured fills: WCAG 2 relative luminance and contrast ratio.

>>> round(contrast_ratio("#000000", "#ffffff"), 1)
21.0
>>> text_colour_on("#1b4f72")
'#ffffff'
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..numeric import dot

BLACK, WHITE = "#000000", "#ffffff"
MIN_CONTRAST = 4.5
"""WCAG 2 level AA for normal text; the least any printed label may have."""


def rgb(colour: str) -> tuple[float, float, float]:
    """``"#rrggbb"`` as three floats in [0, 1]."""
    if len(colour) != 7 or colour[0] != "#":
        raise ValueError(f"{colour!r} is not a colour like '#1b4f72'")
    return tuple(int(colour[i:i + 2], 16) / 255 for i in (1, 3, 5))


@lru_cache(maxsize=4096)
def relative_luminance(colour: str) -> float:
    """WCAG 2 relative luminance of an sRGB colour, 0 (black) to 1 (white) (kept: guides and
    books weigh their few paints again and again)."""
    c = np.array(rgb(colour))
    linear = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return float(dot(linear, [0.2126, 0.7152, 0.0722]))


def contrast_ratio(a: str, b: str) -> float:
    """WCAG 2 contrast ratio of two colours, 1 (same) to 21 (black on white)."""
    la, lb = sorted((relative_luminance(a), relative_luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)


@lru_cache(maxsize=1024)
def text_colour_on(fill: str) -> str:
    """Black or white, whichever has the higher contrast on ``fill`` (kept: a book asks for
    its few fills again and again)."""
    return BLACK if contrast_ratio(BLACK, fill) >= contrast_ratio(WHITE, fill) else WHITE
