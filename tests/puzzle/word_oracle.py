"""An independent reading of the numbers on a painting guide, from the Drawing alone.

Every number is one Polylines on the guide's "numbers" layer, in piece order (of the pieces
that have one), maybe after its plate. Read here without the library's checks:

- the fill under the ink: points along every stroke and on both its edges (half the stroke
  width off), every 0.1 mm, each looked up in the filled polygons in drawing order (the
  topmost that covers it, the paper where none does);
- the gap between two numbers: the distance between their stroke centre lines less half of
  each stroke width (or the plate's edge);
- the angle: the rotation that best lays the font's own strokes of the text onto the word's
  (Procrustes, over corresponding points), as the reader sees it on the sheet;
- the spread: the widest stretch along the reading direction with no ink, per cap height
  (a word whose digits stand apart has a wide one);
- the mark: the strokes a word has beyond its digits' (the font's strokes of the number),
  read as an underline where they are one straight stroke along the reading direction,
  under the digits' ink and as wide as it.
"""

from __future__ import annotations

import numpy as np
import shapely

from weavecut.layout.contrast import contrast_ratio
from weavecut.layout.drawing import Polygons, Polylines
from weavecut.layout.label_checks import filled
from weavecut.layout.strokefont import text_strokes


def words(sheet):
    """[(Polylines, plate polygon or None)] of the numbers layer, in order."""
    out, plate = [], None
    for layer in sheet.layers:
        if layer.name != "numbers":
            continue
        for shape in layer.shapes:
            if isinstance(shape, Polygons):
                plate = shapely.union_all(shape.to_shapely())
            else:
                out.append((shape, plate))
                plate = None
    return out


def _samples(word: Polylines, step: float = 0.1) -> np.ndarray:
    """Points on every stroke's centre line and on both its edges."""
    half = word.style.stroke_width / 2
    out = []
    for line in word.lines():
        for a, b in zip(line[:-1], line[1:]):
            d = b - a
            n = max(int(np.hypot(*d) / step), 1)
            t = np.linspace(0.0, 1.0, n + 1)[:, None]
            p = a + t * d
            normal = np.array([-d[1], d[0]]) / max(np.hypot(*d), 1e-12)
            out += [p, p + half * normal, p - half * normal]
        out.append(line[-1:] + half * np.array([[1, 0], [-1, 0], [0, 1], [0, -1]]))
    return np.concatenate(out)


def contrasts(sheet) -> np.ndarray:
    """Per number: its ink's least contrast with what lies under any of its sample points."""
    polys, fills = filled(sheet)  # every filled polygon, in drawing order
    tree = shapely.STRtree(polys)
    out = []
    for word, _ in words(sheet):
        pts = _samples(word)
        hit_pt, hit_poly = tree.query(shapely.points(pts), predicate="intersects")
        top = np.full(len(pts), -1)
        np.maximum.at(top, hit_pt, hit_poly)
        under = {fills[j] if j >= 0 else "#ffffff" for j in top.tolist()}
        out.append(min(contrast_ratio(word.style.stroke, c) for c in under))
    return np.array(out)


def gaps(sheet, plates: bool = True) -> np.ndarray:
    """Per number: the room (mm) to the nearest other number's ink, or plate (``plates``)."""
    ws = words(sheet)
    shapes = []
    for word, plate in ws:
        lines = shapely.multilinestrings([shapely.linestrings(x) for x in word.lines()])
        plated = plates and plate is not None
        shapes.append((plate if plated else lines, 0.0 if plated else word.style.stroke_width / 2))
    geoms = np.array([g for g, _ in shapes], dtype=object)
    pad = np.array([h for _, h in shapes])
    if not len(geoms):
        return np.zeros(0)
    tree = shapely.STRtree(geoms)
    out = np.full(len(ws), np.inf)
    a, b = tree.query(geoms, predicate="dwithin", distance=20.0)
    keep = a != b
    a, b = a[keep], b[keep]
    d = shapely.distance(geoms[a], geoms[b]) - pad[a] - pad[b]
    np.minimum.at(out, a, d)
    for k in np.flatnonzero(np.isinf(out)).tolist():  # far from all: every other one
        d = shapely.distance(geoms[k], np.delete(geoms, k)) - pad[k] - np.delete(pad, k)
        out[k] = d.min(initial=np.inf)
    return out


def pose(word: Polylines, text: str) -> tuple[float, float, float]:
    """(angle in degrees, cap height, worst misfit in mm) of the font's ``text`` laid onto
    ``word`` by a rotation, a scale and a shift; misfit is inf where the points do not pair."""
    ref, _, _ = text_strokes(text, 1.0)
    w = word.coords
    if len(ref) != len(w):
        return float("nan"), float("nan"), float("inf")
    rc, wc = ref - ref.mean(axis=0), w - w.mean(axis=0)
    h = rc.T @ wc
    angle = np.arctan2(h[0, 1] - h[1, 0], h[0, 0] + h[1, 1])
    c, s = np.cos(angle), np.sin(angle)
    turned = rc @ np.array([[c, s], [-s, c]])
    scale = float((turned * wc).sum() / (turned * turned).sum())
    misfit = float(np.hypot(*(turned * scale - wc).T).max())
    return float(np.degrees(angle)), scale, misfit


def split_mark(word: Polylines, number: str) -> tuple[Polylines, list]:
    """(the word's first strokes, as many as the font draws ``number`` with; the lines after
    them: its mark, [] for none)."""
    _, offsets, _ = text_strokes(number, 1.0)
    n = min(len(offsets) - 1, len(word.offsets) - 1)
    digits = Polylines(word.coords[:word.offsets[n]], word.offsets[:n + 1], word.style)
    return digits, word.lines()[n:]


def underlined(digits: Polylines, mark: list, angle: float, height: float) -> bool:
    """Whether ``mark`` is one straight stroke under ``digits`` (read at ``angle`` degrees,
    ``height`` cap): along the reading direction, below the digits' ink by at least a tenth
    of the cap height and at most half of it, spanning their ink's width (to a tenth)."""
    if len(mark) != 1 or len(mark[0]) != 2:
        return False
    a = np.radians(angle)
    frame = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])  # columns: along, up
    ink, line = digits.coords @ frame, mark[0] @ frame
    lo, hi = ink.min(axis=0), ink.max(axis=0)
    depth = lo[1] - line[:, 1]
    level = abs(line[1, 1] - line[0, 1]) <= 0.02 * height
    below = (depth >= 0.1 * height).all() and (depth <= 0.5 * height).all()
    span = np.sort(line[:, 0])
    wide = abs(span[0] - lo[0]) <= 0.1 * height and abs(span[1] - hi[0]) <= 0.1 * height
    return bool(level and below and wide)


def spread(word: Polylines, angle: float, height: float) -> float:
    """The widest stretch along the reading direction without ink, per cap height."""
    a = np.radians(angle)
    along = word.coords @ np.array([np.cos(a), np.sin(a)])
    segs = []
    for line in word.lines():
        x = line @ np.array([np.cos(a), np.sin(a)])
        segs += [(min(x[i], x[i + 1]), max(x[i], x[i + 1])) for i in range(len(x) - 1)]
    segs.sort()
    widest, reach = 0.0, along.min()
    for lo, hi in segs:
        widest = max(widest, lo - reach)
        reach = max(reach, hi)
    return widest / height


def word_figures(sheet, texts=None) -> dict:
    """Before/after figures of one guide sheet whose words are ``texts`` (default: every
    piece's, 1, 2, ...)."""
    c, g = contrasts(sheet), gaps(sheet)
    texts = texts or [str(k + 1) for k in range(len(words(sheet)))]
    digits = [split_mark(w, t)[0] for (w, _), t in zip(words(sheet), texts)]
    poses = [pose(w, t) for w, t in zip(digits, texts)]
    angles = np.array([p[0] for p in poses])
    spreads = [spread(w, p[0], p[1]) for w, p in zip(digits, poses)]
    return {"numbers": len(c), "under_4.5": int((c < 4.5).sum()),
            "min_contrast": round(float(c.min()), 2),
            "min_gap_mm": round(float(g.min()), 2),
            "touching_pairs": int((g <= 0).sum() // 2),
            "pairs_under_0.5mm": int((g < 0.5).sum() // 2),
            "not_upright": int((np.abs(angles) > 90 + 1e-6).sum()),
            "turned_over_10deg": int((np.abs(angles) > 10).sum()),
            "run_together": int((gaps(sheet, plates=False)
                                 < 0.3 * np.array([p[1] for p in poses])).sum()),
            "smallest_cap_mm": round(min(p[1] for p in poses), 2),
            "max_spread_per_cap": round(max(spreads), 2),
            "misfit_mm": round(max(p[2] for p in poses), 3)}
