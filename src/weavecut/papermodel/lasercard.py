"""Paper strips laser-cut from coloured card: no printer needed.

Every strip is cut from card of its strand's colour: the strips are grouped by colour and packed
onto the material's sheets, one sheet set per colour. The cut layer holds each strip's outline
(grown by half the kerf, so the strip comes out true to size), cut last; the engrave layer
holds, in single strokes, what the printed strip shows: the strip's ID in its own tile, the ID
of the strand on top in every under tile (the under-crossing marks) and the direction arrows'
outlines, and the glue band's edge on a piece of a split strip; the score layer the border
between every two tiles of a strip, so that its tiles, on top and under in turn, show on the
card as the printed tiles' colours show on paper (a light pass: the card creases there, where
it bends over and under). An under tile whose name is left out (too small to engrave, or to
print) gets an engraved dot, as the assembly sheet's callouts show such a crossing. A label tab
(the ID of a strip too small to hold it) is cut with its strip, as on paper, its ID engraved on
it and the line where it is cut off after weaving engraved too. Every engraved or scored line
keeps ``ENGRAVE_MARGIN`` inside its strip, and the score lines keep ``SCORE_CLEAR`` off the
engraved labels.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
import shapely
from numpy.typing import NDArray

from ..numeric import affine, matmul
from ..layout import nesting, strokefont
from ..layout.drawing import (
    Drawing,
    Layer,
    Sheet,
    Text,
    polylines_from_lines,
)
from ..layout.labels import inner_centres, largest_fit, text_boxes
from ..layout.lasersetup import Laser
from .packing import pack
from .pages import GAP
from .printcut import CutReport, cut_layer, cut_report, ordered_outlines
from .strips import Strip

ENGRAVE_MARGIN = 1.0  # mm between an engraved line and its strip's edge (card scorches there)
MIN_ENGRAVED = 1.5  # mm: a smaller label is left out
SHEET_MARGIN = 5.0  # mm of card round every sheet (where the laser bed's stops hold it)
SCORE_CLEAR = 0.6  # mm between a score line and an engraved label
DOT = 0.8  # mm, the radius of the engraved ring in an under tile that carries no name
QUICK = {"cell": 1.5, "angle_step": 30.0}  # a card colour's first packing: grid mm, turns degrees


@dataclass(frozen=True, eq=False)
class CardCut:
    """The card sheets and what the summary and the tests need.

    Parameters
    ----------
    sheets : one Drawing per sheet (engrave layer, then the cut layer)
    colours : (N,) the card colour of every sheet
    pieces : (N,) per sheet, the strips on it, moved to their places (true outlines); a
        strip's ``left_out`` holds every under tile that carries no engraved name (a dot)
    texts : (N,) per sheet, per strip, the engraved labels' strokes as (coords, offsets, the
        label of every polyline)
    scores : (N,) per sheet, the score lines (tile borders) as (n, 2) arrays
    dots : (N,) per sheet, the engraved rings' centres as (n, 2)
    report : cut length, outlines, duplicates, smallest feature over every sheet
    smallest_label : mm, the smallest engraved label
    fill : the share of the sheets' area inside their margins that the strips cover
    """

    sheets: tuple[Drawing, ...]
    colours: tuple[str, ...]
    pieces: tuple[tuple[Strip, ...], ...]
    texts: tuple[tuple[tuple[NDArray, NDArray], ...], ...]
    scores: tuple[tuple[NDArray, ...], ...]
    dots: tuple[NDArray, ...]
    report: CutReport
    smallest_label: float
    fill: float


class Engraved(NamedTuple):
    """A strip's engraved labels: strokes (coords, offsets, the label of every polyline), the
    smallest height, and the labels left out (too small to engrave)."""

    coords: NDArray[np.float64]
    offsets: NDArray[np.int64]
    which: NDArray[np.int64]
    smallest: float
    dropped: tuple[Text, ...]


def engraved_labels(strips: list[Strip], margin: float = ENGRAVE_MARGIN) -> list[Engraved]:
    """Per strip, single-stroke labels where the printed ones are, each as large as fits (up to
    the printed size) in its printed box (printed boxes do not overlap), ``margin`` inside the
    strip; a label under ``MIN_ENGRAVED`` is left out. All strips' labels are fitted at
    once."""
    texts = [[t for t in s.texts if isinstance(t, Text)] for s in strips]
    owner = np.repeat(np.arange(len(strips)), [len(t) for t in texts])
    flat = [t for group in texts for t in group]
    heights = np.zeros(0)
    if flat:
        inner = shapely.buffer([s.cut for s in strips], -margin, join_style="mitre")
        regions = shapely.intersection(text_boxes(flat), inner[owner])
        cap = np.array([max(t.size for t in group) if group else 0.0 for group in texts])
        heights, centres, angles = strokefont.fit_labels(regions, [t.text for t in flat], 0.0,
                                                         cap[owner])
        heights = np.minimum(heights, [t.size for t in flat])
    out = []
    for k, group in enumerate(texts):  # strips
        mine = np.flatnonzero(owner == k)
        keep = mine[heights[mine] >= MIN_ENGRAVED]
        if not group:
            out.append(Engraved(np.zeros((0, 2)), np.zeros(1, dtype=np.int64),
                                np.zeros(0, dtype=np.int64), np.inf, ()))
            continue
        coords, offsets, which = strokefont.labels([flat[i].text for i in keep.tolist()],
                                                   centres[keep], heights[keep], angles[keep])
        out.append(Engraved(coords, offsets, which,
                            float(heights[keep].min()) if len(keep) else np.inf,
                            tuple(flat[i] for i in sorted(set(mine.tolist()) - set(keep.tolist())))))
    return out


def unnamed_tiles(strip: Strip, dropped: tuple[Text, ...]) -> tuple[int, ...]:
    """The under tiles of ``strip`` that carry no name on card: those the printed strip leaves
    unnamed, and those whose name was too small to engrave (``dropped``: each the under tile
    of its name nearest to it)."""
    out = set(strip.left_out)
    under = np.flatnonzero(~strip.over)
    for t in dropped:  # labels left out, a few at most
        mine = [int(i) for i in under if strip.names[i] == t.text]
        if mine:
            at = shapely.Point(t.x, t.y)
            out.add(min(mine, key=lambda i: (strip.tiles[i].distance(at), i)))
    return tuple(sorted(out))


def score_lines(strips: list[Strip], engraved: list[Engraved],
                margin: float = ENGRAVE_MARGIN) -> list[list[NDArray[np.float64]]]:
    """Per strip, the borders between its consecutive tiles (not the one a glue band's edge
    already marks), ``margin`` inside the strip and ``SCORE_CLEAR`` off its engraved labels
    and arrows."""
    pairs = [(k, i) for k, s in enumerate(strips)
             for i in range(len(s.tiles) - 1 - (s.glue is not None))]
    if not pairs:
        return [[] for _ in strips]
    owner = np.array([k for k, _ in pairs], dtype=np.int64)
    first = np.array([strips[k].tiles[i] for k, i in pairs], dtype=object)
    second = np.array([strips[k].tiles[i + 1] for k, i in pairs], dtype=object)
    borders = shapely.intersection(shapely.boundary(first), shapely.boundary(second))
    keep_out = []
    for s, e in zip(strips, engraved):  # strips: their labels' hulls and their arrows
        label = np.repeat(e.which, np.diff(e.offsets))
        hulls = (shapely.convex_hull(shapely.multipoints(e.coords, indices=label)).tolist()
                 if len(e.coords) else [])
        keep_out.append(shapely.union_all([*hulls, *s.arrows.tolist()]))
    inner = shapely.buffer([s.cut for s in strips], -margin, join_style="mitre")
    room = shapely.difference(inner, shapely.buffer(keep_out, SCORE_CLEAR))
    lines = shapely.line_merge(shapely.intersection(borders, room[owner]))
    out: list[list[NDArray[np.float64]]] = [[] for _ in strips]
    for k, line in zip(owner.tolist(), lines.tolist()):  # borders
        out[k] += [np.asarray(g.coords) for g in shapely.get_parts(line).tolist()
                   if g.geom_type == "LineString" and g.length > 1e-6]
    return out


def dot_centres(strip: Strip, tiles: tuple[int, ...], margin: float = ENGRAVE_MARGIN
                ) -> NDArray[np.float64]:
    """(n, 2) where the ring goes in each of ``tiles``: the centre of the largest circle in
    the tile, ``margin`` inside the strip (clear of the tile's borders where the tile leaves
    room, of the strip's edge where it does not)."""
    if not tiles:
        return np.zeros((0, 2))
    inner = shapely.buffer(strip.cut, -margin, join_style="mitre")
    mine = strip.tiles[list(tiles)]
    room = shapely.buffer(shapely.intersection(mine, inner), -DOT - 0.2, join_style="mitre")
    tight = shapely.is_empty(room)
    room[tight] = shapely.intersection(mine[tight], shapely.buffer(inner, -DOT, join_style="mitre"))
    room = room[~shapely.is_empty(room)]
    return inner_centres(room) if len(room) else np.zeros((0, 2))


def rings(centres: NDArray[np.float64], radius: float = DOT, n: int = 16
          ) -> list[NDArray[np.float64]]:
    """Closed ``n``-gon rings of ``radius`` round every centre (an engraved dot)."""
    a = np.linspace(0.0, 2 * np.pi, n + 1)
    circle = radius * np.column_stack([np.cos(a), np.sin(a)])
    return [c + circle for c in np.asarray(centres).reshape(-1, 2)]


def clear_arrows(strip: Strip, clear: float = SCORE_CLEAR) -> Strip:
    """``strip`` with each direction arrow shrunk about its centroid until it keeps ``clear``
    off its tile's borders (where the score lines go: an arrow over one would break it) and
    ``ENGRAVE_MARGIN`` inside the strip; an arrow that would shrink under half its printed
    size is left out."""
    arrows = strip.arrows
    if not len(arrows):
        return strip
    corners = np.array([np.asarray(a.exterior.coords)[:-1] for a in arrows.tolist()])
    centres = shapely.get_coordinates(shapely.centroid(arrows))
    tile = np.argmax(shapely.contains_xy(strip.tiles[:, None], centres[:, 0], centres[:, 1]),
                     axis=0)
    room = shapely.intersection(shapely.buffer(strip.tiles[tile], -clear, join_style="mitre"),
                                shapely.buffer(strip.cut, -ENGRAVE_MARGIN, join_style="mitre"))
    scale = largest_fit(room, corners - centres[:, None], centres, 0.5, 1.0)
    ok = np.isfinite(scale)
    shrunk = (corners - centres[:, None]) * scale[:, None, None] + centres[:, None]
    return replace(strip, arrows=shapely.polygons(shrunk[ok]))


def marks(strip: Strip, margin: float = ENGRAVE_MARGIN) -> list[NDArray[np.float64]]:
    """What is engraved besides the labels, ``margin`` inside the strip: the direction arrows'
    outlines, on a piece of a split strip the edge of its glue band, and the line where a label
    tab is cut off."""
    inner = shapely.buffer(strip.cut, -margin, join_style="mitre")
    out = [np.asarray(a.exterior.coords) for a in shapely.get_parts(strip.arrows).tolist()
           if a.geom_type == "Polygon" and inner.covers(a)]
    edges = [] if strip.glue is None else [shapely.union_all(strip.glue).boundary]
    if strip.flap_edge is not None:
        edges.append(strip.flap_edge)
    for edge in shapely.intersection(edges, inner).tolist():
        out += [np.asarray(g.coords) for g in shapely.get_parts(edge).tolist()
                if g.geom_type == "LineString" and g.length > 1e-6]
    return out


def colour_groups(pieces: list[Strip], colours) -> dict[str, list[Strip]]:
    """The pieces by their strand's colour, colours in order of first use."""
    groups: dict[str, list[Strip]] = {}
    for p in pieces:
        groups.setdefault(colours[p.strand], []).append(p)
    return groups


def pack_card(shapes, width: float, height: float, gap: float) -> list:
    """:func:`.packing.pack` for one card colour: first on a coarse grid with coarse turns
    (``QUICK``), which is enough where the strips fit one sheet (the fewest there is); else
    packed as tightly as the paper strips, and the better of the two kept (fewer sheets; the
    tight one on a tie)."""
    quick = pack(shapes, width, height, gap, **QUICK)
    if max(pl.page for pl in quick) == 0:
        return quick
    tight = pack(shapes, width, height, gap)
    return quick if max(pl.page for pl in quick) < max(pl.page for pl in tight) else tight


def card_sheets(pieces: list[Strip], colours, las: Laser, kerf: float,
                sheet: tuple[float, float], title: str = "weave-cut strands: card",
                margin: float = SHEET_MARGIN) -> CardCut:
    """Every piece on a sheet of card of its colour (``sheet`` mm, ``margin`` round it).

    Parameters
    ----------
    pieces : labelled strips (any frame)
    colours : strand colours ('#rrggbb'), indexed by ``Strip.strand``
    las : the laser's colour conventions
    kerf : mm, the beam's width; outlines are grown by half of it
    sheet : (width, height) mm
    """
    width, height = sheet
    gap = max(GAP, kerf)
    cut_style, engrave_style = las.style("cut"), las.style("engrave")
    score_style = las.style("score")
    drawings, sheet_colours, placed_all, texts_all, scores_all, dots_all = [], [], [], [], [], []
    report, smallest = cut_report([]), np.inf
    groups = colour_groups([clear_arrows(p) for p in pieces], colours)
    for colour, group in groups.items():  # card colours
        places = pack_card(nesting.offset(np.array([p.cut for p in group], dtype=object), kerf),
                           width - 2 * margin, height - 2 * margin, gap)
        moved = [p.moved(matmul(affine(0.0, (margin, margin)), pl.matrix()), pl.angle)
                 for p, pl in zip(group, places)]
        for s in range(max(pl.page for pl in places) + 1):  # this colour's sheets
            here = [m for m, pl in zip(moved, places) if pl.page == s]
            labels = engraved_labels(here)
            here = [replace(m, left_out=unnamed_tiles(m, e.dropped)) for m, e in zip(here, labels)]
            smallest = min([smallest] + [e.smallest for e in labels])
            dots = [dot_centres(m, m.left_out) for m in here]
            lines = [c[a:b] for c, o, *_ in labels for a, b in zip(o[:-1], o[1:])]
            lines += [r for m in here for r in marks(m)] + rings(np.concatenate(dots))
            scores = score_lines(here, labels)
            cuts = nesting.offset(np.array([m.cut for m in here], dtype=object), kerf)
            report = report + cut_report(cuts)
            n = len(drawings) + 1
            layers = (Layer("engrave", "engrave", (polylines_from_lines(lines, engrave_style),)),
                      Layer("score", "score", (polylines_from_lines(
                          [line for group in scores for line in group], score_style),)),
                      cut_layer(ordered_outlines(cuts, (0.0, height)), cut_style))
            drawings.append(Drawing((Sheet(width, height, layers, f"card {colour}, sheet {n}"),),
                                    f"{title}, sheet {n}: card {colour}",
                                    (("card", colour),)))
            sheet_colours.append(colour)
            placed_all.append(tuple(here))
            texts_all.append(tuple((e.coords, e.offsets, e.which) for e in labels))
            scores_all.append(tuple(line for group in scores for line in group))
            dots_all.append(np.concatenate(dots))
    covered = sum(p.cut.area for p in pieces)
    room = (width - 2 * margin) * (height - 2 * margin) * len(drawings)
    return CardCut(tuple(drawings), tuple(sheet_colours), tuple(placed_all), tuple(texts_all),
                   tuple(scores_all), tuple(dots_all), report, float(smallest),
                   covered / max(room, 1e-12))
