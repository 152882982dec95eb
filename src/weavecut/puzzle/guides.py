"""Painting guides a maker paints from: 1:1 sheets registered to the cut, printer pages, and a
colour key per side.

A guide shows every piece in its paint with a bold outline (the cut), the front's split lines
thin and dashed (the parent edge a Z-triplet replaced: "split diagonally, which shows the
replaced edge", paper section 6; the back has none), a ring piece's bare hexagon split off its
paint by the same thin dashes (it is part of the piece, not one of its own), and every piece's
number inside it, placed where it reads (``guide_numbers``). The back is mirrored, as the flipped board
shows it. Printed on pages, only pages that hold paint are kept; the colour key lists every
paint with its swatch, name, hex code, the pieces that carry it and the area it covers.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
import shapely
from numpy.typing import NDArray

from ..layout.label_checks import PAPER, WORDS
from ..layout.drawing import (Drawing, Layer, Polylines, Sheet, Style, Text,
                              polygons_from_rings, polygons_from_shapely)
from ..layout.labels import text_width, wrap
from ..layout.tiling import balanced, tile, word_overlap
from ..numeric import distinct
from .colouring import UNPAINTED, Colouring
from .files import Labels, placement
from .pieces import Puzzle

OUTLINE = Style("#000000", 0.5)
SPLIT = Style("#000000", 0.2)
THIN = Style("#555555", 0.25)
DASH, GAP = 1.5, 1.2  # mm, the split lines' dashes
CAPTION, CAPTION_SIZE = (12.0, 8.0), 6.0  # mm: a preview half's caption: its start from the
# sheet's top left corner (past the crosshair, above the frame: the margin is 10 mm), cap height
NUMBER_STROKE = 0.3  # mm, the numbers' strokes: bolder than the split lines, lighter than outlines


@lru_cache(maxsize=2)
def piece_halves(puzzle: Puzzle) -> NDArray[np.object_]:
    """(P, 2) the two painted halves of every piece, in the order of its tile's faces (kept,
    read-only, for the last two puzzles: the front's paint and its numbers ask for them).

    An octagon is split along the straight line between its two corners that are level-(t-1)
    vertices: the parent edge its Z-triplet replaced, so the paint shows the coarser weave
    ("split diagonally, which shows the replaced edge", paper section 6); where that line
    leaves the piece, along its two pentagons. An enneagon is one half: its pentagon, twice
    (its hexagon is unpainted)."""
    vertices, faces, f0, f1 = _piece_faces(puzzle)
    p0 = shapely.polygons(puzzle.to_mm(vertices[faces[f0]]))
    p1 = shapely.polygons(puzzle.to_mm(vertices[faces[f1]]))
    octagon = f0 != f1
    u, w = split_ends(puzzle)
    cut0, cut1 = _cut_along(shapely.union(p0[octagon], p1[octagon]), u[octagon], w[octagon])
    # the half on f0's side of the line u-w first
    d = (w - u)[octagon]

    def side(polygons):
        a = shapely.get_coordinates(shapely.centroid(polygons)) - u[octagon]
        return np.sign(a[:, 0] * d[:, 1] - a[:, 1] * d[:, 0])

    swap = side(cut0) != side(p0[octagon])
    # where the chord leaves the piece (an octagon bent hard at a sharp tip), its two
    # pentagons are its halves
    inside = shapely.is_valid(cut0) & shapely.is_valid(cut1)
    half0, half1 = p0.copy(), p1.copy()
    half0[octagon] = np.where(inside, np.where(swap, cut1, cut0), half0[octagon])
    half1[octagon] = np.where(inside, np.where(swap, cut0, cut1), half1[octagon])
    # a cut through a corner leaves near-duplicate corners (1e-13 mm apart) that turn into a
    # self-intersection once moved onto a sheet: drop them
    out = shapely.simplify(np.column_stack([half0, half1]), 1e-7)
    out.flags.writeable = False
    return out


@lru_cache(maxsize=2)
def bare_pieces(puzzle: Puzzle) -> NDArray[np.object_]:
    """(P,) every piece less its ring hexagon, if it has one (kept, read-only, for the last two
    puzzles: the back's paint and both sides' numbers ask for them)."""
    hexes = puzzle.hexagons
    has = hexes != None  # noqa: E711
    out = puzzle.pieces.copy()
    out[has] = shapely.difference(out[has], hexes[has].astype(object))
    out.flags.writeable = False
    return out


def _cut_along(polygons, u, w):
    """(N,) polygons cut along the chord between their corners ``u`` and ``w`` ((N, 2) each):
    the corners from u to w and those from w to u, counter-clockwise, as two polygons (exact:
    they share the chord and tile the polygon, even where it is not convex)."""
    rings = shapely.get_exterior_ring(shapely.orient_polygons(polygons))
    xy, index = shapely.get_coordinates(rings, return_index=True)
    counts = np.bincount(index, minlength=len(polygons))
    start = np.cumsum(counts) - counts
    keep = np.arange(len(xy)) != (start + counts - 1)[index]  # the closing repeat
    xy, index = xy[keep], index[keep]
    n = (counts - 1)[index]
    first = np.cumsum(counts - 1) - (counts - 1)
    k = np.arange(len(xy)) - first[index]  # corner number in its ring

    def corner(p):  # the corner nearest to p, per polygon
        order = np.lexsort((np.hypot(*(xy - p[index]).T), index))
        return k[order[first]]

    iu, iw = corner(u)[index], corner(w)[index]
    out = []
    for a, b in ((iu, iw), (iw, iu)):
        step = (k - a) % n
        part = step <= (b - a) % n
        order = np.lexsort((step[part], index[part]))
        out.append(shapely.polygons(shapely.linearrings(xy[part][order],
                                                        indices=index[part][order])))
    return out


def split_ends(puzzle: Puzzle) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(P, 2) twice: the two corners of every piece that are level t-1 vertices (mm), the ends
    of the parent edge its Z-triplet replaced (for an enneagon both lie in its one pentagon)."""
    vertices, faces, f0, f1 = _piece_faces(puzzle)
    n_parent = puzzle.hierarchy[-2].mesh.n_vertices
    rows = np.arange(len(f0))
    old0 = faces[f0][rows, np.argmin(np.where(faces[f0] < n_parent, 0, 1), axis=1)]
    old1 = faces[f1][rows, np.argmin(np.where(faces[f1] < n_parent, 0, 1), axis=1)]
    return puzzle.to_mm(vertices[old0]), puzzle.to_mm(vertices[old1])


def _piece_faces(puzzle: Puzzle):
    """The level t vertices and (F, 5) faces, and every piece's first and last face."""
    weave = puzzle.weaves[-1]
    tiles = puzzle.piece_tiles
    return (weave.mesh.vertices, weave.mesh.dense_faces(),
            weave.tile_faces[weave.tile_offsets[tiles]],
            weave.tile_faces[weave.tile_offsets[tiles + 1] - 1])


@dataclass(frozen=True, eq=False)
class Painted:
    """What one side paints: polygons, their colours and the piece each belongs to."""

    polygons: NDArray[np.object_]
    colours: NDArray[np.object_]
    piece: NDArray[np.int64]

    def areas(self) -> dict[str, float]:
        """Painted area (mm^2) per colour."""
        area = shapely.area(self.polygons)
        return {c: float(area[self.colours == c].sum()) for c in dict.fromkeys(self.colours)}

    def pieces(self, colour: str) -> NDArray[np.int64]:
        """Piece numbers (1-based) that carry ``colour``, ascending."""
        return distinct(self.piece[self.colours == colour]) + 1


@lru_cache(maxsize=2)
def painted(puzzle: Puzzle, colouring: Colouring, side: str) -> Painted:
    """Every painted area of one side (ring hexagons stay unpainted); kept for the last
    puzzle's two sides, which its guide and its colour key both paint (a puzzle and a
    colouring are the same while they are the same objects: both are frozen)."""
    if side == "front":
        halves = piece_halves(puzzle)
        # an enneagon's 'halves' are its one pentagon twice: paint it once
        one = shapely.equals(halves[:, 0], halves[:, 1])
        pick = np.column_stack([np.ones(len(one), dtype=bool), ~one]).ravel()
        polys, colours = halves.ravel()[pick], colouring.front.ravel()[pick]
        piece = np.repeat(np.arange(puzzle.n_pieces), 2)[pick]
    else:
        polys = bare_pieces(puzzle)
        colours, piece = colouring.back, np.arange(puzzle.n_pieces)
    keep = colours != UNPAINTED
    out = (polys[keep], colours[keep].astype(object), piece[keep].astype(np.int64))
    for a in out:  # shared by every caller
        a.flags.writeable = False
    return Painted(*out)


def guide(puzzle: Puzzle, colouring: Colouring, side: str, numbers=None,
          margin: float = 10.0) -> Drawing:
    """The front (level t-1 weave, two halves per piece) or back (level t weave, mirrored)
    painting guide at 1:1, registered to the shared cut sheet; with ``numbers`` (a
    ``guide_numbers.GuideNumbers`` of this side) every piece's number on a layer of its own,
    one word per numbered piece in piece order."""
    width, height, shift = placement(puzzle, margin)
    mirror = side == "back"

    def place_xy(xy):
        xy = xy + shift
        return np.column_stack([width - xy[:, 0], xy[:, 1]]) if mirror else xy

    def place(geoms):
        return shapely.transform(geoms, place_xy)

    paint = painted(puzzle, colouring, side)
    layers = [Layer("paint", "paint", (polygons_from_shapely(
        place(paint.polygons), Style(None, 0.0), paint.colours.tolist()),))]
    hexes = puzzle.hexagons[puzzle.hexagons != None]  # noqa: E711
    if len(hexes):  # the ring stays natural wood on both sides
        layers.append(Layer("ring-unpainted", "paint", (polygons_from_shapely(
            place(hexes), Style(None, 0.0, UNPAINTED)),)))
    if side == "front":
        layers.append(Layer("split-lines", "guide", (_split_lines(puzzle, colouring,
                                                                  place_xy),)))
    if len(hexes):  # a ring piece's bare hexagon is part of it: split off thin, not cut bold
        layers.append(Layer("hexagon-lines", "guide", (_dashes(
            *map(place_xy, hexagon_edges(puzzle)), SPLIT),)))
    outlines = [polygons_from_shapely(place(np.array([puzzle.frame], dtype=object)), OUTLINE)]
    if len(puzzle.ring):
        outlines.append(polygons_from_shapely(place(puzzle.ring), THIN))
    layers.append(Layer("frame", "guide", tuple(outlines)))
    layers.append(Layer("pieces", "guide", (polygons_from_shapely(place(puzzle.pieces),
                                                                  OUTLINE),)))
    if numbers is not None:  # moved with the pieces, but never mirrored: they must read
        labels = numbers.labels
        placed = Labels(labels.texts, labels.heights, place_xy(labels.centres),
                        -labels.angles if mirror else labels.angles)
        layers.append(Layer(WORDS, "label", _number_shapes(placed, numbers.inks,
                                                           place(numbers.plates))))
    layers.append(Layer("registration", "guide", tuple(_registration(width, height, margin))))
    title = f"weave-cut puzzle: {side} painting guide (level {puzzle.levels - (side == 'front')}" \
            " weave)" + (", mirrored" if mirror else "")
    paints = len(set(paint.colours.tolist()) - {UNPAINTED})  # the bare wood is no paint
    return Drawing((Sheet(width, height, tuple(layers), f"{side} guide"),), title,
                   (("paints", str(paints)),))


def preview(puzzle: Puzzle, colouring: Colouring) -> Drawing:
    """A quick look at the painted puzzle: the front and the back guide without numbers, one
    sheet each (``weave-cut puzzle --preview``; the web app's live preview)."""
    sheets = []
    for side, what in (("front", f"level {puzzle.levels - 1} weave"),
                       ("back", f"level {puzzle.levels} weave, mirrored as the turned board")):
        sheet = guide(puzzle, colouring, side).sheets[0]
        caption = Text(CAPTION[0], sheet.height - CAPTION[1], f"{side} ({what})",
                       CAPTION_SIZE)  # in the margin above the frame, which half is which
        sheets.append(replace(sheet, layers=sheet.layers + (Layer("caption", "label",
                                                                   (caption,)),)))
    return Drawing(tuple(sheets), f"weave-cut puzzle: preview, level {puzzle.levels}")


def _split_lines(puzzle: Puzzle, colouring: Colouring, place_xy) -> Polylines:
    """Dashed parent edges across the two-coloured pieces (the paint's diagonal)."""
    u, w = split_ends(puzzle)
    two = colouring.front[:, 0] != colouring.front[:, 1]
    return _dashes(place_xy(u[two]), place_xy(w[two]), SPLIT)


def hexagon_edges(puzzle: Puzzle) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(E, 2) twice: the ends of every ring hexagon's edge that lies inside its piece (the
    edge it shares with the piece's pentagon), in piece order."""
    has = np.flatnonzero(puzzle.hexagons != None)  # noqa: E711
    if not len(has):
        return np.zeros((0, 2)), np.zeros((0, 2))
    rings = shapely.get_exterior_ring(puzzle.hexagons[has].astype(object))
    xy, k = shapely.get_coordinates(rings, return_index=True)
    last = np.r_[k[1:] != k[:-1], True]  # each ring's closing repeat ends no edge
    a, b, k = xy[:-1][~last[:-1]], xy[1:][~last[:-1]], k[:-1][~last[:-1]]
    middle = shapely.points((a + b) / 2)
    outline = shapely.get_exterior_ring(puzzle.pieces[has[k]].astype(object))
    inside = shapely.distance(middle, outline) > 1e-6
    return a[inside], b[inside]


def _dashes(a: NDArray[np.float64], b: NDArray[np.float64], style: Style) -> Polylines:
    """Every segment a -> b as dashes of DASH mm with GAP mm between (vectorised)."""
    length = np.hypot(*(b - a).T)
    n = np.maximum(np.floor((length + GAP) / (DASH + GAP)), 1).astype(np.int64)
    seg = np.repeat(np.arange(len(a)), n)
    k = np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)
    spare = (length - (n * DASH + (n - 1) * GAP)) / 2  # centre the dashes on the segment
    start = spare[seg] + k * (DASH + GAP)
    end = np.minimum(start + DASH, length[seg])
    d = (b - a)[seg] / np.maximum(length[seg], 1e-12)[:, None]
    coords = np.stack([a[seg] + d * start[:, None], a[seg] + d * end[:, None]], axis=1)
    return Polylines(coords.reshape(-1, 2), np.arange(0, 2 * len(seg) + 1, 2, dtype=np.int64),
                     style)


def _number_shapes(numbers: Labels, inks: NDArray[np.object_], plates) -> tuple:
    """One Polylines per number, in piece order (a word: its digits together), each after its
    white plate where it has one; none for a piece too small for any (height 0)."""
    shapes = []
    some = np.flatnonzero(numbers.heights > 0)
    for k, (coords, offsets) in zip(some.tolist(), numbers.strokes_each(some)):
        if plates[k] is not None:
            shapes.append(polygons_from_shapely([plates[k]], Style(None, 0.0, PAPER)))
        shapes.append(Polylines(coords, offsets, Style(inks[k], NUMBER_STROKE)))
    return tuple(shapes)


def _registration(width: float, height: float, margin: float) -> list:
    """Crosshairs in the four corners (symmetric, so front and back register)."""
    r = margin * 0.4
    pts = [(margin / 2, margin / 2), (width - margin / 2, margin / 2),
           (margin / 2, height - margin / 2), (width - margin / 2, height - margin / 2)]
    segs = np.array([[(x - r, y), (x + r, y), (x, y - r), (x, y + r)] for x, y in pts])
    coords = segs.reshape(-1, 2)
    return [Polylines(coords, np.arange(0, len(coords) + 1, 2, dtype=np.int64),
                      Style("#000000", 0.2))]


# --- printed pages ----------------------------------------------------------------------------

def printed(guide_drawing: Drawing, key: Drawing, page: tuple[float, float]) -> Drawing:
    """The colour key, then the guide tiled on ``page``s (or the same turned), keeping only
    pages with paint, on the page and grid that need the fewest and leave the emptiest page
    the most paint (``tiling.balanced``); the pages overlap by more than the widest
    number, which each shows whole or not at all. The 1:1 sheet's crosshairs are left off:
    the pages register on the frame's outline and on each other."""
    sheet = guide_drawing.sheets[0]
    sheet = replace(sheet, layers=tuple(layer for layer in sheet.layers
                                        if layer.name != "registration"))
    bare = replace(guide_drawing, sheets=(sheet,))
    overlap = word_overlap(bare)
    best, shift = balanced(sheet, (page, page[::-1]), overlap, 10.0)
    tiled = tile(bare, best, overlap, keep=_has_paint, before=len(key.sheets), shift=shift)
    return replace(tiled, sheets=key.sheets + tiled.sheets)


def _has_paint(sheet: Sheet) -> bool:
    return any(layer.role == "paint" and layer.shapes for layer in sheet.layers)


def colour_key(puzzle: Puzzle, colouring: Colouring, side: str,
               page: tuple[float, float] = (210.0, 297.0), margin: float = 15.0) -> Drawing:
    """Every paint of one side: swatch, name, hex code, pieces and area (cm²), then the bare
    wood of the ring pieces' hexagons (white on the guide), on as many ``page``s as it
    takes."""
    paint = painted(puzzle, colouring, side)
    areas = paint.areas()
    order = [c for c in colouring.names if c in areas] + sorted(set(areas) - set(
        colouring.names))
    size, line = 3.0, 4.6  # lines' boxes (cap height, descenders) 0.5 mm apart
    room = page[0] - 2 * margin - 30  # right of the swatches
    rows = []
    for colour in order:
        numbers = " ".join(str(k) for k in paint.pieces(colour).tolist())
        wrapped = wrap(f"pieces: {numbers}", room, size)
        rows.append((colour, wrapped))
    ring = np.flatnonzero(puzzle.hexagons != None)  # noqa: E711
    if len(ring):  # what the guide shows white: the ring pieces' hexagons, bare wood
        bare = float(shapely.area(puzzle.hexagons[ring].astype(object)).sum())
        rows.append((None, wrap("the hexagon of pieces: " + " ".join(
            str(k + 1) for k in ring.tolist()), room, size)))
    most = max(1, int((page[1] - 2 * margin - 14 - 3) // line) - 1)  # lines a page holds
    rows = [(colour, wrapped[k:k + most], max(14.0, line * (len(wrapped[k:k + most]) + 1) + 3))
            for colour, wrapped in rows for k in range(0, len(wrapped), most)]
    total = sum(areas.values())
    sheets, shapes, y = [], [], None
    heading = (f"Colour key, {side}: {len(order)} paints, {total / 100:.0f} cm² painted "
               f"({'level ' + str(puzzle.levels - (side == 'front')) + ' weave'})")
    for colour, wrapped, height in rows:
        if y is None or y - height < margin:
            if shapes:
                sheets.append(shapes)
            y = page[1] - margin
            shapes = [Text(margin, y - 6, heading,
                           min(5.0, 5.0 * (page[0] - 2 * margin) / text_width(heading, 5.0)))]
            y -= 14
        swatch = np.array([(margin, y - 12), (margin + 25, y - 12), (margin + 25, y),
                           (margin, y)])
        shapes.append(polygons_from_rings([swatch], Style("#000000", 0.3),
                                          [colour or UNPAINTED]))
        x = margin + 30
        title = (f"{colouring.names.get(colour, colour)}   {colour}   "
                 f"{areas[colour] / 100:.1f} cm²" if colour else
                 f"bare wood, not painted (white on the guide)   {bare / 100:.1f} cm²")
        shapes.append(Text(x, y - 4, title, 3.5))
        for k, text in enumerate(wrapped):
            shapes.append(Text(x, y - 4 - line * (k + 1), text, size, fill="#333333"))
        y -= height
    if shapes:
        sheets.append(shapes)
    out = [Sheet(page[0], page[1], (Layer("key", "label", tuple(s)),),
                 f"{side} colour key {k + 1}") for k, s in enumerate(sheets)]
    return Drawing(tuple(out), f"weave-cut puzzle: {side} colour key")

