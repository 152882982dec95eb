"""The crossings the strips cannot name, called out on page 1 or on pages of their own.

An under tile too small for a 2.5 mm name even on a plate over its neighbours (a border tile of
the pentagon flower at the paper's 23 cm) is printed without it (:func:`label_strip`). Each
such crossing is called out once, "C8 over A14" on a white plate with a leader line to a dot on
the crossing: on the assembly sheet where they all find a free spot (:mod:`.assembly`), else
on pages after the weaving page that show the pattern once more between two columns of
callouts, as a technical drawing's. The greedy free-spot search alone fails there: on the
pentagon flower the plates that hug the border wall the later leaders off, and only 61 of its
155 crossings found a spot on a page; a column of an A4 page holds 42.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..numeric import affine_inverse, distinct, transform
from ..layout.drawing import Layer, Polylines, Style, Text, polygons_from_shapely
from ..layout.labels import MIN_CAP, centred_text, text_box, text_width
from ..weave.model import Weave
from .pages import GAP
from .pattern import label_spots, pattern
from .strips import model_tiles
from .wording import PRINTED, Words, paragraphs

PLATE_PAD = 0.8  # mm of white plate round a callout's text
LEADER = Style("#000000", 0.25)
CASING = Style("#ffffff", 0.7)  # under the leader, so it shows on dark tiles too
DOT = 0.7  # mm, radius of the dot on the crossing
RING = 1.0  # mm, outer radius of the ring round a strand ID's leader end
ROW_GAP = 0.6  # mm between two plates of a column


def left_out_crossings(weave: Weave, plan, pieces, layout: str) -> list[tuple[int, int, int]]:
    """(tile, strand on top, strand below) of every crossing some printed strip leaves unnamed,
    sorted. A piece's tile is found by putting the piece back through the inverse of its page
    transform; in the module layout every print names the same tiles of every copy."""
    tiles = shapely.make_valid(model_tiles(weave), method="structure", keep_collapsed=False)
    tree = shapely.STRtree(tiles)
    found: set[int] = set()
    for piece in pieces:  # pieces, not mesh elements
        if not piece.left_out:
            continue
        spots = shapely.transform(shapely.point_on_surface(piece.tiles[list(piece.left_out)]),
                                  transform(affine_inverse(piece.frame)))
        which, hit = tree.query(spots, predicate="intersects")
        mine = weave.tile_under[hit] == piece.strand
        found.update(hit[mine].tolist())
        if len(distinct(which[mine])) != len(spots):
            raise AssertionError(f"a left-out crossing of {piece.label} lies on no tile")
    t = np.array(sorted(found), dtype=np.int64)
    if layout == "module":  # one print per copy
        t = distinct(plan.symmetry.tile_powers()[:, t])
    return list(zip(t.tolist(), weave.tile_over[t].tolist(), weave.tile_under[t].tolist()))


def too_small(n: int, name: str = "a name") -> str:
    """"3 crossings are too small to carry a name on their strips" (or "1 crossing is ... its
    strip")."""
    if n == 1:
        return f"1 crossing is too small to carry {name} on its strip"
    return f"{n} crossings are too small to carry {name} on their strips"


def crossing_label(ids, over: int, under: int) -> str:
    """"C8 over A14": strand ``over`` lies on top of strip ``under`` there."""
    return f"{ids[over]} over {ids[under]}"


def crossing_meaning(ids, crossing) -> str:
    """'"C8 over A14": strip A14 goes under strand C8 at the dot', told with ``crossing``
    (tile, strand on top, strand below), so the example is one the maker finds on the page."""
    _, over, under = crossing
    return (f"\"{crossing_label(ids, over, under)}\": strip {ids[under]} goes under strand "
            f"{ids[over]} at the dot")


def column_callouts(spots, labels: list[str], frame, middle: float, right=None) -> list:
    """A (text, plate, leader) for every ``spots[i]`` (sheet mm) saying ``labels[i]`` at
    ``MIN_CAP``: a spot left of ``middle`` (x) gets its plate in a column at the left edge of
    ``frame`` (x0, y0, x1, y1), the others at the right edge (or those where ``right``). The plates of a column are as wide
    as its widest, so every leader starts on one line and runs away from the column (clear of
    its plates); their slots lie in the order of the spots from top to bottom, each as near its
    spot's height as the slots above and below allow, and :func:`uncrossed` then deals the slots
    out so that no two leaders cross. A column holds :func:`column_room` plates."""
    spots = np.asarray(spots, dtype=float).reshape(-1, 2)
    x0, y0, x1, y1 = frame
    h = _plate_height()
    out: list = [None] * len(spots)
    side = spots[:, 0] >= middle if right is None else np.asarray(right, dtype=bool)
    for right in (False, True):  # the two columns
        mine = np.flatnonzero(side == right)
        mine = mine[np.argsort(-spots[mine, 1], kind="stable")]  # top first
        y = np.clip(spots[mine, 1], y0 + h / 2, y1 - h / 2)  # ideal heights, then pushed
        for k in range(1, len(y)):  # push down below the plate above
            y[k] = min(y[k], y[k - 1] - h - ROW_GAP)
        y[-1:] = np.maximum(y[-1:], y0 + h / 2)
        for k in range(len(y) - 2, -1, -1):  # and up above the plate below
            y[k] = max(y[k], y[k + 1] + h + ROW_GAP)
        if len(y) and y[0] > y1 - h / 2 + 1e-9:
            raise ValueError(f"{len(y)} callouts do not fit in one column")
        if not len(y):
            continue
        y += np.clip(np.mean(spots[mine, 1] - y), y0 + h / 2 - y[-1], y1 - h / 2 - y[0])
        w = max(text_width(labels[i], MIN_CAP) for i in mine.tolist()) + 2 * PLATE_PAD
        left = x1 - w if right else x0
        edges = np.column_stack([np.full(len(y), x1 - w if right else x0 + w), y])
        for i, k in zip(mine.tolist(), uncrossed(edges, spots[mine]).tolist()):  # callouts
            text = centred_text((left + w / 2, y[k]), labels[i], MIN_CAP)
            plate = shapely.box(left, y[k] - h / 2, left + w, y[k] + h / 2)
            out[i] = (text, plate, np.array([edges[k], spots[i]]))
    return out


def uncrossed(starts, ends) -> np.ndarray:
    """``slot``: the leaders ``starts[slot[i]]`` to ``ends[i]`` cross nowhere. Starting from
    ``slot[i] = i``, two leaders that cross swap their starts (2-opt): the two new leaders are
    together strictly shorter than the two old ones (the triangle inequality twice), so the
    total length falls with every swap and the swaps come to an end."""
    starts, ends = np.asarray(starts, dtype=float), np.asarray(ends, dtype=float)
    slot = np.arange(len(ends))
    while True:
        i, j = np.nonzero(np.triu(segments_cross(starts[slot], ends), 1))
        if not len(i):
            return slot
        slot[[i[0], j[0]]] = slot[[j[0], i[0]]]


def segments_cross(a, b) -> np.ndarray:
    """(n, n) bool: segment ``a[i]``-``b[i]`` crosses segment ``a[j]``-``b[j]``, each passing
    strictly between the other's ends (segments that only touch, or lie on one line, do not)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    d = b - a

    def side(pts):  # (i, j): the side of segment i that pts[j] lies on
        r = pts[None, :, :] - a[:, None, :]
        return np.sign(d[:, None, 0] * r[..., 1] - d[:, None, 1] * r[..., 0])

    apart = side(a) * side(b) < 0  # (i, j): a[j], b[j] on two sides of segment i
    return apart & apart.T


def _plate_height() -> float:
    bx = text_box(centred_text((0.0, 0.0), "A8", MIN_CAP)).bounds
    return bx[3] - bx[1] + 2 * PLATE_PAD


def column_room(frame) -> int:
    """How many plates one column of :func:`column_callouts` holds in ``frame``."""
    return int((frame[3] - frame[1] + ROW_GAP) // (_plate_height() + ROW_GAP))


def callout_shapes(placed: list, spots, dots=True) -> tuple[list, list[Text]]:
    """(shapes, texts) drawing the ``callouts`` ``placed`` at ``spots``: white plates, leader
    lines on a white casing, and a dot on every spot where ``dots`` (one bool, or one per
    callout), a ring round it elsewhere (the tile's own colour shows inside)."""
    placed_at = list(zip(placed, np.asarray(spots).reshape(-1, 2)))
    lines = np.concatenate([p[2] for p, _ in placed_at])
    offsets = np.arange(0, len(lines) + 1, 2, dtype=np.int64)
    shapes = [polygons_from_shapely([p[1] for p, _ in placed_at],
                                    Style("#333333", 0.15, "#ffffff")),
              Polylines(lines, offsets, CASING), Polylines(lines, offsets, LEADER)]
    points = shapely.points([s for _, s in placed_at])
    ring = ~np.broadcast_to(np.asarray(dots, dtype=bool), (len(placed_at),))
    marks = shapely.buffer(points, np.where(ring, RING, DOT))
    marks[ring] = shapely.difference(marks[ring], shapely.buffer(points[ring], RING - 0.4))
    shapes.append(polygons_from_shapely(list(marks), Style("#ffffff", 0.2, "#000000")))
    return shapes, [p[0] for p, _ in placed_at]


def named_by_callouts(unnamed, crossings) -> tuple[list, list]:
    """(called, rest): the strands of ``unnamed`` (strand, tile where it lies on top) that a
    callout of ``crossings`` (tile, strand on top, strand below) names, and the others. A
    callout "C8 over A14" names C8 only: its dot lies in a tile of C8's colour, as an ID's ring
    would; A14 is hidden there (the maker learns that it passes, not where it shows)."""
    tops = {over for _, over, _ in crossings}
    return [u for u in unnamed if u[0] in tops], [u for u in unnamed if u[0] not in tops]


def strand_notes(ids, crossings, unnamed, called) -> list[str]:
    """What the pages of :func:`crossing_pages` say about the strands page 1 has no room to
    name: ``called`` named first in a callout of ``crossings``, ``unnamed`` once here."""
    parts = []
    if called:
        s = called[0][0]
        over, under = next((o, u) for _, o, u in crossings if o == s)
        parts.append(f"{len(called)} {'is' if len(called) == 1 else 'are'} named first in a "
                     f"callout, on top at its dot ({ids[s]} in "
                     f"\"{crossing_label(ids, over, under)}\")")
    if unnamed:
        n, ring = len(unnamed), " (a ring round the line's end)" if crossings else ""
        parts.append(f"{n} {'is' if n == 1 else 'are'} named here once{' each' if n > 1 else ''}"
                     f", with a line to a tile where the strand lies on top{ring}")
    return [f"Of the strands page 1 has no room to name, {'; '.join(parts)}."] if parts else []


def crossing_pages(weave: Weave, plan, colours, area, crossings, turn: float,
                   words: Words = PRINTED, unnamed=(), called=()) -> list[tuple]:
    """The layers of the pages naming every crossing in ``crossings``
    (:func:`left_out_crossings`) and the strands page 1 has no room for that no callout names
    (``unnamed``: strand, tile where it lies on top; ``called``: those a callout names, see
    :func:`named_by_callouts`), without the page furniture: the pattern between two columns
    of callouts, 3 GAP clear of the widest plate (room for the leaders); as few pages as the
    columns hold them in (a side with more than its columns hold gives the callouts nearest
    the middle to the other), the callouts of each side dealt out over them in turn from the
    top. A crossing's leader ends on a dot, its text in a layer "crossings"; a strand's on a
    ring (the tile's colour, the strand's, shows inside), its ID in a layer "ids" as on page
    1. ``words`` say how such a crossing looks on its strip."""
    tiles, labels, kinds, note = _callouts(plan.labels, crossings, words, unnamed, called)
    return callout_pages(weave, colours, area, tiles, labels, note, turn, kinds)


def crossing_page_count(plan, area, crossings, words: Words = PRINTED, unnamed=(),
                        called=()) -> int:
    """How many pages :func:`crossing_pages` has, without drawing them."""
    _, labels, _, note = _callouts(plan.labels, crossings, words, unnamed, called)
    return _frame(area, note, len(labels))[2]


def _callouts(ids, crossings, words: Words, unnamed, called):
    """(tiles, labels, kinds, note) of the callouts of :func:`crossing_pages`."""
    notes = []
    if crossings:
        notes.append(f"{too_small(len(crossings))}: there the "
                     f"strip {words.unnamed_there}. Each is called out once: "
                     f"{crossing_meaning(ids, crossings[0])}.")
    notes += strand_notes(ids, crossings, unnamed, called)
    labels = ([crossing_label(ids, over, under) for _, over, under in crossings]
              + [ids[s] for s, _ in unnamed])
    tiles = [c[0] for c in crossings] + [t for _, t in unnamed]
    kinds = ["crossings"] * len(crossings) + ["ids"] * len(unnamed)
    return tiles, labels, kinds, " ".join(notes)


def id_pages(weave: Weave, plan, colours, area, unnamed, turn: float) -> list[tuple]:
    """The layers of the pages of their own naming ``unnamed``, the strands page 1 has no room
    for that no callout names: :func:`crossing_pages` of ``unnamed`` alone."""
    return crossing_pages(weave, plan, colours, area, (), turn, unnamed=unnamed)


def _frame(area, note: str, count: int):
    """(the note's texts, the frame below it, pages): the pages ``count`` callouts take in two
    columns of :func:`column_room` each."""
    x0, y0, x1, y1 = area.box
    texts, bottom = paragraphs([note], x0, y1, x1 - x0)
    frame = (x0, y0, x1, bottom - GAP)
    return texts, frame, max(1, -(-count // (2 * column_room(frame))))


def callout_pages(weave: Weave, colours, area, tiles, labels: list[str], note: str,
                  turn: float, kinds: list[str]) -> list[tuple]:
    """The layers of the pages calling out ``labels[i]`` at ``tiles[i]`` (a white plate in a
    column, a leader into the tile, ending on a dot for a crossing, on a ring for a strand's ID:
    ``kinds[i]`` "crossings" or "ids", the layer of its text), with ``note`` above."""
    x0, y0, x1, y1 = area.box
    texts, frame, n = _frame(area, note, len(tiles))
    room = max((text_width(s, MIN_CAP) for s in labels), default=0.0) + 2 * PLATE_PAD + 3 * GAP
    on_sheet, _, paint, _ = pattern(weave, turn, (x0 + room, y0, x1 - room, frame[3]), colours)
    spots = label_spots(on_sheet[list(tiles)])
    middle = (x0 + x1) / 2
    side = spots[:, 0] >= middle
    room = column_room(frame)
    for heavy in (False, True):  # a side with more than its columns hold: those nearest the
        mine = np.flatnonzero(side == heavy)  # middle go to the other side (no leaders cross)
        if len(mine) > n * room:
            near = np.argsort(np.abs(spots[mine, 0] - middle), kind="stable")
            side[mine[near[:len(mine) - n * room]]] = not heavy
    page = np.zeros(len(spots), dtype=np.int64)
    for right in (False, True):  # deal each side's callouts out over the pages, top first
        mine = np.flatnonzero(side == right)
        page[mine[np.argsort(-spots[mine, 1], kind="stable")]] = np.arange(len(mine)) % n
    dots = np.array([k == "crossings" for k in kinds], dtype=bool)
    pages = []
    for p in range(n):  # pages
        on = np.flatnonzero(page == p)
        placed = column_callouts(spots[on], [labels[i] for i in on.tolist()], frame, middle,
                                 side[on])
        shapes, named = callout_shapes(placed, spots[on], dots[on])
        pages.append((Layer("pattern", "paint", (paint, *shapes)),
                      *(Layer(k, "label", tuple(t for t, i in zip(named, on.tolist())
                                                if kinds[i] == k))
                        for k in ("crossings", "ids") if k in kinds),
                      Layer("notes", "label", tuple(texts))))
    return pages
