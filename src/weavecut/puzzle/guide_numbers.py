"""Where a painting guide prints every piece's number, in which ink, and on what.

A number must be found: its ink reads on whatever lies under it (WCAG contrast at least
``MIN_CONTRAST``), it stands apart from its neighbours by more than its own digits do, and it
reads upright. So every number is fitted, up to ``MAX_CAP`` mm, into a part of its piece
whose paint is known: the piece less its ring hexagon (all its paints under the number), on
the front one half (one paint), a ring piece's bare hexagon (natural wood, printed white), or
the whole ring piece (its paints and the white hexagon). No number crosses a dashed line (the
parent edge across a two-coloured piece, a ring piece's hexagon edge): it would read as split
in two, so a fit that meets one is dropped.
The largest of these on which black or white reaches the contrast wins, level where a level
number is nearly as large; a ring piece's hexagon (or the whole piece) only where its
painted part has no room even at ``RING_CAP``: a white hexagon with a number reads as a piece
of its own, so a ring piece's number goes on its paint a little smaller first. Where no
ink reads (two paints of which one wants black and the other white, or a mid-tone paint) the
number sits on a small white plate in black ink. A number that fits nowhere at ``MIN_CAP``
is printed smaller, down to ``LEAST``; a piece too small even for that is left without a
number. Both are named in a warning, never silently.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import shapely
from numpy.typing import NDArray

from ..layout.contrast import BLACK, MIN_CONTRAST, WHITE, contrast_ratio
from ..layout.labels import MIN_CAP
from ..layout import strokefont
from ..layout.strokefont import fit_labels, ink_box
from ..numeric import turn
from .colouring import UNPAINTED, Colouring
from .files import Labels, _listed, piece_texts
from .guides import NUMBER_STROKE, bare_pieces, hexagon_edges, piece_halves, split_ends
from .pieces import Puzzle

MAX_CAP = 6.0  # mm, the largest number on a guide
WORD_SPAN = 9.5  # mm, the most a number spans: under the 10 mm by which printed pages overlap,
# so each is whole on one page (layout.tiling keeps a word whole or leaves it to the next page)
LEAST = 1.5  # mm, the smallest: a piece without room for it is named, not numbered
RING_CAP = 2.3  # mm: a ring piece's number on its paint at this size, where an ink reads there,
# goes before a MIN_CAP number on its bare hexagon (a white hexagon with a number reads as a
# piece of its own; 2.3 mm is 8 % smaller, the default puzzle's last 12 ring pieces fit 2.31-2.5)
MARGIN = 0.6  # mm from a number's box to its piece's edge
PAD = 0.25  # of the cap height, each side of a number's ink: its room from the next number
TIGHT_CAP = 3.0  # mm, the largest number fitted without PAD: the two MARGINs between it and
# the next number (less the strokes) are then still wider than its digits' spacing (2/7 cap)
PLATE = 0.25  # mm each side of a number's ink box: its plate (twice MARGIN less this keeps two
# plates in neighbouring pieces MIN_GAP apart)
LEVEL_SHARE = 0.8  # a level number this large against the largest turned one goes level
PAPER = UNPAINTED  # what a printed guide shows where nothing is painted


@dataclass(frozen=True, eq=False)
class GuideNumbers:
    """Every piece's number on one side's guide (in the puzzle's coordinates, unmirrored).

    ``inks`` (P,) black or white; ``plates`` (P,) the white plate under a number (None for
    none); a height of 0: no number fits, even at ``LEAST``; ``ring`` (P,) the ring pieces
    (their numbers go down to ``RING_CAP`` on their paint by design, unwarned)."""

    labels: Labels
    inks: NDArray[np.object_]
    plates: NDArray[np.object_]
    ring: NDArray[np.bool_] | None = None


@lru_cache(maxsize=1024)
def _ink(fills: tuple[str, ...]) -> tuple[str, float]:
    """Black or white, whichever reads better on all of ``fills``, and its least contrast (kept:
    the pieces of a puzzle share a few paints)."""
    worst = {ink: min(contrast_ratio(ink, f) for f in fills) for ink in (BLACK, WHITE)}
    ink = BLACK if worst[BLACK] >= worst[WHITE] else WHITE
    return ink, worst[ink]


def _paper(colour: str) -> str:
    return PAPER if colour == UNPAINTED else colour


def _candidates(puzzle: Puzzle, colouring: Colouring, side: str) -> list[tuple]:
    """[(regions (P,), fills per piece, pad)]: the parts of every piece a number may fill, with
    the paints it then lies on; the whole piece less its hexagon first."""
    hexes = puzzle.hexagons
    has = hexes != None  # noqa: E711
    base = bare_pieces(puzzle)
    paints = (colouring.front if side == "front" else colouring.back[:, None]).tolist()
    painted = [tuple(dict.fromkeys(map(_paper, f))) for f in paints]
    out = [(base, painted, PAD)]
    if side == "front":
        halves = piece_halves(puzzle)
        for j in (0, 1):
            part = _largest_parts(shapely.intersection(halves[:, j], base))
            out.append((part, [(_paper(f[j]),) for f in paints], PAD))
    if has.any():  # a ring piece: on its bare hexagon, or across hexagon and paint
        hexagon = np.where(has, hexes, None)
        out.append((hexagon, [(PAPER,)] * len(base), PAD))
        out.append((puzzle.pieces, [tuple(dict.fromkeys((*p, PAPER))) if h else p
                                    for p, h in zip(painted, has.tolist())], PAD))
    return out


def _largest_parts(geoms: NDArray[np.object_]) -> NDArray[np.object_]:
    """The largest part of every geometry (the first of equal ones; itself where it has
    none)."""
    parts, of = shapely.get_parts(geoms, return_index=True)
    out = geoms.copy()
    if len(parts):
        area = shapely.area(parts)
        # by owner, the largest first, the first of equal ones first (a stable sort)
        order = np.lexsort((-area, of))
        first = order[np.r_[True, of[order][1:] != of[order][:-1]]]
        out[of[first]] = parts[first]
    return out


def guide_numbers(puzzle: Puzzle, colouring: Colouring, side: str) -> GuideNumbers:
    """Every piece's number for ``side``'s guide: the largest that reads, where it reads; on
    the painted part of a ring piece wherever that has room (its bare hexagon, white like the
    paper, would read as a piece of its own)."""
    texts = piece_texts(puzzle.n_pieces)
    n = len(texts)
    candidates = _candidates(puzzle, colouring, side)
    painted = len(candidates) - 2 * bool((puzzle.hexagons != None).any())  # noqa: E711
    reads = [[_ink(f) for f in fills] for _, fills, _ in candidates]
    splits = split_lines(puzzle, colouring, side)  # never a number across a dashed line

    def fits(ks, pad, where=None):  # candidates ks fitted with room ``pad`` for ``where``
        return [(_off_the_splits(_fit(candidates[k][0] if where is None else
                                      np.where(where, candidates[k][0], None), texts, pad),
                                 texts, splits), reads[k], pad)
                for k in ks]

    paint, hexes = range(painted), range(painted, len(candidates))
    roomy = fits(paint, PAD)
    # a number without room round it is looked at only for a piece that no number with room
    # round it reads on at MIN_CAP on the paint (_choose: one without room never replaces one):
    # it is fitted for those pieces alone
    chosen = _unchosen(n)
    _read(roomy, MIN_CAP, chosen)
    on_paint = roomy + fits(paint, 0.0, chosen[0] == 0)
    # at MIN_CAP if anywhere, else smaller; on the paint before the hexagon (a ring piece's
    # down to RING_CAP, where an ink reads); on a plate before smaller: a ring piece's hexagon
    # (or the whole piece) is looked at only for the pieces without a number on the paint by
    # then, and fitted for those alone
    ring = puzzle.hexagons != None  # noqa: E711
    chosen = _unchosen(n)
    _choose(on_paint, MIN_CAP, chosen)
    _choose(on_paint, RING_CAP, chosen, ring, plates=False)
    left = chosen[0] == 0
    every = (on_paint[:painted] + fits(hexes, PAD, left) + on_paint[painted:]
             + fits(hexes, 0.0, left))
    _choose(every, MIN_CAP, chosen)
    for group in (on_paint, every):
        _choose(group, LEAST, chosen)
    best_h, centres, angles, inks, plated = chosen
    plates = np.full(n, None, dtype=object)
    if plated.any():
        plates[plated] = _plates([texts[k] for k in np.flatnonzero(plated).tolist()],
                                 best_h[plated], centres[plated], angles[plated])
    return GuideNumbers(Labels(tuple(texts), best_h, centres, angles), inks, plates, ring)


def _unchosen(n: int) -> tuple:
    """``n`` pieces without a number: heights, centres, angles, inks, plated."""
    return (np.zeros(n), np.zeros((n, 2)), np.zeros(n), np.full(n, BLACK, dtype=object),
            np.zeros(n, dtype=bool))


def _read(fits, floor: float, chosen, only=True) -> None:
    """Number the pieces without one (``chosen``, changed in place; of those, the pieces
    ``only`` marks) from ``fits`` at ``floor`` mm or more where an ink reads: the first that
    reads wins, a larger one with room round it over it."""
    best_h, centres, angles, inks, _ = chosen
    todo = (best_h == 0) & only
    for (h, c, a), read, pad in fits:
        ok = todo & np.array([r[1] >= MIN_CONTRAST for r in read]) & (h >= floor)
        better = ok & ((best_h == 0) | ((h > best_h + 1e-9) & (pad > 0)))
        best_h[better], centres[better], angles[better] = h[better], c[better], a[better]
        inks[better] = np.array([r[0] for r in read], dtype=object)[better]


def _choose(fits, floor: float, chosen, only=True, plates: bool = True) -> None:
    """Number the pieces still without one (``chosen``: heights, centres, angles, inks, plated,
    changed in place; of those, the pieces ``only`` marks) from ``fits`` at ``floor`` mm or
    more: where an ink reads, else (with ``plates``) on a plate."""
    best_h, centres, angles, _, plated = chosen
    _read(fits, floor, chosen, only)
    if not plates:
        return
    # no part reads: where the number is largest, with room round it if it can, on a plate,
    # in black
    todo = (best_h == 0) & only
    for want in (PAD, 0.0):
        for (h, c, a), _, pad in fits:
            better = todo & (pad == want) & (h >= floor) & (h > best_h + 1e-9)
            best_h[better], centres[better], angles[better] = h[better], c[better], a[better]
            plated |= better
        todo &= best_h == 0


def _fit(regions, texts, pad: float) -> tuple:
    """:func:`fit_labels` of the numbers into ``regions`` (none where a region is None):
    level where a level number is nearly as large and at least ``MIN_CAP``."""
    h, c, a = np.zeros(len(texts)), np.zeros((len(texts), 2)), np.zeros(len(texts))
    some = np.flatnonzero(regions != None)  # noqa: E711
    if len(some):
        chosen = [texts[k] for k in some.tolist()]
        args = (regions[some].astype(object), chosen, MARGIN,
                np.minimum(MAX_CAP if pad else TIGHT_CAP, largest_caps(chosen)), pad)
        h[some], c[some], a[some] = fit_labels(*args, LEVEL_SHARE, MIN_CAP)
    return h, c, a


def largest_caps(texts) -> NDArray[np.float64]:
    """(n,) the largest cap height at which every text, turned any way, spans at most
    ``WORD_SPAN`` mm across and up (its box's diagonal, with its strokes)."""
    box = np.array([ink_box(t) for t in texts], dtype=float).reshape(-1, 4)
    diagonal = np.hypot(box[:, 2] - box[:, 0], box[:, 3] - box[:, 1])
    return (WORD_SPAN - NUMBER_STROKE) / np.maximum(diagonal, 1e-9)


def split_lines(puzzle: Puzzle, colouring: Colouring, side: str) -> NDArray[np.object_]:
    """The dashed lines of ``side``'s guide as whole segments (linestrings): the parent edge
    across a two-coloured piece (the front's) and a ring piece's hexagon edge (both sides')."""
    ends = [hexagon_edges(puzzle)]
    if side == "front":
        u, w = split_ends(puzzle)
        two = colouring.front[:, 0] != colouring.front[:, 1]
        ends.append((u[two], w[two]))
    a, b = (np.concatenate(e).reshape(-1, 2) for e in zip(*ends))
    return shapely.linestrings(np.stack([a, b], axis=1)) if len(a) else np.array([], object)


def _off_the_splits(fit: tuple, texts, splits: NDArray[np.object_]) -> tuple:
    """``fit`` (heights, centres, angles) less the numbers whose strokes (with their width)
    meet a dashed line of ``splits``: such a number reads as split in two, its digits as
    belonging to two parts (issue 29's piece 377, across its hexagon's line)."""
    h, c, a = fit
    some = np.flatnonzero(h > 0)
    if not len(some) or not len(splits):
        return fit
    xy, offsets, owner = strokefont.labels([texts[k] for k in some.tolist()], c[some], h[some],
                                           a[some])
    lines = shapely.linestrings(xy, indices=np.repeat(np.arange(len(offsets) - 1),
                                                      np.diff(offsets)))
    hit = shapely.STRtree(splits).query(lines, predicate="dwithin",
                                        distance=NUMBER_STROKE / 2)[0]
    owner = some[owner]
    h = h.copy()
    h[owner[hit]] = 0.0  # (no np.unique: it would import numpy.ma)
    return h, c, a


def _plates(texts, heights, centres, angles) -> NDArray[np.object_]:
    """The white plates under numbers: their ink boxes widened by ``PLATE`` (inside the
    ``MARGIN`` a number keeps from its piece's edge)."""
    box = np.array([ink_box(t) for t in texts], dtype=float)
    hx = (box[:, 2] - box[:, 0]) / 2 * heights + PLATE
    hy = (box[:, 3] - box[:, 1]) / 2 * heights + PLATE
    corners = np.stack([np.stack([-hx, -hy], -1), np.stack([hx, -hy], -1),
                        np.stack([hx, hy], -1), np.stack([-hx, hy], -1)], axis=1)
    return shapely.polygons(turn(corners, angles[:, None], centres[:, None]))


def warnings(numbers: GuideNumbers, side: str) -> list[str]:
    """Lines naming the pieces whose number on ``side``'s guide is smaller than ``MIN_CAP``
    (a ring piece's: than ``RING_CAP``, the size it is given on its paint before its bare
    hexagon), and those too small for any (they are left without one: the colour key lists
    them)."""
    h = numbers.labels.heights
    least = MIN_CAP if numbers.ring is None else np.where(numbers.ring, RING_CAP, MIN_CAP)
    small, none = np.flatnonzero((h > 0) & (h < least - 1e-9)), np.flatnonzero(h == 0)
    out = []
    if len(small):
        out.append(f"pieces {_listed(small)} are too small for {MIN_CAP:g} mm numbers on the "
                   f"{side} painting guide; theirs are printed smaller (down to "
                   f"{h[small].min():.1f} mm)")
    if len(none):
        out.append(f"pieces {_listed(none)} are too small for {LEAST:g} mm numbers on the "
                   f"{side} painting guide and are printed without one (the colour key lists "
                   "them by their paint)")
    return out
