"""Pages for paper strips: the printable area, splitting long strips, shelf packing, and what
every page carries (title, page number, a 100 mm scale bar, a legend).

Strips come in their own frame (mm, long axis along x from 0). Packing works in a frame whose
u axis runs along the longer side of the printable area; on a portrait page the strips are
turned by +90 degrees (never mirrored: a mirrored strip would weave the other way round).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import shapely
from numpy.typing import NDArray

from ..layout.drawing import Layer, Polygons, Polylines, Style, Text, polygons_from_shapely
from .strips import Strip, tint

HEADER = 13.0  # mm above the printable area for the title lines
FOOTER = 15.0  # mm below it for the scale bar and the legend
GAP = 3.0  # mm between strips, and between the area and header / footer
CUT = Style("#ff0000", 0.25)
TILE_LINE = Style("#555555", 0.12)
GLUE = "#9a9a9a"


@dataclass(frozen=True)
class PageArea:
    """A page and the rectangle strips may use, all in mm."""

    width: float
    height: float
    margin: float

    @property
    def footer(self) -> float:
        """Footer height: the legend sits beside the scale bar on wide pages, above it else."""
        return FOOTER if self.width - 2 * self.margin >= 190 else FOOTER + 10

    @property
    def box(self) -> tuple[float, float, float, float]:
        m = self.margin
        return (m, m + self.footer + GAP, self.width - m, self.height - m - HEADER - GAP)

    @property
    def portrait(self) -> bool:
        x0, y0, x1, y1 = self.box
        return y1 - y0 >= x1 - x0

    @property
    def long(self) -> float:
        x0, y0, x1, y1 = self.box
        return max(x1 - x0, y1 - y0)

    @property
    def short(self) -> float:
        x0, y0, x1, y1 = self.box
        return min(x1 - x0, y1 - y0)

    def check(self) -> None:
        if self.short < 20 or self.long < 40:
            raise ValueError(f"page {self.width:g} x {self.height:g} mm with margin "
                             f"{self.margin:g} mm leaves no room for strips")


def _shift(geoms, dx: float, dy: float = 0.0):
    return shapely.transform(geoms, lambda xy: xy + (dx, dy))


def split_strip(strip: Strip, max_length: float, overlap: float = 8.0) -> list[Strip]:
    """``strip`` cut into pieces no longer than ``max_length`` mm that overlap by ``overlap``
    mm to glue; pieces are labelled "A7 1/2", "A7 2/2" and the glue bands marked."""
    if strip.length <= max_length:
        return [strip]
    if max_length <= 2 * overlap:
        raise ValueError(f"a strip piece must be longer than twice the glue overlap "
                         f"({2 * overlap:g} mm); the page is too small for strip {strip.label}")
    step = max_length - overlap
    n = math.ceil((strip.length - overlap) / step)
    pieces = []
    for i in range(n):  # pieces of one strip
        a, b = i * step, min(i * step + max_length, strip.length)
        window = shapely.box(a - 1e-9, -1e3, b + 1e-9, 1e3)
        outline = shapely.intersection(strip.outline, window)
        tiles = shapely.intersection(strip.tiles, window)
        keep = ~shapely.is_empty(tiles) & (shapely.area(tiles) > 1e-9)
        arrows = shapely.intersection(strip.arrows, window)
        arrows = arrows[~shapely.is_empty(arrows)]
        texts = [t for t in strip.texts if a + 1 <= t.x <= b - 1]
        name = f"{strip.label} {i + 1}/{n}"
        bands = []
        size = 2.2
        _, y0, _, y1 = strip.outline.bounds
        if i + 1 < n:
            bands.append(shapely.intersection(strip.outline, shapely.box(b - overlap, -1e3, b, 1e3)))
            texts.append(Text(b - overlap / 2, (y0 + y1) / 2, f"glue {strip.label} {i + 2}/{n}",
                              size, "middle", 90.0, "#000000"))
        if i > 0:
            texts.append(Text(a + overlap / 2, (y0 + y1) / 2, f"under {strip.label} {i}/{n}",
                              size, "middle", 90.0, "#000000"))
        texts.append(Text(a + overlap + 1.5 if i else a + 1.5, y0 + 1.0, name, size, "start",
                          0.0, "#000000"))
        glue = np.array(bands, dtype=object) if bands else None
        piece = replace(strip, label=name, outline=outline, tiles=tiles[keep],
                        fills=tuple(f for f, k in zip(strip.fills, keep.tolist()) if k),
                        texts=tuple(texts), arrows=arrows, glue=glue)
        pieces.append(_moved(piece, -a, 0.0))
    return pieces


def _moved(strip: Strip, dx: float, dy: float) -> Strip:
    return replace(strip, outline=_shift(strip.outline, dx, dy),
                   tiles=_shift(strip.tiles, dx, dy), arrows=_shift(strip.arrows, dx, dy),
                   glue=None if strip.glue is None else _shift(strip.glue, dx, dy),
                   texts=tuple(replace(t, x=t.x + dx, y=t.y + dy) for t in strip.texts))


def pack(outlines, long: float, short: float, gap: float = GAP, step: float = 1.0
         ) -> list[list[tuple[int, bool, float, float]]]:
    """Bottom-left packing of strip outlines (frame: x along the strip) into long x short bins.

    Pieces go longest first. Each takes, on the first bin with room, the lowest v (then the
    lowest u) at which it stays ``gap`` mm clear of every piece already there; u is tried at 0
    and just past the end of every placed piece, v in ``step`` mm steps. So curved strips nest
    into each other's bays instead of each taking its bounding box.

    Pieces may be turned by 180 degrees (never mirrored) where that nests better.

    Returns per bin a list of (piece index, turned, u, v): the piece's bounding box, turned
    about its centre if ``turned``, goes with its lower-left corner to (u, v).
    """
    outlines = list(outlines)
    bounds = shapely.bounds(np.asarray(outlines, dtype=object)).reshape(-1, 4)
    sizes = bounds[:, 2:] - bounds[:, :2]
    too_big = (sizes[:, 0] > long + 1e-9) | (sizes[:, 1] > short + 1e-9)
    if too_big.any():
        i = int(np.flatnonzero(too_big)[0])
        raise ValueError(f"strip piece {i} ({sizes[i, 0]:.1f} x {sizes[i, 1]:.1f} mm) does not "
                         f"fit a {long:.1f} x {short:.1f} mm printable area")
    order = np.lexsort((np.arange(len(sizes)), -sizes[:, 1], -sizes[:, 0]))
    bins: list[list[tuple[int, bool, float, float]]] = []
    placed: list[list] = []  # per bin, placed outlines (bin frame)
    free: list[float] = []
    for i in order.tolist():  # strips, not mesh elements
        shape = shapely.transform(outlines[i], lambda xy: xy - bounds[i, :2])
        turned = shapely.transform(shape, lambda xy: sizes[i] - xy)  # the same, turned 180
        area = shape.area
        for b in range(len(bins) + 1):
            if b == len(bins):
                bins.append([])
                placed.append([])
                free.append(long * short)
            if free[b] < area:
                continue
            spots = [(_lowest_spot(g, sizes[i], placed[b], long, short, gap, step), flip, g)
                     for flip, g in enumerate((shape, turned))]
            spots = [sp for sp in spots if sp[0] is not None]
            if spots:
                (u, v), flip, g = min(spots, key=lambda sp: (sp[0][1], sp[0][0], sp[1]))
                bins[b].append((i, bool(flip), u, v))
                placed[b].append(shapely.transform(g, lambda xy: xy + (u, v)))
                free[b] -= area
                break
        else:  # pragma: no cover - a fresh bin always has room (checked above)
            raise AssertionError("packing failed")
    return bins


def _lowest_spot(shape, size, placed, long: float, short: float, gap: float, step: float):
    """(u, v) placing ``shape`` (lower-left at the origin) lowest in v, then in u."""
    if not placed:
        return (0.0, 0.0)
    blocked = shapely.buffer(shapely.union_all(placed), gap, quad_segs=2)
    shapely.prepare(blocked)
    ends = shapely.bounds(np.asarray(placed, dtype=object))[:, 2] + gap
    us = np.unique(np.round(np.r_[0.0, ends], 3))
    us = us[us + size[0] <= long + 1e-9]
    vs = np.arange(0.0, short - size[1] + 1e-9, step)
    if len(us) == 0 or len(vs) == 0:
        return None
    parts = [np.asarray(p.exterior.coords)[:-1] for p in shapely.get_parts(shape)
             if p.geom_type == "Polygon"]
    coords = np.concatenate(parts)
    part_of = np.repeat(np.arange(len(parts)), [len(p) for p in parts])
    n, n_parts = len(coords), len(parts)
    best = None
    for u in us.tolist():  # candidate positions, not mesh elements
        pts = coords[None] + np.column_stack([np.full(len(vs), u), vs])[:, None, :]
        ring_id = (np.arange(len(vs))[:, None] * n_parts + part_of[None, :]).ravel()
        rings = shapely.linearrings(pts.reshape(-1, 2), indices=ring_id)
        hit = shapely.intersects(blocked, shapely.polygons(rings))
        hit = hit.reshape(len(vs), n_parts).any(axis=1)
        ok = np.flatnonzero(~hit)
        if len(ok) and (best is None or vs[ok[0]] < best[1]):
            best = (u, float(vs[ok[0]]))
            if best[1] == 0.0:
                break
    return best


def placement(area: PageArea, bounds, turned: bool, u: float, v: float):
    """(transform, angle) taking a piece (frame ``bounds``), turned by 180 degrees about its
    box centre if ``turned``, to packing position (u, v) and onto the page: turned by a
    further +90 degrees on a portrait area (columns from the right)."""
    x0, y0, x1, y1 = area.box
    bx0, by0, bx1, by1 = bounds

    def frame(xy):
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        if turned:
            return np.column_stack([bx1 - xy[:, 0] + u, by1 - xy[:, 1] + v])
        return np.column_stack([xy[:, 0] - bx0 + u, xy[:, 1] - by0 + v])

    spin = 180.0 if turned else 0.0
    if area.portrait:
        def f(xy):
            p = frame(xy)
            return np.column_stack([x1 - p[:, 1], y0 + p[:, 0]])
        return f, 90.0 + spin

    def g(xy):
        p = frame(xy)
        return np.column_stack([x0 + p[:, 0], y0 + p[:, 1]])
    return g, spin


def placed_strip(strip: Strip, f, angle: float) -> Strip:
    """``strip`` moved onto the page by ``f`` (texts turned by ``angle`` degrees)."""
    texts = []
    for t in strip.texts:
        x, y = f([[t.x, t.y]])[0]
        texts.append(replace(t, x=float(x), y=float(y), angle=t.angle + angle))
    return replace(strip, outline=shapely.transform(strip.outline, f),
                   tiles=shapely.transform(strip.tiles, f),
                   arrows=shapely.transform(strip.arrows, f),
                   glue=None if strip.glue is None else shapely.transform(strip.glue, f),
                   texts=tuple(texts))


def _parts(geoms) -> list:
    parts = shapely.get_parts(np.asarray(geoms, dtype=object))
    return [p for p in parts if p.geom_type == "Polygon" and p.area > 1e-9]


def strip_layers(strips: list[Strip]) -> list[Layer]:
    """Layers for strips already on the page: tiles (fills and thin outlines), glue bands,
    arrows, labels and the cut lines."""
    tiles, fills, arrows_by_ink, glue, texts, outlines = [], [], {}, [], [], []
    for s in strips:
        for tile, fill in zip(s.tiles, s.fills):
            for part in _parts([tile]):
                tiles.append(part)
                fills.append(fill)
        arrows_by_ink.setdefault(s.arrow_ink, []).extend(_parts(s.arrows))
        if s.glue is not None:
            glue.extend(_parts(s.glue))
        texts.extend(s.texts)
        outlines.extend(_parts([s.outline]))
    layers = [Layer("strips", "paint", (polygons_from_shapely(tiles, TILE_LINE, fills),))]
    if glue:
        layers.append(Layer("glue", "paint", (polygons_from_shapely(
            glue, Style("#555555", 0.15, GLUE, 0.45)),)))
    arrow_shapes = tuple(polygons_from_shapely(g, Style(None, 0.0, ink))
                         for ink, g in sorted(arrows_by_ink.items()) if g)
    layers.append(Layer("arrows", "paint", arrow_shapes))
    layers.append(Layer("labels", "label", tuple(texts)))
    layers.append(Layer("cut", "cut", (polygons_from_shapely(outlines, CUT),)))
    return layers


def scale_bar(x: float, y: float, length: float = 100.0) -> tuple:
    """A ``length`` mm bar from (x, y) with ticks every 10 mm, and its caption."""
    ticks = np.arange(0, length + 1e-9, 10.0)
    tall = np.where(np.isclose(ticks % 50, 0), 2.0, 1.0)
    tick_lines = np.stack([np.column_stack([x + ticks, np.full_like(ticks, y)]),
                           np.column_stack([x + ticks, y + tall])], axis=1).reshape(-1, 2)
    bar = Polylines(np.array([[x, y], [x + length, y]]), np.array([0, 2], dtype=np.int64),
                    Style("#000000", 0.3))
    marks = Polylines(tick_lines, np.arange(0, len(tick_lines) + 1, 2, dtype=np.int64),
                      Style("#000000", 0.2))
    caption = Text(x + length / 2, y + 2.8, f"{length:g} mm: check this at 100 % scale",
                   2.2, "middle")
    return bar, marks, caption


LEGEND = (
    ("own", "on top"),
    ("light", "under: ID = strand on top"),
    ("cut", "cut line"),
    ("glue", "glue overlap"),
)


def page_layers(area: PageArea, title: str, subtitle: str, number: int, total: int,
                sample: str = "#3e9fb0", glue: bool = False) -> list[Layer]:
    """Title, page number, a 100 mm scale bar and a legend for one page."""
    w, h, m = area.width, area.height, area.margin
    texts = [Text(m, h - m - 4.5, title, min(4.0, (w - 2 * m - 28) / (0.7 * max(len(title), 1)))),
             Text(w - m, h - m - 4.5, f"page {number} / {total}", 3.2, "end"),
             *(Text(m, h - m - 9.8 - 3.4 * i, line, 2.2)
               for i, line in enumerate(_wrap(subtitle, (w - 2 * m) / 1.55, 2)))]
    bar, marks, caption = scale_bar(m, m + 1.5)
    shapes: list = [bar, marks, caption]
    # legend: to the right of the bar on wide pages, above it otherwise
    lx, ly = (m + 108.0, m + 1.0) if w - 2 * m >= 190 else (m, m + 7.5)
    swatches, fills, strokes = [], [], []
    entries = [e for e in LEGEND if glue or e[0] != "glue"]
    col_w = 28.0
    for i, (kind, text) in enumerate(entries):
        x = lx + (i % 2) * col_w
        y = ly + (1 - i // 2) * 5.0
        box = shapely.box(x, y, x + 5, y + 3)
        if kind == "cut":
            strokes.append(box)
        else:
            swatches.append(box)
            fills.append({"own": sample, "light": tint(sample), "glue": GLUE}[kind])
        texts.append(Text(x + 6.5, y + 0.5, text, 2.2))
    if swatches:
        shapes.append(polygons_from_shapely(swatches, TILE_LINE, fills))
    if strokes:
        shapes.append(polygons_from_shapely(strokes, CUT))
    return [Layer("page", "label", tuple(shapes) + tuple(texts))]


def _wrap(text: str, chars: float, lines: int) -> list[str]:
    """``text`` broken at spaces into at most ``lines`` lines of about ``chars`` characters."""
    out, line = [], ""
    for word in text.split(" "):
        if line and len(line) + 1 + len(word) > chars:
            out.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    out.append(line)
    if len(out) > lines:
        out = out[:lines - 1] + [" ".join(out[lines - 1:])]
    return out


def occupied(layers: list[Layer]) -> list[shapely.Geometry]:
    """The cut outlines on a sheet's "cut" layer as shapely polygons (for checks)."""
    out = []
    for layer in layers:
        if layer.role == "cut":
            for shape in layer.shapes:
                if isinstance(shape, Polygons):
                    out.extend(shape.to_shapely().tolist())
    return out
