"""Single-stroke vector text (Hershey Simplex Roman), and labels fitted inside polygons.

Lasers engrave and plotters draw lines, and CAM programs substitute or drop font-dependent text
entities; a stroke font turns text into plain polylines that every writer, cutter and viewer
shows the same. The glyphs are the public-domain Hershey fonts (1967), read from the
``Hershey-Fonts`` package (MIT licence, pure Python, no dependencies).

Coordinates are millimetres, y up. A label of height ``h`` has its cap height ``h``: digits and
capitals span exactly ``[0, h]`` above the baseline.

>>> coords, offsets, width = text_strokes("10", 3.0)
>>> round(float(coords[:, 1].max()), 6), len(offsets) - 1   # the 1 is one stroke, the 0 one more
(3.0, 2)
"""

from __future__ import annotations

from collections import OrderedDict
from functools import lru_cache
from threading import Lock

import numpy as np
import shapely
from numpy.typing import NDArray

from ..numeric import offsets_of, turn
from .hershey_futural import FONT, GLYPHS  # Hershey Simplex Roman: the engravers' font
from .labels import largest_fit
from .poles import poles

_CAP, _BASE = -12, 9  # raw cap and base lines (raw y points down)


@lru_cache(maxsize=1)
def _font():
    from HersheyFonts import HersheyFonts

    font = HersheyFonts()
    font.load_default_font(FONT)
    return font


@lru_cache(maxsize=256)
def _glyph(char: str) -> tuple[tuple[NDArray[np.float64], ...], float]:
    """Strokes of one character at cap height 1 (x from its left side), and its advance
    (printable ASCII from ``hershey_futural``, other characters from the package)."""
    if char in GLYPHS:
        left, width, raw = GLYPHS[char]
    else:
        glyph = next(iter(_font().glyphs_for_text(char)))
        left, width, raw = glyph.left_offset, glyph.char_width, glyph.strokes
    scale = 1.0 / (_BASE - _CAP)
    strokes = tuple(np.array([((x - left) * scale, (_BASE - y) * scale) for x, y in stroke])
                    for stroke in raw if len(stroke) > 1)
    return strokes, width * scale


def text_strokes(text: str, height: float) -> tuple[NDArray[np.float64], NDArray[np.int64],
                                                    float]:
    """Polylines of ``text`` with its baseline on y = 0, starting at x = 0.

    Returns
    -------
    coords : (N, 2) float64, mm
    offsets : (L + 1,) int64, polyline l is ``coords[offsets[l]:offsets[l + 1]]``
    width : the advance of the whole text, mm
    """
    coords, offsets, width = _unit_strokes(text)
    return coords * height, offsets.copy(), width * height


DIGITS = frozenset("0123456789")
UNDERLINE = "\u0332"  # COMBINING LOW LINE: at a text's end, one straight stroke under its ink
UNDER = 0.3  # the underline's depth below the baseline, per cap height (clear of the digits'
# strokes down to 1.5 mm numbers)
DIGIT_SIDE = 3 / 21  # the bearing either side of a digit's ink, at cap height 1 (the font's '0')


@lru_cache(maxsize=16)
def _digit(char: str) -> tuple[tuple[NDArray[np.float64], ...], float]:
    """A digit's strokes and advance, set proportionally: its ink ``DIGIT_SIDE`` from either
    side. The font's figures are tabular (all as wide as a '0'), which leaves a '1' alone in
    its wide cell and spreads a number's digits apart ("1 16"); set proportionally a number
    reads as one word."""
    strokes, _ = _glyph(char)
    left = min(float(s[:, 0].min()) for s in strokes)
    right = max(float(s[:, 0].max()) for s in strokes)
    return tuple(s - (left - DIGIT_SIDE, 0.0) for s in strokes), right - left + 2 * DIGIT_SIDE


@lru_cache(maxsize=4096)
def _unit_strokes(text: str) -> tuple[NDArray[np.float64], NDArray[np.int64], float]:
    """:func:`text_strokes` at cap height 1 (kept: labels repeat their texts); digits are set
    proportionally (:func:`_digit`); a text ending in ``UNDERLINE`` is underlined from its
    ink's left to its right, the line its last stroke."""
    strokes, x = [], 0.0
    body = text.removesuffix(UNDERLINE)
    for char in body:
        glyph, advance = _digit(char) if char in DIGITS else _glyph(char)
        strokes.extend(s + (x, 0.0) for s in glyph)
        x += advance
    if body != text and strokes:
        ink = np.concatenate(strokes)[:, 0]
        strokes.append(np.array([[ink.min(), -UNDER], [ink.max(), -UNDER]]))
    coords = np.concatenate(strokes) if strokes else np.zeros((0, 2))
    coords.flags.writeable = False
    return coords, offsets_of([len(s) for s in strokes]), x


# 4 floats each, and a puzzle's numbers are asked for again and again: 4,096 kept none of the
# 8-4 level-4 puzzle's 5,932 (118,000 misses for its two guides)
@lru_cache(maxsize=65536)
def ink_box(text: str) -> tuple[float, float, float, float]:
    """(x0, y0, x1, y1) of the strokes of ``text`` at cap height 1."""
    coords, _, _ = _unit_strokes(text)
    return (*coords.min(axis=0), *coords.max(axis=0)) if len(coords) else (0.0, 0.0, 0.0, 0.0)


def labels(texts: list[str], centres: NDArray[np.float64], heights: NDArray[np.float64],
           angles: NDArray[np.float64] | None = None
           ) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.int64]]:
    """Every text's strokes with its ink box centred on its centre, at its height, turned by
    its angle (degrees counter-clockwise).

    Returns
    -------
    coords : (N, 2) float64
    offsets : (L + 1,) int64 polyline offsets
    owner : (L,) int64 the label each polyline belongs to
    """
    angles = np.zeros(len(texts)) if angles is None else np.asarray(angles, dtype=float)
    units = [_unit_strokes(text) for text in texts]  # kept per text: all labels at once
    inked = [k for k, unit in enumerate(units) if len(unit[0])]
    if not inked:
        return np.zeros((0, 2)), np.zeros(1, dtype=np.int64), np.zeros(0, dtype=np.int64)
    h = np.asarray(heights, dtype=float)[inked]
    x0, y0, x1, y1 = (np.array([ink_box(texts[k]) for k in inked]) * h[:, None]).T
    points = [len(units[k][0]) for k in inked]
    lines = [len(units[k][1]) - 1 for k in inked]
    # each label's strokes at its height, less its ink box's centre, as text_strokes has them
    coords = np.concatenate([units[k][0] for k in inked]) * np.repeat(h, points)[:, None]
    coords -= np.repeat(np.column_stack([(x0 + x1) / 2, (y0 + y1) / 2]), points, axis=0)
    # every label's stroke ends after the points of the labels before it
    ends = np.concatenate([units[k][1][1:] for k in inked])
    offsets = np.r_[0, ends + np.repeat(np.cumsum(points) - points, lines)].astype(np.int64)
    owner = np.repeat(np.array(inked, dtype=np.int64), lines)
    point_owner = np.repeat(owner, np.diff(offsets))
    return turn(coords, angles[point_owner], np.asarray(centres, dtype=float)[point_owner]), \
        offsets, owner


class _Kept(OrderedDict):
    """At most ``most`` answers, the last asked for kept longest; the web app's threads share
    it (one lock for all)."""

    lock = Lock()

    def __init__(self, most: int) -> None:
        super().__init__()
        self.most = most

    def take(self, keys: list) -> list:
        """The answer kept for each key, or None."""
        with self.lock:
            found = [self.get(k) for k in keys]
            for k, v in zip(keys, found):
                if v is not None:
                    self.move_to_end(k)
        return found

    def keep(self, answers) -> None:
        with self.lock:
            self.update(answers)
            while len(self) > self.most:
                self.popitem(last=False)


_KEPT = 8192  # facts of polygons kept, by their WKB ...
_FITS = 16  # ... and the last fits asked for
_kept = _Kept(_KEPT)
_fits = _Kept(_FITS)


def _kept_values(what, keys: list[bytes], make) -> list:
    """Per key (a polygon's WKB: its type and every coordinate, exactly) its ``what``, kept
    from an earlier call or made now, all at once, by ``make`` (the keys not kept -> their
    values): a puzzle fits its engraved and its printed numbers into the same pieces and parts
    of them, with room round them and without, so the same polygon built twice is worked out
    once."""
    known = _kept.take([(what, k) for k in keys])
    new = list(dict.fromkeys(k for k, v in zip(keys, known) if v is None))
    if new:
        found = dict(zip(new, make(new)))
        known = [found[k] if v is None else v for k, v in zip(keys, known)]
        _kept.keep(((what, k), v) for k, v in found.items())
    return known


def _poles(polygons: NDArray[np.object_]) -> NDArray[np.float64]:
    """(N, 2) every polygon's pole of inaccessibility (the centre of its largest inscribed
    circle, :func:`~weavecut.layout.poles.poles`), kept (:func:`_kept_values`)."""
    keys = shapely.to_wkb(np.asarray(polygons, dtype=object).ravel()).tolist()
    return _facts(keys)[:, :2]


def _facts(keys: list[bytes]) -> NDArray[np.float64]:
    """(N, 3) the pole (x, y) and the long axis (:func:`_long_axes`) of every polygon, given
    by its WKB, kept (:func:`_kept_values`)."""
    def make(new):
        polygons = shapely.from_wkb(new)
        return map(tuple, np.column_stack([poles(polygons), _long_axes(polygons)]).tolist())

    return np.array(_kept_values("facts", keys, make), dtype=float).reshape(-1, 3)


def fit_labels(polygons: NDArray[np.object_], texts: list[str], margin: float, max_height,
               pad: float = 0.0, level_share: float = 1.0, level_least: float = 0.0
               ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The largest cap height (up to ``max_height``, a number or one per text) at which each
    text fits inside its polygon
    with ``margin`` mm to spare: centred on the polygon's pole of inaccessibility, its centroid
    or half-way between, level or along the polygon's long axis, whichever fits largest (the
    first on a tie). ``pad`` widens every text's ink box by that share of its cap height on
    each side (room that grows with the text: two texts fitted so stand apart by more than
    their letters do); a level text wins where it is at least ``level_share`` of the largest
    and at least ``level_least`` tall. The last fits asked for are kept (the same polygons,
    texts and sizes: a guide's back asks for its front's again).

    Parameters
    ----------
    polygons : (N,) shapely polygons, mm
    texts : N strings

    Returns
    -------
    heights : (N,) float64, 0 where not even a tiny label fits
    centres : (N, 2) float64, where each label's ink box is centred
    angles : (N,) float64, degrees counter-clockwise, in (-90, 90]
    """
    keys = shapely.to_wkb(np.asarray(polygons, dtype=object).ravel()).tolist()
    top = np.asarray(max_height, dtype=float)
    call = (tuple(keys), tuple(texts), float(margin), top.shape, top.tobytes(), float(pad),
            float(level_share), float(level_least))
    found, = _fits.take([call])
    if found is None:
        found = _fit(keys, texts, margin, top, pad, level_share, level_least)
        _fits.keep([(call, found)])
    return tuple(a.copy() for a in found)


def _fit(keys, texts, margin, max_height, pad, level_share, level_least) -> tuple:
    """:func:`fit_labels` of the polygons with WKB ``keys``."""
    polygons = shapely.from_wkb(keys)
    inner = np.array(_kept_values(("inner", float(margin)), keys, lambda new: shapely.buffer(
        shapely.from_wkb(new), -margin, join_style="mitre").tolist()), dtype=object)
    facts = _facts(keys)
    pole, long_axis = facts[:, :2].copy(), facts[:, 2].copy()
    middle = shapely.get_coordinates(shapely.centroid(polygons))
    boxes = np.array([ink_box(t) for t in texts], dtype=float).reshape(-1, 4)
    hx, hy = (boxes[:, 2] - boxes[:, 0]) / 2 + pad, (boxes[:, 3] - boxes[:, 1]) / 2 + pad
    level = np.stack([np.stack([-hx, -hy], -1), np.stack([hx, -hy], -1),
                      np.stack([hx, hy], -1), np.stack([-hx, hy], -1)], axis=1)
    n = len(texts)
    # every label at every (centre, angle) at once: pole, half-way, centroid; level, long axis
    spots = [(at, angle) for at in (pole, (pole + middle) / 2, middle)
             for angle in (np.zeros(n), long_axis)]
    boxes = turn(np.tile(level, (len(spots), 1, 1)),
                 np.concatenate([a for _, a in spots])[:, None])
    h = largest_fit(np.tile(inner, len(spots)), boxes,
                    np.concatenate([at for at, _ in spots]), 0.0,
                    np.tile(np.broadcast_to(np.asarray(max_height, dtype=float), (n,)), len(spots)))
    h = np.nan_to_num(h, nan=0.0).reshape(len(spots), n)
    best_h, best_a, centres = np.zeros(n), np.zeros(n), pole.copy()
    if level_share < 1.0:  # a level text that is nearly as large goes first
        flat = h[0::2].max(axis=0)
        level = (flat >= level_share * h.max(axis=0) - 1e-9) & (flat >= level_least)
        h = np.where((np.arange(len(spots)) % 2 == 1)[:, None] & level[None, :], 0.0, h)
    for (at, angle), fit in zip(spots, h):  # in order: the first of equal fits wins
        better = fit > best_h + 1e-9
        best_h, best_a = np.where(better, fit, best_h), np.where(better, angle, best_a)
        centres[better] = at[better]
    return best_h, centres, best_a


def _long_axes(polygons) -> NDArray[np.float64]:
    """(N,) direction of every polygon's minimum rotated rectangle's long side, in (-90, 90]."""
    rect = shapely.minimum_rotated_rectangle(polygons)
    ring = shapely.get_coordinates(shapely.get_exterior_ring(rect)).reshape(len(rect), -1, 2)
    e1, e2 = ring[:, 1] - ring[:, 0], ring[:, 2] - ring[:, 1]
    long = np.where((np.hypot(*e1.T) >= np.hypot(*e2.T))[:, None], e1, e2)
    angle = np.degrees(np.arctan2(long[:, 1], long[:, 0]))
    return np.where(angle <= -90, angle + 180, np.where(angle > 90, angle - 180, angle))
