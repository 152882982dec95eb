"""Pages for paper strips: the printable area, splitting long strips, and what every page
carries (title, page number, a 100 mm scale bar, a legend). ``packing`` places the strips.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import shapely
from numpy.typing import NDArray

from ..layout.drawing import (Layer, Polygons, Polylines, Style, Text, polygons_from_shapely,
                              polylines_from_lines)
from ..layout.contrast import text_colour_on
from ..layout.labels import DESCENT, MIN_CAP, text_box, text_width
from ..numeric import affine
from .header import SMALL, shortened, wrapped
from .slim import outline_of, printed_once, thickened
from .strips import MIN_PIECE, Strip, flat_angle, tint
from .unfold import dashed

HEADER = 10.0  # mm above the printable area for the title line and one line of subtitle
FOOTER = 8.5  # mm below it for the scale bar and the legend
GAP = 2.0  # mm between strips (at least), and between the area and header / footer
FURNITURE_GAP = 1.0  # mm at least between the boxes of two texts of the page furniture
PITCH = SMALL * (1 + DESCENT) + FURNITURE_GAP  # mm from one subtitle line to the next
CUT = Style("#ff0000", 0.25)
TILE_LINE = Style("#555555", 0.12)
GLUE = "#c8c8c8"
FOLD = Style("#333333", 0.3)  # dashed fold lines of strips unfolded from a surface
EDGE = 1e-6  # mm: a point this near a band's edge is on the edge, not on the band
FLAP_LINE = Style("#333333", 0.3)  # dashed line where a label tab is cut off after weaving
FLAP_DASH = (0.6, 0.4)  # mm dash and gap


def page_span(pages, short: bool = False) -> str:
    """"pages 3-4", or "page 3" for a single page ("p. 3-4", "p. 3" when ``short``), of the
    consecutive page numbers ``pages``; "-" if there are none."""
    if not len(pages):
        return "-"
    first, last = pages[0], pages[-1]
    word = "p." if short else "page" if first == last else "pages"
    return f"{word} {first}" if first == last else f"{word} {first}-{last}"


@dataclass(frozen=True)
class PageArea:
    """A page and the rectangle strips may use, all in mm; ``limit`` (x0, y0, x1, y1), when
    given, bounds that rectangle further (the area a cutter reads). A sheet without
    ``furniture`` (a sheet of card: no title, page number or legend) gives strips all of it
    inside the margin; the header above it holds ``header_lines`` lines of subtitle."""

    width: float
    height: float
    margin: float
    limit: tuple[float, float, float, float] | None = None
    furniture: bool = True
    header_lines: int = 1

    @property
    def header(self) -> float:
        """Header height: the title line and the subtitle's lines."""
        return HEADER + (self.header_lines - 1) * PITCH

    @property
    def plain(self) -> PageArea:
        """The page with one line of subtitle, as the pages before the strips have."""
        return replace(self, header_lines=1)

    @property
    def footer(self) -> float:
        """Footer height: the legend sits beside the scale bar on wide pages, above it else."""
        return FOOTER if self.width - 2 * self.margin >= 190 else FOOTER + 6

    @property
    def box(self) -> tuple[float, float, float, float]:
        m = self.margin
        box = ((m, m + self.footer + GAP, self.width - m, self.height - m - self.header - GAP)
               if self.furniture else (m, m, self.width - m, self.height - m))
        if self.limit is None:
            return box
        return (*np.maximum(box[:2], self.limit[:2]).tolist(),
                *np.minimum(box[2:], self.limit[2:]).tolist())

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


def rect_sides(geoms) -> np.ndarray:
    """(n, 2) the short and the long side of each of ``geoms``' smallest rectangles."""
    rects = shapely.minimum_rotated_rectangle(np.asarray(geoms, dtype=object))
    corners = shapely.get_coordinates(shapely.get_exterior_ring(rects)).reshape(-1, 5, 2)[:, :3]
    return np.sort(np.hypot(*np.diff(corners, axis=1).transpose(2, 0, 1)), axis=1)


def _fits(geom, length: float, width: float) -> bool:
    short, long = rect_sides([geom])[0]
    return bool(long <= length and short <= width)


GLUE_MARKS = {"mixed": "{}", "module": "({})"}  # per layout: what marks the tile a glue band
# goes under; a module strip's ID is a bare number ("1"), so its marks are bracketed ("(1)")


def split_strip(strip: Strip, max_length: float, max_width: float,
                mark: str = "{}") -> list[Strip]:
    """``strip`` (unlabelled) as it is if it fits a ``max_length`` x ``max_width`` rectangle,
    else cut into runs of whole tiles that do, each laid flat. Consecutive pieces share one
    tile: on the earlier piece it is the glue band ("glue 1"), glued under the same tile of the
    next, which is marked (``mark`` of 1: "1" as the ball's are, "(1)" in the module layout,
    ``GLUE_MARKS``). Pieces are named "A7 1/2", "A7 2/2"."""
    if _fits(strip.outline, max_length, max_width):
        return [strip]
    tiles, n = strip.tiles, len(strip.tiles)
    runs, a = [], 0
    while True:  # runs of tiles
        b = a + 1
        while b + 1 < n and _fits(shapely.union_all(tiles[a:b + 2]), max_length, max_width):
            b += 1
        runs.append((a, min(b, n - 1)))
        if b >= n - 1:
            break
        a = b
    # as many runs, of equal length where they still fit (no short stub at the end)
    ends = np.round(np.linspace(0, n - 1, len(runs) + 1)).astype(int)
    even = list(zip(ends[:-1].tolist(), ends[1:].tolist()))
    if all(_fits(shapely.union_all(tiles[a:b + 1]), max_length, max_width) for a, b in even):
        runs = even
    eps = 1e-6 * max(strip.length, 1.0)
    pieces = []
    for i, (a, b) in enumerate(runs):
        part = slice(a, b + 1)  # cut where a strip was mended: mended again (see .slim)
        outline, mine = thickened(outline_of(tiles[part], eps), tiles[part], MIN_PIECE)
        piece = replace(strip, label=f"{strip.label} {i + 1}/{len(runs)}",
                        outline=outline, tiles=mine,
                        fills=strip.fills[part], over=strip.over[part], names=strip.names[part],
                        glue=tiles[b:b + 1] if i + 1 < len(runs) else None,
                        tab=f"glue {i + 1}" if i + 1 < len(runs) else "glue",
                        mark=mark.format(i) if i else "")
        flat = piece.moved(affine(flat_angle(piece.outline)))
        x0, y0 = flat.outline.bounds[:2]
        pieces.append(flat.moved(affine(0.0, (-x0, -y0))))
    return pieces


def _parts(geoms, tags=None):
    """The polygons of some area among the parts of ``geoms``, in order; with ``tags`` (one per
    geometry: its fill, its ink) also each part's tag."""
    parts, of = shapely.get_parts(np.asarray(geoms, dtype=object), return_index=True)
    keep = (shapely.get_type_id(parts) == 3) & (shapely.area(parts) > 1e-9)
    if tags is None:
        return parts[keep].tolist()
    return parts[keep].tolist(), [tags[i] for i in of[keep].tolist()]


def _printed(strips: list[Strip]) -> tuple[NDArray[np.object_], list, NDArray[np.intp]]:
    """(tiles, fills, owner): every strip's tiles and its label tab, if it has one, as
    printed, with each one's fill and strip: the paper two tiles of a strip share printed once
    (:func:`.slim.printed_once`)."""
    tiles = [(*s.tiles, *(() if s.flap is None else (s.flap,))) for s in strips]
    fills = [f for s, t in zip(strips, tiles) for f in (s.fills + (s.flap_fill,))[:len(t)]]
    owner = np.repeat(np.arange(len(strips)), [len(t) for t in tiles])
    return printed_once(np.array([g for t in tiles for g in t], dtype=object), owner), fills, \
        owner


def strip_layers(strips: list[Strip], bleed: float = 0.0) -> list[Layer]:
    """Layers for strips already on the page: tiles (fills and thin outlines), glue bands,
    fold lines, arrows, labels and the cut lines; with a ``bleed`` (mm, print and cut) no cut
    lines but the strips' colours bled that far past them (:func:`bleed_layer`)."""
    printed, fills, _ = _printed(strips)
    tiles, fills = _parts(printed, fills)
    plates = [g for s in strips for g in s.plates.tolist()]
    plate_fills = [f for s in strips for f in s.plate_fills]
    arrows, inks = _parts([a for s in strips for a in s.arrows],
                          [s.arrow_ink for s in strips for _ in s.arrows])
    arrows_by_ink: dict[str, list] = {}
    for arrow, ink in zip(arrows, inks):
        arrows_by_ink.setdefault(ink, []).append(arrow)
    glue = _parts([g for s in strips if s.glue is not None for g in s.glue])
    texts = [t for s in strips for t in s.texts]
    outlines = _parts([s.cut for s in strips])
    # the label plates over the tiles as a shape of their own: a writer may paint one shape's
    # polygons grouped by fill, which would put a plate under the tile it covers
    painted = (polygons_from_shapely(tiles, TILE_LINE, fills),) if bleed <= 0 else (
        polygons_from_shapely(tiles, Style(None, 0.0), fills), inner_borders(strips))
    layers = [Layer("strips", "paint", painted + (
        (polygons_from_shapely(plates, TILE_LINE, plate_fills),) if plates else ()))]
    if glue:
        layers.append(Layer("glue", "paint", (polygons_from_shapely(
            glue, Style("#555555", 0.15, GLUE)),)))
    folds_by_ink: dict[str, list] = {}
    for s in strips:  # a fold's dashes on the glue band in the ink that reads on the band
        # (a dash along the band's edge, its centre on the edge, keeps its ink: the band is
        # shrunk by far more than rounding moves a point, so no last bit decides)
        band = None if s.glue is None else shapely.buffer(shapely.union_all(s.glue), -EDGE)
        for fold, ink in zip(s.folds, s.fold_inks):
            dashes = shapely.get_parts(fold)
            on_band = (np.zeros(len(dashes), dtype=bool) if band is None
                       else shapely.contains(band, shapely.centroid(dashes)))
            for where, dash_ink in ((on_band, text_colour_on(GLUE)), (~on_band, ink)):
                if where.any():
                    folds_by_ink.setdefault(dash_ink, []).extend(dashes[where].tolist())
    if folds_by_ink:
        layers.append(Layer("folds", "score", tuple(polylines_from_lines(
            [np.asarray(f.coords) for f in lines], replace(FOLD, stroke=ink))
            for ink, lines in sorted(folds_by_ink.items()))))
    tabs = [s for s in strips if s.flap_edge is not None]
    if tabs:  # "cut off after weaving", in the ink that reads on the tab
        coords = shapely.get_coordinates([s.flap_edge for s in tabs]).reshape(-1, 2, 2)
        dashes = dashed(coords[..., 0] + 1j * coords[..., 1], *FLAP_DASH)
        by_ink: dict[str, list] = {}
        for s, d in zip(tabs, dashes):
            by_ink.setdefault(text_colour_on(s.flap_fill), []).extend(shapely.get_parts(d))
        layers.append(Layer("tabs", "paint", tuple(polylines_from_lines(
            [np.asarray(d.coords) for d in lines], replace(FLAP_LINE, stroke=ink))
            for ink, lines in sorted(by_ink.items()))))
    arrow_shapes = tuple(polygons_from_shapely(g, Style(None, 0.0, ink))
                         for ink, g in sorted(arrows_by_ink.items()) if g)
    layers.append(Layer("arrows", "paint", arrow_shapes))
    layers.append(Layer("labels", "label", tuple(texts)))
    if bleed > 0:
        return [bleed_layer(strips, bleed), *layers]
    layers.append(Layer("cut", "cut", (polygons_from_shapely(outlines, CUT),)))
    return layers


def inner_borders(strips: list[Strip]) -> Polylines:
    """The tiles' thin outlines where they border each other, not along a strip's cut line
    (print and cut: a line there would show on the strip's edge as a cut line would)."""
    lines = []
    tiles, _, owner = _printed(strips)
    for i, s in enumerate(strips):
        edge = shapely.buffer(shapely.boundary(s.cut), 1e-6)
        borders = shapely.difference(
            shapely.union_all(shapely.boundary(tiles[owner == i])), edge)
        lines += [np.asarray(g.coords) for g in shapely.get_parts(shapely.line_merge(borders))
                  if g.length > 1e-6]
    return polylines_from_lines(lines, TILE_LINE)


def bleed_layer(strips: list[Strip], bleed: float) -> Layer:
    """What a print-and-cut page prints under its strips in place of their cut lines: every
    tile (and tab) grown by ``bleed`` mm, clipped to its strip's outline grown as far, in the
    tile's colour and without an outline, so a cutter that cuts up to ``bleed`` off the
    printed page still leaves colour to the strip's edge; inside the strip the true tiles
    cover it and nothing changes."""
    tiles, fills, owner = _printed(strips)
    rooms = shapely.buffer(np.array([s.cut for s in strips], dtype=object), bleed)
    grown, fills = _parts(shapely.intersection(shapely.buffer(tiles, bleed), rooms[owner]),
                          fills)
    return Layer("bleed", "paint", (polygons_from_shapely(grown, Style(None, 0.0), fills),))


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
    caption = Text(x + length / 2, y + 3.0, f"{length:g} mm: check this at 100 % scale",
                   SMALL, "middle")
    return bar, marks, caption


LEGEND_BASE = 0.25  # mm from a legend swatch's bottom edge up to its text's baseline
LEGEND = (
    ("own", "on top"),
    ("light", "under"),
    ("cut", "cut"),
    ("glue", "glue"),
    ("fold", "fold"),
    ("tab", "tab: cut off after weaving"),
)


def page_layers(area: PageArea, title: str, subtitle: str, number: int, total: int,
                sample: str = "#3e9fb0", glue: bool = False, folds: bool = False,
                tabs: bool = False, legend: bool = True, bar: bool = False,
                cut: bool = True) -> list[Layer]:
    """Title, page number, a 100 mm scale bar and a legend for one page (all text at least
    ``MIN_CAP`` tall, in the margins outside the printable box); ``glue``, ``folds`` and ``tabs``
    add their entries. Without ``legend`` (pages that neither show printed strips nor need
    printing at true scale) the bar and the legend are left out, the bar kept with ``bar`` (a
    page with one drawing at 100 %). Without ``cut`` (print and cut: no cut line is printed)
    the legend has no "cut" entry."""
    w, h, m = area.width, area.height, area.margin
    number_text = f"page {number} / {total}"
    room = w - 2 * m - text_width(number_text, 3.2) - 4
    title = shortened(title, room, MIN_CAP)
    title_size = max(MIN_CAP, min(4.0, 4.0 * room / max(text_width(title, 4.0), 1e-9)))
    head = Text(m, h - m - 4.0, title, title_size)
    below = min(h - m - 8.5, text_box(head).bounds[1] - FURNITURE_GAP - SMALL)  # the subtitle
    texts = [head, Text(w - m, h - m - 4.0, number_text, 3.2, "end"),
             *(Text(m, below - i * PITCH, line, SMALL) for i, line in
               enumerate(wrapped(subtitle, w - 2 * m, area.header_lines)))]
    if not legend:
        return [Layer("page", "label", (scale_bar(m, m + 1.5) if bar else ()) + tuple(texts))]
    bar, marks, caption = scale_bar(m, m + 1.5)
    shapes: list = [bar, marks, caption]
    # legend: right of the bar on wide pages, above its caption otherwise (FURNITURE_GAP clear
    # of the caption's box, under a text with descenders); entries left to right
    above = text_box(caption).bounds[3] + FURNITURE_GAP + DESCENT * SMALL - LEGEND_BASE
    x, y = (m + 106.0, m + 0.5) if w - 2 * m >= 190 else (m, above)
    start = x
    swatches, fills, strokes, dashes = [], [], [], []
    shown = {"glue": glue, "fold": folds, "tab": tabs, "cut": cut}
    for kind, text in (e for e in LEGEND if shown.get(e[0], True)):
        step = 6.5 + text_width(text, SMALL) + 2.5
        if x + step > w - m and x > start:
            x, y = start, y + 5.0
        box = shapely.box(x, y, x + 5, y + 3)
        if kind == "cut":
            strokes.append(box)
        elif kind in ("fold", "tab"):
            dashes += [np.array([[x + a, y + 1.5], [x + a + 1.5, y + 1.5]]) for a in (0, 1.75, 3.5)]
        else:
            swatches.append(box)
            fills.append({"own": sample, "light": tint(sample), "glue": GLUE}[kind])
        texts.append(Text(x + 6.5, y + LEGEND_BASE, text, SMALL))
        x += step
    if swatches:
        shapes.append(polygons_from_shapely(swatches, TILE_LINE, fills))
    if strokes:
        shapes.append(polygons_from_shapely(strokes, CUT))
    if dashes:
        shapes.append(polylines_from_lines(dashes, FOLD))
    return [Layer("page", "label", tuple(shapes) + tuple(texts))]


def occupied(layers: list[Layer]) -> list[shapely.Geometry]:
    """The cut outlines on a sheet's "cut" layer as shapely polygons (for checks)."""
    out = []
    for layer in layers:
        if layer.role == "cut":
            for shape in layer.shapes:
                if isinstance(shape, Polygons):
                    out.extend(shape.to_shapely().tolist())
    return out
