"""Paper strips laser-cut from coloured card: no printer needed.

Every strip is cut from card of its strand's colour: the strips are grouped by colour and packed
onto the material's sheets, one sheet set per colour. The cut layer holds each strip's outline
(grown by half the kerf, so the strip comes out true to size), cut after the engraving; the
engrave layer holds, in single strokes, what the printed strip shows: the strip's ID in its own
tile, the ID of the strand on top in every under tile (the under-crossing marks) and the
direction arrows' outlines, and the glue band's edge on a piece of a split strip. A label tab
(the ID of a strip too small to hold it) is cut with its strip, as on paper, its ID engraved on
it and the line where it is cut off after weaving engraved too. Every engraved line keeps
``ENGRAVE_MARGIN`` inside its strip.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from numpy.typing import NDArray

from ..numeric import affine, matmul
from ..layout import nesting, strokefont
from ..layout.drawing import (
    Drawing,
    Layer,
    Sheet,
    Style,
    Text,
    polygons_from_shapely,
    polylines_from_lines,
)
from ..layout.labels import MIN_CAP, text_boxes
from ..layout.lasersetup import Laser
from .packing import pack
from .pages import GAP
from .printcut import CutReport, cut_layer, cut_report, ordered_outlines
from .strips import Strip

ENGRAVE_MARGIN = 1.0  # mm between an engraved line and its strip's edge (card scorches there)
MIN_ENGRAVED = 1.5  # mm: a smaller label is left out
SHEET_MARGIN = 5.0  # mm of card round every sheet (where the laser bed's stops hold it)


@dataclass(frozen=True, eq=False)
class CardCut:
    """The card sheets and what the summary and the tests need.

    Parameters
    ----------
    sheets : one Drawing per sheet (engrave layer, then the cut layer)
    colours : (N,) the card colour of every sheet
    pieces : (N,) per sheet, the strips on it, moved to their places (true outlines)
    texts : (N,) per sheet, per strip, the engraved labels' strokes as (coords, offsets, the
        label of every polyline)
    report : cut length, outlines, duplicates, smallest feature over every sheet
    smallest_label : mm, the smallest engraved label
    """

    sheets: tuple[Drawing, ...]
    colours: tuple[str, ...]
    pieces: tuple[tuple[Strip, ...], ...]
    texts: tuple[tuple[tuple[NDArray, NDArray], ...], ...]
    report: CutReport
    smallest_label: float


def engraved_labels(strips: list[Strip], margin: float = ENGRAVE_MARGIN
                    ) -> list[tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.int64],
                                    float]]:
    """Per strip, single-stroke labels where the printed ones are, each as large as fits (up to
    the printed size) in its printed box (printed boxes do not overlap), ``margin`` inside the
    strip: (coords, offsets, the label of every polyline, smallest height). All strips' labels
    are fitted at once."""
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
            out.append((np.zeros((0, 2)), np.zeros(1, dtype=np.int64), np.zeros(0, dtype=np.int64),
                        np.inf))
            continue
        coords, offsets, which = strokefont.labels([flat[i].text for i in keep.tolist()],
                                                   centres[keep], heights[keep], angles[keep])
        out.append((coords, offsets, which, float(heights[keep].min()) if len(keep) else np.inf))
    return out


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
    drawings, sheet_colours, placed_all, texts_all = [], [], [], []
    report, smallest = cut_report([]), np.inf
    groups = colour_groups(pieces, colours)
    for colour, group in groups.items():  # card colours
        places = pack([nesting.offset(np.array([p.cut], dtype=object), kerf)[0]
                       for p in group], width - 2 * margin, height - 2 * margin, gap)
        moved = [p.moved(matmul(affine(0.0, (margin, margin)), pl.matrix()), pl.angle)
                 for p, pl in zip(group, places)]
        for s in range(max(pl.page for pl in places) + 1):  # this colour's sheets
            here = [m for m, pl in zip(moved, places) if pl.page == s]
            labels = engraved_labels(here)
            smallest = min([smallest] + [h for *_, h in labels])
            lines = [c[a:b] for c, o, *_ in labels for a, b in zip(o[:-1], o[1:])]
            lines += [r for m in here for r in marks(m)]
            cuts = nesting.offset(np.array([m.cut for m in here], dtype=object), kerf)
            report = report + cut_report(cuts)
            n = len(drawings) + 1
            layers = (Layer("engrave", "engrave", (polylines_from_lines(lines, engrave_style),)),
                      cut_layer(ordered_outlines(cuts, (0.0, height)), cut_style))
            drawings.append(Drawing((Sheet(width, height, layers, f"card {colour}, sheet {n}"),),
                                    f"{title}, sheet {n}: card {colour}",
                                    (("card", colour),)))
            sheet_colours.append(colour)
            placed_all.append(tuple(here))
            texts_all.append(tuple((c, o, w) for c, o, w, _ in labels))
    return CardCut(tuple(drawings), tuple(sheet_colours), tuple(placed_all), tuple(texts_all),
                   report, float(smallest))


def card_colour_sheet(cut: CardCut, size: tuple[float, float], title: str,
                      margin: float = 15.0) -> Sheet:
    """A page saying which card colour every strand is cut from, and on which sheets."""
    width, height = size
    shapes: list = [Text(margin, height - margin - 6.0, "Card colours: cut every strip from card "
                         "of its strand's colour", 5.0),
                    Text(margin, height - margin - 12.0, title, MIN_CAP)]
    y = height - margin - 24.0
    swatches, fills = [], []
    for colour in dict.fromkeys(cut.colours):  # card colours, in order
        numbers = [n + 1 for n, c in enumerate(cut.colours) if c == colour]
        labels = sorted({p.label.split(" ")[0] for n in numbers for p in cut.pieces[n - 1]},
                        key=lambda s: (s[0], len(s), s))
        swatches.append(shapely.box(margin, y - 1.0, margin + 14.0, y + 7.0))
        fills.append(colour)
        shapes.append(Text(margin + 18.0, y + 3.5, f"card {colour}: sheets "
                           f"{', '.join(map(str, numbers))}", 4.0))
        shapes.append(Text(margin + 18.0, y - 1.0, "strands " + _listed(labels), MIN_CAP))
        y -= 14.0
    shapes.insert(0, polygons_from_shapely(swatches, Style("#333333", 0.2), fills))
    return Sheet(width, height, (Layer("card colours", "label", tuple(shapes)),), "card colours")


def _listed(labels: list[str], most: int = 24) -> str:
    more = f" and {len(labels) - most} more" if len(labels) > most else ""
    return ", ".join(labels[:most]) + more

