"""Line work too fine to draw as vectors, drawn as a greyscale picture (a ``Raster``).

A stroke thinner than one dot of a 600 dpi printer does not print as drawn (a printer makes it
a whole dot wide, a viewer that samples coverage drops it: librsvg drew the level-8 panel of
``edge-renders`` empty, issue #29), and a million of them make a file of tens of megabytes. The
paper shows such levels as pictures; :func:`picture` draws them as one at ``DPI``, every pixel
as grey as the share of it the lines cover (their area: length times width), so the texture
looks like the vector panel from a distance.

The pixels are the same bytes on every machine: the points are rounded once to a grid of
``SUB`` steps per pixel, and from there on everything is integer arithmetic (the one square
root is IEEE's, correctly rounded everywhere, floored); no decision rests on the last bits of
a float.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .drawing import Polygons, Polylines, Raster

DPI = 600  # a laser printer's dots per inch: the paper's figures printed
MAX_SEGMENTS = 100_000  # per panel: 2 MB of SVG path data (rsvg opens it, a viewer slows)
SHIFT = 4
SUB = 1 << SHIFT  # grid steps per pixel the points are rounded to (16)
WIDTH_STEPS = 1024  # steps per pixel a line's width is rounded to (a sixteenth of a pixel
# made level 8's 0.0153 mm lines 4 % wider)
STEP = 4  # grid steps between samples along a line: four samples per pixel
CHUNK = 1 << 21  # samples held at once


def n_segments(shapes) -> int:
    """Straight pieces the stroked Polylines and Polygons of ``shapes`` draw."""
    n = 0
    for s in shapes:
        if isinstance(s, Polylines):
            n += max(0, len(s.coords) - (len(s.offsets) - 1))
        elif isinstance(s, Polygons) and s.style.stroke:
            n += len(s.coords)
    return n


def too_fine(shapes, dpi: float = DPI, max_segments: int = MAX_SEGMENTS) -> bool:
    """Whether ``shapes`` print as a texture, not as lines: a stroke thinner than a dot at
    ``dpi`` (hairlines, width 0, are cut lines and never are), or more than ``max_segments``."""
    dot = 25.4 / dpi
    thin = any(0 < s.style.stroke_width < dot for s in shapes
               if isinstance(s, (Polylines, Polygons)) and s.style.stroke)
    return thin or n_segments(shapes) > max_segments


def picture(shapes, dpi: float = DPI) -> Raster:
    """The stroked Polylines and Polygons ``shapes`` as a greyscale picture at ``dpi``, its
    box their bounds grown by a pixel (the corner on the 0.001 mm grid the writers write).

    Raises ValueError for a fill, a stroke wider than a pixel (the ink is laid along the
    centre line) or a picture over 100 megapixels."""
    shapes = tuple(shapes)
    pitch = 25.4 / dpi
    for s in shapes:
        if not isinstance(s, (Polylines, Polygons)) or (isinstance(s, Polygons) and (
                s.fills and any(s.fills) or s.style.fill)):
            raise ValueError(f"a picture draws strokes only, not a {type(s).__name__} "
                             "with a fill or text")
        if s.style.stroke and s.style.stroke_width > pitch:
            raise ValueError(f"a {s.style.stroke_width:g} mm stroke is wider than a pixel "
                             f"at {dpi:g} dpi ({pitch:.4f} mm); draw it as a vector")
    xy = np.concatenate([s.coords for s in shapes]) if shapes else np.zeros((0, 2))
    if not len(xy):
        raise ValueError("a picture of nothing")
    x0, y0 = np.floor((xy.min(axis=0) - pitch) * 1000) / 1000
    x1, y1 = xy.max(axis=0) + pitch
    w, h = int(np.ceil((x1 - x0) / pitch)), int(np.ceil((y1 - y0) / pitch))
    if w * h > 100_000_000:
        raise ValueError(f"a {w} x {h} px picture is too large; draw it at a lower dpi")
    top = y0 + h * pitch
    ink = np.zeros(w * h, dtype=np.int64)
    by_style: dict = {}  # the segments of all shapes of a style at once (a panel: hundreds)
    for s in shapes:
        if s.style.stroke:
            by_style.setdefault(s.style, []).append(_segments(s))
    for style, segs in by_style.items():
        ink += _ink(np.concatenate(segs), style, (float(x0), float(top)), (w, h), pitch)
    unit = SUB * WIDTH_STEPS  # ink per pixel covered
    grey = 255 - np.minimum(255, (ink + unit // 2) // unit)
    return Raster(float(x0), float(y0), w * pitch, h * pitch,
                  grey.reshape(h, w).astype(np.uint8), shapes)


def _segments(shape) -> NDArray[np.float64]:
    """(n, 2, 2) every straight piece of a Polylines, or of a Polygons' rings (closed)."""
    xy = shape.coords
    if isinstance(shape, Polylines):
        last = np.zeros(len(xy), dtype=bool)
        last[shape.offsets[1:] - 1] = True  # a line's last point starts no segment
        start = np.flatnonzero(~last)
        return np.stack([xy[start], xy[start + 1]], axis=1)
    ro = shape.ring_offsets
    sizes = np.diff(ro)
    nxt = np.arange(1, len(xy) + 1)
    nxt[ro[1:][sizes > 0] - 1] = ro[:-1][sizes > 0]  # each ring's last point to its first
    return np.stack([xy, xy[nxt]], axis=1)


def _ink(segs: NDArray[np.float64], style, corner, size, pitch: float) -> NDArray[np.int64]:
    """(H * W,) the ink of ``segs`` per pixel in SUB * WIDTH_STEPS parts of a pixel, times the
    darkness (0-255) of ``style``'s colour. Each segment is sampled every STEP grid steps; a
    sample lays its share of the segment's length (integer, the shares summing to the whole)
    times the line's width into the pixel it falls in."""
    w, h = size
    x0, top = corner
    grid = np.empty(segs.shape, dtype=np.int64)
    grid[..., 0] = np.rint((segs[..., 0] - x0) / pitch * SUB)
    grid[..., 1] = np.rint((top - segs[..., 1]) / pitch * SUB)  # down from the top
    d = grid[:, 1] - grid[:, 0]
    length = np.floor(np.sqrt((d * d).sum(axis=1).astype(np.float64))).astype(np.int64)
    n = length // STEP + 1
    width = int(np.rint(style.stroke_width / pitch * WIDTH_STEPS))
    dark = 255 - _luma(style.stroke)
    ink = np.zeros(w * h, dtype=np.int64)
    ends = np.cumsum(n)
    first = 0
    while first < len(segs):  # chunks of about CHUNK samples
        last = max(first + 1, int(np.searchsorted(ends, ends[first] - n[first] + CHUNK)))
        seg = np.repeat(np.arange(first, last), n[first:last])
        k = np.arange(len(seg)) - np.repeat(ends[first:last] - n[first:last] - ends[first]
                                            + n[first], n[first:last])
        m = n[seg]
        at = grid[seg, 0] + d[seg] * (2 * k + 1)[:, None] // (2 * m)[:, None]
        upto = length[seg] * (k + 1) // m  # the length up to the end of sample k's share
        share = upto.copy()
        share[1:] -= upto[:-1]
        share[k == 0] = upto[k == 0]  # a segment's first share starts at 0
        col = np.clip(at[:, 0] >> SHIFT, 0, w - 1)  # floor division by SUB
        row = np.clip(at[:, 1] >> SHIFT, 0, h - 1)
        # integer weights below 2**53: bincount's float sums are exact
        ink += np.bincount(row * w + col, weights=share * width, minlength=w * h).astype(
            np.int64)
        first = last
    return ink * dark


def _luma(colour: str) -> int:
    """Grey value (0-255) of ``#rrggbb``: ITU-R 601 weights, in integers."""
    r, g, b = (int(colour[i:i + 2], 16) for i in (1, 3, 5))
    return (299 * r + 587 * g + 114 * b + 500) // 1000
