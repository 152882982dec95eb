"""The puzzle as Drawings: cut files (shared or separate), painting guides, the summary.

Coordinates: the shared cut sheet and both guides use one frame of reference, the frame's
bounding box moved to ``margin`` mm from the sheet's bottom-left corner, so a guide printed at
1:1 lies exactly on the cut sheet (the back guide mirrored left-right about the sheet's centre,
as the flipped board shows it).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import shapely
from numpy.typing import NDArray

from ..layout import cutpaths, nesting
from ..layout import strokefont
from ..layout.lasersetup import Laser
from ..layout.drawing import Drawing, Layer, Polygons, Polylines, Sheet, Style
from ..errors import WeaveCutError
from ..numeric import offsets_of, turn
from .pieces import Puzzle

TRAVEL_SPEED = 300.0  # mm/s head moves between cuts, for the time estimate
MIN_DIGITS = 3.0  # mm, the smallest engraved digits that read well
MIN_ENGRAVED = 1.5  # mm, smaller numbers are not engraved at all


@dataclass(frozen=True)
class CutResult:
    """A cut Drawing plus what the summary needs (lengths in mm)."""

    drawing: Drawing
    cut_length: float
    travel_length: float
    n_paths: int
    n_sheets: int


def _lines(paths: list[NDArray], style: Style) -> Polylines:
    coords = np.concatenate(paths) if paths else np.zeros((0, 2))
    offsets = offsets_of([len(p) for p in paths])
    return Polylines(coords, offsets, style)


def placement(puzzle: Puzzle, margin: float = 10.0) -> tuple[float, float, NDArray]:
    """Sheet width, height and the shift that puts the frame ``margin`` mm from the corner."""
    x0, y0, x1, y1 = puzzle.outer.bounds
    return x1 - x0 + 2 * margin, y1 - y0 + 2 * margin, np.array([margin - x0, margin - y0])


@dataclass(frozen=True, eq=False)
class Labels:
    """Texts as single strokes, each fitted inside its part (mm, in the parts' coordinates).

    Parameters
    ----------
    texts : one per part
    heights : (N,) cap heights, the largest that fit up to a maximum
    centres : (N, 2) where each text's ink box is centred
    angles : (N,) degrees counter-clockwise
    """

    texts: tuple[str, ...]
    heights: NDArray[np.float64]
    centres: NDArray[np.float64]
    angles: NDArray[np.float64]

    @classmethod
    def fitted(cls, parts: NDArray[np.object_], texts: list[str], max_height: float,
               margin: float) -> Labels:
        return cls(tuple(texts), *strokefont.fit_labels(parts, texts, margin, max_height))

    def strokes(self, transform=None, pick=None) -> tuple[NDArray, NDArray]:
        """Polylines (coords, offsets) of the texts (``pick``: the parts wanted), moved by
        ``transform(coords, part_of_every_point)``."""
        pick = np.arange(len(self.texts)) if pick is None else np.asarray(pick)
        pick = pick[self.heights[pick] > 0]  # a text too small to engrave is left out
        coords, offsets, owner = strokefont.labels([self.texts[k] for k in pick.tolist()],
                                                   self.centres[pick], self.heights[pick],
                                                   self.angles[pick])
        if transform is not None and len(coords):
            coords = transform(coords, pick[np.repeat(owner, np.diff(offsets))])
        return coords, offsets

    def strokes_each(self, pick) -> list[tuple[NDArray, NDArray]]:
        """:meth:`strokes` of each text of ``pick`` (all of height > 0) on its own, all made in
        one go."""
        pick = np.asarray(pick, dtype=np.int64)
        coords, offsets, owner = strokefont.labels([self.texts[k] for k in pick.tolist()],
                                                   self.centres[pick], self.heights[pick],
                                                   self.angles[pick])
        first = np.searchsorted(owner, np.arange(len(pick) + 1))  # each text's first line
        return [(coords[offsets[a]:offsets[b]], offsets[a:b + 1] - offsets[a])
                for a, b in zip(first[:-1].tolist(), first[1:].tolist())]


TURNED = {"0": "0", "1": "1", "6": "9", "8": "8", "9": "6"}  # digits that read as digits
# turned half a turn (in the stroke font a 2 or a 5 does not)


def turned_over(number: str) -> str | None:
    """What ``number`` reads as turned half a turn (its digits reversed, 6 and 9 swapped), or
    None where that is no number (a digit without a turned reading, a leading 0)."""
    if not number or not set(number) <= TURNED.keys():
        return None
    turned = "".join(TURNED[c] for c in reversed(number))
    return None if turned.startswith("0") else turned


def piece_texts(n: int) -> list[str]:
    """The numbers 1..n as printed and engraved: one that reads as another number upside down
    (6/9, 16/91, 86/98, ...) underlined, as on bingo balls, so it shows which way is up."""
    out = []
    for k in range(1, n + 1):
        text, turned = str(k), turned_over(str(k))
        out.append(text + strokefont.UNDERLINE if turned not in (None, text) else text)
    return out


def piece_numbers(puzzle: Puzzle, max_height: float = 4.0, margin: float = 0.6,
                  least: float = MIN_ENGRAVED) -> Labels:
    """Every piece's number (1..P, :func:`piece_texts`) at the largest cap height up to
    ``max_height`` mm that keeps its strokes ``margin`` mm inside the piece; none where that is
    under ``least`` mm."""
    labels = Labels.fitted(puzzle.pieces, piece_texts(puzzle.n_pieces), max_height, margin)
    return replace(labels, heights=np.where(labels.heights >= least, labels.heights, 0.0))


def number_warnings(numbers: Labels, least: float = MIN_DIGITS) -> list[str]:
    """Lines naming the pieces too small for ``least`` mm digits and those left without."""
    small = np.flatnonzero((numbers.heights < least) & (numbers.heights > 0))
    none = np.flatnonzero(numbers.heights == 0)
    out = []
    if len(small):
        out.append(f"pieces {_listed(small)} are too small for {least:g} mm digits; their "
                   f"numbers are engraved smaller (down to {numbers.heights[small].min():.1f} "
                   "mm)")
    if len(none):
        out.append(f"pieces {_listed(none)} are too small for {MIN_ENGRAVED:g} mm digits and "
                   "get no number")
    return out


def _listed(pieces: NDArray[np.int64], most: int = 12) -> str:
    more = f" and {len(pieces) - most} more" if len(pieces) > most else ""
    return ", ".join(str(k + 1) for k in pieces[:most].tolist()) + more


def _outlines(polygons: NDArray[np.object_]) -> list[NDArray[np.float64]]:
    """Every polygon's exterior ring (k, 2), all read in one call."""
    if not len(polygons):
        return []
    coords, of = shapely.get_coordinates(shapely.get_exterior_ring(polygons), return_index=True)
    return np.split(coords, np.cumsum(np.bincount(of, minlength=len(polygons)))[:-1])


def _number_layer(coords, offsets, style: Style) -> Layer:
    return Layer("engrave-numbers", "engrave", (Polylines(coords, offsets, style),))


def ring_score_lines(puzzle: Puzzle) -> list[NDArray]:
    """Edges of the unclaimed ring hexagons that are not on the frame's hole (score lines)."""
    if not len(puzzle.ring):
        return []
    free = shapely.difference(shapely.union_all(shapely.get_exterior_ring(puzzle.ring)),
                              shapely.buffer(puzzle.hole.exterior, 1e-6))
    free = shapely.line_merge(free)
    parts = shapely.get_parts(free)
    return [np.asarray(p.coords) for p in parts if p.length > 1e-6]


def shared_cut(puzzle: Puzzle, las: Laser, numbers: Labels | None = None,
               score_ring: bool = True, margin: float = 10.0) -> CutResult:
    """One sheet, every shared edge cut once: inner trails, then the hole outline, then the
    frame's outer outline, in an order that shortens head travel (home: top-left)."""
    width, height, shift = placement(puzzle, margin)
    rings = shapely.get_exterior_ring(shapely.transform(puzzle.pieces, lambda xy: xy + shift))
    n = shapely.get_num_coordinates(rings) - 1
    coords = shapely.get_coordinates(rings)
    keep = np.ones(len(coords), dtype=bool)
    keep[np.cumsum(n + 1) - 1] = False
    graph = cutpaths.shared_edges(coords[keep], offsets_of(n))
    home = (0.0, height)
    inner, here = cutpaths.order_paths(cutpaths.trails(graph, graph.uses > 1), home)
    hole, here = cutpaths.order_paths(cutpaths.trails(graph, graph.uses == 1), here)
    outer_ring = np.asarray(puzzle.outer.exterior.coords) + shift
    outer, _ = cutpaths.order_paths([outer_ring], here)
    paths = inner + hole + outer
    cut = las.style("cut")
    layers = [Layer("cut-1-inner", "cut", (_lines(inner, cut),)),
              Layer("cut-2-hole", "cut", (_lines(hole, cut),)),
              Layer("cut-3-outer", "cut", (_lines(outer, cut),))]
    layers += _extras(puzzle, las, shift, numbers, score_ring)
    meta = (("mode", "shared"),)
    drawing = Drawing((Sheet(width, height, tuple(layers), "puzzle shared cut"),),
                      "weave-cut puzzle: shared-edge cut", meta)
    return CutResult(drawing, cutpaths.path_length(paths),
                     cutpaths.travel_length(paths, home), len(paths), 1)


def _extras(puzzle: Puzzle, las: Laser, shift, numbers: Labels | None,
            score_ring: bool) -> list[Layer]:
    layers = []
    if score_ring:
        lines = [p + shift for p in ring_score_lines(puzzle)]
        if lines:
            layers.append(Layer("score-ring", "score", (_lines(lines, las.style("score")),)))
    if numbers is not None:
        coords, offsets = numbers.strokes(lambda xy, _: xy + shift)
        layers.append(_number_layer(coords, offsets, las.style("engrave")))
    return layers


def check_kerf(puzzle: Puzzle, kerf: float) -> None:
    """Refuse a kerf that would eat the smallest piece: it must stay below the piece's inner
    radius (2 area / perimeter, exact for polygons with an incircle)."""
    inner = 2 * shapely.area(puzzle.pieces) / shapely.length(puzzle.pieces)
    k = int(np.argmin(inner))
    if kerf >= inner[k]:
        raise WeaveCutError(f"a kerf of {kerf:g} mm is wider than piece {k + 1} "
                            f"({inner[k]:.3g} mm inner radius); use a smaller --kerf or a "
                            "larger --size")


def separate_cut(puzzle: Puzzle, las: Laser, kerf: float, sheet: tuple[float, float],
                 spacing: float = 2.0, numbers: Labels | None = None, margin: float = 5.0,
                 frame_parts: NDArray[np.object_] | None = None) -> CutResult:
    """Every piece a closed outline offset by kerf/2, the frame (its ``frame_parts`` when split,
    hole shrunk by kerf/2) first, all nested onto ``sheet``-sized sheets, pieces inside the
    frame's hole too (``nesting.nest``); per sheet: the pieces, then the frame's hole, then the
    frame's outer outlines last. Frame parts carry engraved labels
    (F1, F2, ...)."""
    spacing = max(spacing, kerf)
    frames = np.array([puzzle.frame], dtype=object) if frame_parts is None else frame_parts
    n_frame = len(frames)
    labels = frame_labels(frames)
    parts = np.concatenate([nesting.offset(frames, kerf), nesting.offset(puzzle.pieces, kerf)])
    names = ([f"frame part {t}" for t in labels] if n_frame > 1 else ["the frame"]) + [
        f"piece {k + 1}" for k in range(puzzle.n_pieces)]
    rooms = np.arange(len(parts)) < n_frame  # the frame's hole and bays take pieces
    placed_at = nesting.nest(parts, sheet, spacing, margin, names=names, rooms=rooms)
    placed = placed_at.apply(parts)
    cut, eng = las.style("cut"), las.style("engrave")
    sheets, total, travel, n_paths = [], 0.0, 0.0, 0

    def move(coords, owner):  # owner: part index; rotate about the origin, then shift
        return turn(coords, placed_at.angle[owner], placed_at.shift[owner])

    frame_text = _frame_text(frames, labels)
    for s in range(placed_at.n_sheets):
        on = np.flatnonzero(placed_at.sheet == s)
        home = (0.0, sheet[1])
        frame_here = on[on < n_frame]
        inner_rings = [np.asarray(r.coords) for k in frame_here for r in placed[k].interiors]
        piece_rings = _outlines(placed[on[on >= n_frame]])
        # the pieces first (those in the frame's hole before the hole frees its slug), then
        # the hole, then the frame's outer outline
        pieces, here = cutpaths.order_paths(piece_rings, home)
        holes, here = cutpaths.order_paths(inner_rings, here)
        outer, _ = cutpaths.order_paths([np.asarray(placed[k].exterior.coords)
                                         for k in frame_here], here)
        inner = pieces + holes
        paths = inner + outer
        total += cutpaths.path_length(paths)
        travel += cutpaths.travel_length(paths, home)
        n_paths += len(paths)
        layers = [Layer("cut-1-inner", "cut", (_closed(inner, cut),))]
        if outer:
            layers.append(Layer("cut-2-outer", "cut", (_closed(outer, cut),)))
        engrave = []
        if numbers is not None and (on >= n_frame).any():
            engrave.append(numbers.strokes(lambda xy, part: move(xy, part + n_frame),
                                           on[on >= n_frame] - n_frame))
        if frame_text is not None and len(frame_here):
            engrave.append(frame_text.strokes(move, frame_here))
        if engrave:
            coords = np.concatenate([c for c, _ in engrave])
            counts = np.concatenate([np.diff(o) for _, o in engrave])
            layers.append(_number_layer(coords, offsets_of(counts), eng))
        sheets.append(Sheet(sheet[0], sheet[1], tuple(layers), f"sheet {s + 1}"))
    drawing = Drawing(tuple(sheets), "weave-cut puzzle: separate pieces",
                      (("mode", "separate"), ("kerf", f"{kerf:g} mm")))
    return CutResult(drawing, total, travel, n_paths, placed_at.n_sheets)


def frame_labels(frames: NDArray[np.object_]) -> list[str]:
    """F1, F2, ... for the parts of a split frame; nothing for a frame in one piece."""
    return [f"F{k + 1}" for k in range(len(frames))] if len(frames) > 1 else [""]


def _frame_text(frames: NDArray[np.object_], labels: list[str]) -> Labels | None:
    """The frame parts' labels, fitted inside each part (None for an unsplit frame)."""
    return Labels.fitted(frames, labels, 8.0, 1.0) if len(frames) > 1 else None


def _closed(paths: list[NDArray], style: Style) -> Polygons:
    """Closed rings (drop the repeated last point) in cutting order."""
    rings = [p[:-1] if closed else p for p, closed in zip(paths, cutpaths.are_closed(paths, 2))]
    coords = np.concatenate(rings) if rings else np.zeros((0, 2))
    offsets = offsets_of([len(r) for r in rings])
    return Polygons(coords, offsets, style)


def nested_parts(result: CutResult) -> list[NDArray[np.object_]]:
    """The cut rings of every sheet as shapely polygons (for checks)."""
    out = []
    for sheet in result.drawing.sheets:
        rings = [r for layer in sheet.layers if layer.role == "cut" for shape in layer.shapes
                 for r in shape.rings()]
        out.append(np.array([shapely.Polygon(r) for r in rings], dtype=object))
    return out


def split_sheets(drawing: Drawing) -> list[Drawing]:
    """One Drawing per sheet."""
    return [Drawing((s,), f"{drawing.title}, {s.name}", drawing.metadata) for s in drawing.sheets]
