"""A ball's strands in printable pieces: every strand's unfolding (:mod:`.unfold`) cut into
runs of whole tiles that fit the page, consecutive pieces sharing a tile (the glue band of one
goes under the first tile of the next), each laid flat with its folds; and, when two tiles
(the shortest piece) do not fit the page, the largest ball that does."""

from __future__ import annotations

import math

import numpy as np
import shapely

from ..layout.contrast import text_colour_on
from ..numeric import affine
from ..units import PAPER_SIZES
from ..weave.model import Weave
from .book import CURL
from .notches import widen_notches
from .pages import FOLD, PageArea, _fits, rect_sides
from .slim import outline_of
from .strips import Strip, flat_angle, tint
from .unfold import OVERLAP, Unfolding, UnfoldError, dashed

MIN_FOLD = math.radians(1.0)  # joints flatter than this are not drawn as folds
VALLEY = (0.5, 1.0)  # mm dash and gap of a valley fold (a mountain fold: unfold.DASH)


class PageTooSmall(UnfoldError):
    """Two tiles of a strip, its shortest piece (one tile and the glue band under the next
    piece), do not fit the page: ``need`` (long, short) mm, the rectangle every two do fit."""

    def __init__(self, need: tuple[float, float]) -> None:
        super().__init__(f"two tiles of a strip need {need[0]:.0f} x {need[1]:.0f} mm, more than "
                         "the page holds: make the ball smaller or the page larger")
        self.need = need


def piece_runs(tiles, length: float, width: float, widest: float | None = None
               ) -> list[tuple[int, int]]:
    """Runs (first, last) of whole tiles, consecutive runs sharing a tile, such that each run
    fits a ``length`` x ``width`` rectangle and no two tiles of a run overlap (but neighbours,
    which share an edge); as few runs as greedy extension gives, then evened out if the
    even runs still fit. ``width`` (where a curling strip is cut: a packing choice) gives way,
    up to ``widest`` (the page's), to the widest two tiles: the shortest piece there is.

    Raises
    ------
    PageTooSmall when two tiles do not fit ``length`` x ``widest``
    """
    tiles = np.asarray(tiles, dtype=object)
    m = len(tiles)
    if m > 1:  # what the shortest pieces need
        pairs = rect_sides(shapely.union(tiles[:-1], tiles[1:]))
        short, long = pairs[:, 0].max(), pairs[:, 1].max()
        if long > length or short > (width if widest is None else widest):
            raise PageTooSmall((float(long), float(short)))
        width = max(width, short)

    def ok(a: int, b: int) -> bool:
        part = tiles[a:b + 1]
        if not _fits(shapely.union_all(part), length, width):
            return False
        i, j = shapely.STRtree(part).query(part, predicate="intersects")
        far = j > i + 1
        overlap = shapely.area(shapely.intersection(part[i[far]], part[j[far]]))
        return bool((overlap <= OVERLAP * shapely.area(part[i[far]])).all())

    if m == 1:
        return [(0, 0)]
    runs, a = [], 0
    while True:  # runs
        b = a + 1
        while b + 1 < m and ok(a, b + 1):
            b += 1
        runs.append((a, b))
        if b >= m - 1:
            return _even(runs, m, ok)
        a = b


def _even(runs, m: int, ok) -> list[tuple[int, int]]:
    """As many runs as ``runs`` over ``m`` tiles, of equal length if those pass ``ok``."""
    ends = np.round(np.linspace(0, m - 1, len(runs) + 1)).astype(int).tolist()
    even = list(zip(ends[:-1], ends[1:]))
    return even if all(b > a and ok(a, b) for a, b in even) else runs


def too_large(need, diameter: float, page, margin: float) -> str:
    """What to do when two tiles of a strip, ``need`` (long, short) mm on a ball ``diameter``
    mm across, do not fit ``page``: the largest ball in cm on this page, and on A3."""
    def largest(w: float, h: float) -> int:  # cm: every two tiles fit inside the margins
        return math.floor(diameter * min(max(w, h) / need[0], min(w, h) / need[1]) / 10)

    area = PageArea(page[0], page[1], margin)
    on_a3 = PageArea(*PAPER_SIZES["a3"], margin)
    bigger = f", or --page a3 (up to {largest(on_a3.long, on_a3.short)}cm)" \
        if largest(on_a3.long, on_a3.short) > largest(area.long, area.short) else ""
    return (f"on a {diameter / 10:g} cm ball two tiles of a strip (its shortest piece) need "
            f"{need[0]:.0f} x {need[1]:.0f} mm; the page holds {area.long:.0f} x "
            f"{area.short:.0f} mm inside its margins: use --size "
            f"{largest(area.long, area.short)}cm or less{bigger}")


def strand_pieces(weave: Weave, u: Unfolding, colours, labels, scale: float,
                  area: PageArea) -> list[Strip]:
    """Strand ``u.strand``'s strip in pieces (mm, unlabelled), each laid flat, long axis
    along x, walking towards +x."""
    s = u.strand
    tiles = shapely.transform(u.tile_polygons(), lambda xy: xy * scale)
    runs = piece_runs(tiles, area.long, CURL * area.short, area.short)
    top = weave.tile_over[u.tiles]
    fills = tuple(colours[s] if o else tint(colours[t]) for o, t in zip(u.over, top.tolist()))
    names = tuple(labels[t] for t in top.tolist())
    fold = np.abs(u.fold_angles) >= MIN_FOLD
    # a fold across an own tile in the ink that reads on the strand's colour, else dark
    across_own = (u.face_visit[:-1] == u.face_visit[1:]) & u.over[u.face_visit[:-1]]
    inks = np.where(across_own, text_colour_on(colours[s]), FOLD.stroke)
    # mountain folds (the printed side bulges out) dashed, valley folds dotted
    lines = np.where(u.fold_angles > 0, dashed(u.folds * scale),
                     dashed(u.folds * scale, *VALLEY))
    closed = bool(weave.strand_closed[s])
    n = len(runs)
    eps = 1e-6 * scale
    out = []
    for i, (a, b) in enumerate(runs):  # pieces of one strand
        band = closed or i + 1 < n
        inside = fold & (u.face_visit[:-1] >= a) & (u.face_visit[1:] <= b)
        outline = widen_notches(outline_of(tiles[a:b + 1], eps))
        paper = shapely.intersection(tiles[a:b + 1], outline)  # less the widened notches
        piece = Strip(s, labels[s] if n == 1 else f"{labels[s]} {i + 1}/{n}",
                      outline, paper, fills[a:b + 1], u.over[a:b + 1], names[a:b + 1],
                      np.eye(3), arrow_ink=text_colour_on(colours[s]),
                      glue=paper[-1:] if band else None, folds=lines[inside],
                      fold_inks=tuple(inks[inside].tolist()),
                      tab=f"glue {i + 1}", mark=str(i) if i else (str(n) if closed else ""))
        flat = piece.moved(affine(flat_angle(piece.outline)))
        ends = shapely.get_coordinates(shapely.centroid(flat.tiles[[0, -1]]))
        if ends[1, 0] < ends[0, 0]:
            flat = flat.moved(affine(180.0))
        bx, by = flat.outline.bounds[:2]
        out.append(flat.moved(affine(0.0, (-bx, -by))))
    return out
