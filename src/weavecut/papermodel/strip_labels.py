"""Labels on paper strips: each one's ID, the names in its under tiles, direction arrows, label tabs.

Every label is fitted into its tile (less ``PAD``) as large as it goes up to a cap, or spread
over the neighbouring tiles on a plate; an ID that no own tile holds goes on a label tab cut
with the strip (``label_flap``, :mod:`.label_tabs`). ``strips`` makes the unlabelled strips. The
strips of a book are labelled together: each step is one call over the tiles of every strip, and
congruent strips (a module's copies) share what depends on their shape alone.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import shapely

from ..numeric import distinct, snap, turn
from ..layout.contrast import text_colour_on
from ..layout.labels import (
    MIN_CAP,
    centred_text,
    centred_texts,
    inner_centres,
    largest_fit,
    text_boxes,
    unit_corners,
)
from .label_tabs import label_flap, tab_fill
from .strips import Strip


PAD = 0.3  # mm between a label and its tile's edge
PLATE = 0.4  # mm a label's plate reaches beyond its text
ANGLES = tuple(np.arange(0.0, 180.0, 15.0).tolist())  # label turns tried (strip frame)
ID_SIZE = 6.0  # largest cap height of a strip's ID (mm)
NAME_SIZE = 3.0  # largest cap height of the ID printed in an under tile (well below an ID)


def label_strip(strip: Strip, tile_mm: float) -> Strip:
    """``strip`` with its labels (:func:`label_strips` of one strip)."""
    return label_strips([strip], tile_mm)[0]


def label_strips(strips: list[Strip], tile_mm: float) -> list[Strip]:
    """Every strip with its labels: its ID in its largest own tile (and in the other half of a
    long strip), the ID of the strand on top in every under tile, and direction arrows in own
    tiles that hold no ID. Every label is fitted into its tile (less ``PAD``) as large as it goes
    up to a cap, or spread over the neighbouring tiles on a plate; a name that still cannot
    reach ``MIN_CAP`` is left out (the assembly sheet shows that crossing); an ID no own tile
    holds goes on a label tab (:func:`label_flap`), or is kept at the size that fits (so the
    caller can name the tile size that works)."""
    if not strips:
        return []
    lay = _Tiles(strips)
    own, under, ids, id_tiles = _owners(lay)
    # IDs first (spread onto the neighbours if they must), a piece's number ("2/3") in the own
    # tile nearest, then the names round them
    first = _place(lay, [w[:1] for w in ids], [[] for _ in strips])
    taken = _taken(first)
    second = _place(lay, [w[1:] for w in ids], taken)
    placed = [(a + b, c + d, e + f) for (a, c, e), (b, d, f) in zip(first, second)]
    taken = _taken(placed)
    lay.clear_of(taken, recentre=True)
    empty = shapely.is_empty(lay.regions)
    names = [[(int(i), strip.names[i], NAME_SIZE) for i in under[s].tolist()
              if strip.names[i] and not empty[lay.first[s] + i]]
             for s, strip in enumerate(strips)]
    placed = [(a + b, c + d, e + f) for (a, c, e), (b, d, f) in
              zip(placed, _place(lay, names, taken))]
    # an under tile too small for the name (a border tile at 23 cm): the assembly sheet shows
    # that crossing, the strip leaves it out
    left_out = [tuple(w[0] for t, w in zip(texts, ids[s] + names[s]) if t.size < MIN_CAP
                      and w not in ids[s]) for s, (texts, _, _) in enumerate(placed)]
    texts = [[t for t, w in zip(texts, ids[s] + names[s]) if t.size >= MIN_CAP or w in ids[s]]
             for s, (texts, _, _) in enumerate(placed)]
    lay.clear_of([p for _, p, _ in placed], recentre=False)
    arrows = _arrows(lay, own, id_tiles, tile_mm)
    out, tabs = [], {}  # tabs: the first answer of label_flap for a shape and a text size
    for s, strip in enumerate(strips):
        if texts[s] and texts[s][0].size < MIN_CAP and ids[s]:  # no own tile reads: a tab
            word = texts[s][0].text
            key = (int(lay.same[s]), unit_corners([word]).tobytes())
            if key not in tabs:
                tabs[key] = label_flap(strip, word)
            if tabs[key] is not None:  # a congruent strip's tab, for a text as large
                tab, label = tabs[key]
                fill = tab_fill(strip)
                strip = replace(strip, flap=tab.flap, flap_edge=tab.flap_edge, flap_fill=fill)
                texts[s][0] = replace(label, text=word, fill=text_colour_on(fill))
        out.append(replace(strip, arrows=np.array(arrows[s], dtype=object),
                           plates=np.array(placed[s][1], dtype=object),
                           plate_fills=tuple(placed[s][2]), left_out=left_out[s]))
    return [replace(s, texts=tuple(t)) for s, t in zip(out, _glue_words(lay, texts))]


def _taken(placed) -> list[list]:
    """Per strip what later labels keep clear of: its plates and its texts' boxes (the boxes of
    every strip made at once)."""
    boxes = text_boxes([t for texts, _, _ in placed for t in texts])
    ends = np.cumsum([len(texts) for texts, _, _ in placed]).tolist()
    return [[*p, *boxes[a:b]] for (_, p, _), a, b in zip(placed, [0, *ends], ends)]


class _Tiles:
    """Every tile of every strip in one array (``first[s]`` is strip s's first), with the room
    a label has in it (``regions``: the tile on its strip, less its glue band, less ``PAD``) and
    the centre of that room."""

    def __init__(self, strips: list[Strip]):
        self.strips = strips
        count = np.array([len(s.tiles) for s in strips])
        self.first = np.cumsum(count) - count
        self.of = np.repeat(np.arange(len(strips)), count)
        # congruent strips (a module's copies: the same shapes in their own frames) share their
        # tiles, outline, glue band and regions, each worked out once
        self.same = same = _congruent(strips)
        twin = self.first[same[self.of]] + np.arange(len(self.of)) - self.first[self.of]
        self.tiles = np.concatenate([s.tiles for s in strips])[twin]
        self.bands = np.array([None if s.glue is None or same[i] != i else
                               shapely.union_all(s.glue) for i, s in enumerate(strips)],
                              dtype=object)[same]
        self.outlines = np.array([s.outline for s in strips], dtype=object)[same]
        mine, back = np.unique(twin, return_inverse=True)
        regions = shapely.intersection(self.tiles[mine], self.outlines[self.of[mine]])
        banded = np.flatnonzero(np.not_equal(self.bands, None)[self.of[mine]])
        regions[banded] = shapely.difference(regions[banded], self.bands[self.of[mine][banded]])
        self.regions = shapely.buffer(regions, -PAD, join_style="mitre")[back.reshape(-1)]
        self.centres = inner_centres(self.regions)

    def clear_of(self, shapes, recentre: bool) -> None:
        """Takes ``shapes[s]`` (polygons on strip s) and ``PAD`` round them out of the strips'
        regions; with ``recentre`` the changed regions get new centres."""
        owner = np.array([s for s, g in enumerate(shapes) for _ in g], dtype=np.int64)
        if not len(owner):
            return
        hit = distinct(owner)
        keep_out = np.full(len(shapes), None, dtype=object)
        keep_out[hit] = shapely.buffer(shapely.geometrycollections(
            [g for group in shapes for g in group], indices=np.searchsorted(hit, owner)), PAD)
        t = np.flatnonzero(np.isin(self.of, hit))
        t = t[shapely.intersects(self.regions[t], keep_out[self.of[t]])]  # the others keep theirs
        self.regions[t] = shapely.difference(self.regions[t], keep_out[self.of[t]])
        if recentre:
            self.centres[t] = inner_centres(self.regions[t])


def _congruent(strips: list[Strip]) -> np.ndarray:
    """(strips,) for each strip the first one of the same shape: the same outline, tiles and
    glue band, coordinate for coordinate."""
    geoms = [np.array([s.outline, *s.tiles, *(() if s.glue is None else s.glue)], dtype=object)
             for s in strips]
    wkb = np.split(shapely.to_wkb(np.concatenate(geoms)), np.cumsum([len(g) for g in geoms]))
    first: dict = {}
    return np.array([first.setdefault((len(s.tiles), *w), i)
                     for i, (s, w) in enumerate(zip(strips, wkb))], dtype=np.int64)


def _owners(lay: _Tiles):
    """(own tiles, under tiles, wanted IDs, the IDs' tiles) per strip: the ID goes in the largest own tile that
    holds it (a long strip's also in the largest of its other half), a piece's number in
    the own tile nearest that, and the first tile of a piece with a mark keeps its room for
    the mark."""
    empty = shapely.is_empty(lay.regions)
    area = snap(shapely.area(lay.regions))
    own, under, cand = [], [], []
    for s, strip in enumerate(lay.strips):
        lo = lay.first[s]
        free = ~empty[lo:lo + len(strip.tiles)]
        o = np.flatnonzero(strip.over & free)
        own.append(o)
        under.append(np.flatnonzero(~strip.over & free))
        cand.append(o[o != 0] if strip.mark and (o != 0).any() else o)
    at = np.concatenate([lay.first[s] + c for s, c in enumerate(cand)]).astype(np.int64)
    size, _ = _fit_text(lay.regions[at], lay.centres[at], [
        s.label.partition(" ")[0] for s, c in zip(lay.strips, cand) for _ in c], ID_SIZE)
    sizes = np.split(size, np.cumsum([len(c) for c in cand])[:-1])
    wanted, id_tiles = [], []
    for s, strip in enumerate(lay.strips):
        c, size = cand[s], sizes[s]
        tiles: list[int] = []
        if len(c):
            rank = np.lexsort((np.arange(len(c)), -area[lay.first[s] + c])).tolist()
            top = rank[0] if size[rank[0]] >= MIN_CAP else int(np.argmax(snap(size)))
            tiles = [int(c[top])]
            if len(c) >= 6:
                half = c > c[top] if c[top] < c[len(c) // 2] else c < c[top]
                tiles += [int(c[r]) for r in rank if half[r] and size[r] >= MIN_CAP][:1]
        name, _, part = strip.label.partition(" ")
        w = [(i, name, ID_SIZE) for i in tiles]
        if part and tiles:  # the part's number in the own tile nearest its ID
            spare = sorted((int(t) for t in c if int(t) not in tiles),
                           key=lambda t: (abs(t - tiles[0]), t))
            if spare:
                w.append((spare[0], part, NAME_SIZE))
            else:  # one own tile: it says both ("B 2/3")
                w[0] = (tiles[0], strip.label, ID_SIZE)
        if strip.mark:
            w.append((0, strip.mark, NAME_SIZE))
        wanted.append(w)
        id_tiles.append(tiles)
    return own, under, wanted, id_tiles


def _arrows(lay: _Tiles, own, id_tiles, tile_mm: float) -> list[list]:
    """Per strip, arrows in the first and the last own tile without an ID, pointing the way
    the strand goes, as long as they fit."""
    empty = shapely.is_empty(lay.regions)
    mid = shapely.get_coordinates(shapely.centroid(lay.tiles))
    at, dirs, owner = [], [], []
    for s, strip in enumerate(lay.strips):
        lo, n = lay.first[s], len(strip.tiles)
        free = [i for i in own[s].tolist() if i not in id_tiles[s] and not empty[lo + i]]
        for i in (sorted({free[0], free[-1]}) if free else []):
            at.append(lo + i)
            dirs.append(mid[lo + min(i + 1, n - 1)] - mid[lo + max(i - 1, 0)])
            owner.append(s)
    out: list[list] = [[] for _ in lay.strips]
    if at:
        unit = unit_arrows(dirs)
        length = largest_fit(lay.regions[at], unit, lay.centres[at], 2.0, 0.45 * tile_mm)
        ok = np.isfinite(length)
        shapes = shapely.polygons(unit[ok] * length[ok, None, None] + lay.centres[at][ok, None])
        for s, a in zip(np.asarray(owner)[ok].tolist(), shapes):
            out[s].append(a)
    return out


def _glue_words(lay: _Tiles, texts):
    """``texts`` per strip, with the strip's ``tab`` ("glue") on its glue band where it fits."""
    banded = np.flatnonzero(np.not_equal(lay.bands, None))
    if len(banded):
        zones = shapely.buffer(shapely.intersection(lay.bands[banded], lay.outlines[banded]),
                               -PAD, join_style="mitre")
        c = inner_centres(zones)
        tabs = [lay.strips[s].tab for s in banded.tolist()]
        size, angle = _fit_text(zones, c, tabs, NAME_SIZE)
        for s, xy, tab, z, a in zip(banded.tolist(), c, tabs, size.tolist(), angle.tolist()):
            if z >= MIN_CAP:
                texts[s].append(centred_text(xy, tab, z, a))
    return texts


def _place(lay: _Tiles, wanted, taken):
    """(texts, plates, plate fills) per strip for its ``wanted`` (tile, text, largest size)
    labels: each fitted into its tile; one that does not reach ``MIN_CAP`` there, or lies on
    something in its ``taken``, is spread over its neighbouring tiles on a plate of its tile's
    fill, clear of ``taken`` and of the labels placed before it. Each strip's cramped labels go
    one at a time, the strips' together."""
    strips = lay.strips
    flat = [(s, i, text, high) for s, w in enumerate(wanted) for i, text, high in w]
    out = [([], [], []) for _ in strips]
    if not flat:
        return out
    owner, tile, text, high = (list(v) for v in zip(*flat))
    at = lay.first[owner] + np.array(tile)
    size, angle = _fit_text(lay.regions[at], lay.centres[at], text, np.array(high))
    ink = [text_colour_on(strips[s].fills[i]) for s, i in zip(owner, tile)]
    texts = centred_texts(lay.centres[at], text, size, angle, ink)
    boxes = text_boxes(texts)
    pairs = [(k, g) for k, s in enumerate(owner) for g in taken[s]]
    clash = np.zeros(len(flat), dtype=bool)
    if pairs:
        k, g = zip(*pairs)
        clash[np.asarray(k)[shapely.intersects(boxes[list(k)], np.array(g, dtype=object))]] = True
    queues: list[list[int]] = [[] for _ in strips]
    for k in np.flatnonzero((size < MIN_CAP) | clash).tolist():  # the few cramped labels
        queues[owner[k]].append(k)
    mine = [[] for _ in strips]
    for k, s in enumerate(owner):
        mine[s].append(k)
    for r in range(max(map(len, queues))):  # the first cramped label of every strip, ...
        ks = [q[r] for q in queues if len(q) > r]
        ss = [owner[k] for k in ks]
        around = np.full((len(ks), 3), None, dtype=object)
        for row, k in enumerate(ks):
            s, i = owner[k], tile[k]
            near = lay.first[s] + np.arange(max(i - 1, 0), min(i + 2, len(strips[s].tiles)))
            around[row, :len(near)] = lay.tiles[near]
        wide = _once(lambda a, o: shapely.intersection(shapely.union_all(a, axis=1), o), around,
                     lay.outlines[ss])  # congruent strips share their tiles and outlines
        blocked = [[g for g in (lay.bands[s], *taken[s], *out[s][1]) if g is not None]
                   + [boxes[j] for j in mine[s] if j != k and texts[j].size >= MIN_CAP]
                   for k, s in zip(ks, ss)]
        flat = np.array([g for b in blocked for g in b], dtype=object)
        of = np.repeat(np.arange(len(blocked)), [len(b) for b in blocked])
        box, room = shapely.bounds(flat), shapely.bounds(wide)[of]
        near = ((box[:, :2] <= room[:, 2:] + PAD) & (room[:, :2] <= box[:, 2:] + PAD)).all(axis=1)
        rows = np.flatnonzero(np.bincount(of[near], minlength=len(blocked)))  # what reaches the
        if len(rows):  # tiles' boxes: the rest of the strip is far
            keep_out = shapely.buffer(shapely.geometrycollections(
                flat[near], indices=np.searchsorted(rows, of[near])), PAD)
            wide[rows] = shapely.difference(wide[rows], keep_out)
        wide = shapely.buffer(wide, -PAD - PLATE, join_style="mitre")
        zone = shapely.intersection(wide, _once(lambda t: shapely.buffer(t, 2 * MIN_CAP),
                                                lay.tiles[at[ks]]))
        inner = inner_centres(zone)
        full = ~shapely.is_empty(zone)
        mid = np.zeros_like(inner)
        mid[full] = shapely.get_coordinates(shapely.centroid(zone[full]))
        spots = [np.vstack([c, m, (c + m) / 2]) if f else c[None]
                 for c, m, f in zip(inner, mid, full.tolist())]
        row_of = np.repeat(np.arange(len(ks)), [len(p) for p in spots])
        spots = np.vstack(spots)
        words = [text[ks[row]] for row in row_of]
        z, a = np.zeros(len(spots)), np.zeros(len(spots))
        hope = _may_reach(wide, row_of, spots, words, MIN_CAP)
        z[hope], a[hope] = _fit_text(wide[row_of[hope]], spots[hope],
                                     [w for w, h in zip(words, hope.tolist()) if h], MIN_CAP)
        best = [pick[int(np.argmax(snap(z[pick])))] for pick in
                np.split(np.arange(len(z)), np.cumsum(np.bincount(row_of))[:-1])]
        done = [(k, b) for k, b in zip(ks, best) if z[b] >= MIN_CAP - 1e-9]
        if done:
            k, b = (list(v) for v in zip(*done))
            now = centred_texts(spots[b], [text[j] for j in k], z[b], a[b], [ink[j] for j in k])
            new = text_boxes(now)
            for j, t, box, plate in zip(k, now, new, shapely.buffer(new, PLATE,
                                                                    join_style="mitre")):
                texts[j], boxes[j] = t, box
                out[owner[j]][1].append(plate)
                out[owner[j]][2].append(strips[owner[j]].fills[tile[j]])
    for k, s in enumerate(owner):
        out[s][0].append(texts[k])
    return out


def _once(op, *columns):
    """``op(*columns)`` (a vectorised operation on object arrays, a row per item; a column may
    be 2-D) worked out once per distinct row of the same objects."""
    ids = np.column_stack([np.array([id(g) for g in np.ravel(c)], dtype=np.int64).reshape(
        len(c), -1) for c in columns])
    _, first, back = np.unique(ids, axis=0, return_index=True, return_inverse=True)
    return op(*(c[first] for c in columns))[back.reshape(-1)]


def arrow_polygon(tip, direction, length: float) -> shapely.Polygon:
    """A filled arrow of ``length`` mm ending at ``tip``, pointing along ``direction``."""
    d = np.asarray(direction, dtype=float)
    d = d / max(np.hypot(*d), 1e-12)
    n = np.array([-d[1], d[0]])
    t = np.asarray(tip, dtype=float)
    w, head = 0.12 * length, 0.4 * length
    pts = [t, t - head * d + 0.3 * length * n, t - head * d + w * n, t - length * d + w * n,
           t - length * d - w * n, t - head * d - w * n, t - head * d - 0.3 * length * n]
    return shapely.Polygon(pts)


def unit_arrows(directions) -> np.ndarray:
    """(n, 7, 2) the corners of an arrow 1 long centred on the origin, pointing along each
    of ``directions`` (n, 2)."""
    ring = np.asarray(arrow_polygon((0.5, 0.0), (1.0, 0.0), 1.0).exterior.coords)[:-1]
    d = np.asarray(directions, dtype=float).reshape(-1, 2)
    d = d / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-12)[:, None]
    c, s = d[:, :1], d[:, 1:]
    return np.stack([c * ring[:, 0] - s * ring[:, 1], s * ring[:, 0] + c * ring[:, 1]], axis=-1)


def _may_reach(regions, of, centres, texts, size: float) -> np.ndarray:
    """(n,) False where text i centred on ``centres[i]`` cannot reach cap height ``size`` in
    ``regions[of[i]]`` at any angle: the centre lies outside, or nearer the edge than the
    circle a text box of that size holds (half its height or width, the smaller)."""
    inside = shapely.contains_xy(regions[of], centres[:, 0], centres[:, 1])
    room = np.zeros(len(of))
    if inside.any():
        with np.errstate(all="ignore"):  # a degenerate edge's distance: NaN, kept below
            room[inside] = shapely.distance(shapely.boundary(regions)[of[inside]],
                                            shapely.points(centres[inside]))
    box = unit_corners(texts)
    least = np.minimum(box[:, 1, 0] - box[:, 0, 0], box[:, 2, 1] - box[:, 1, 1])  # shorter side
    return inside & ~(2.0 * room < size * least * (1.0 - 1e-6))


def _fit_text(regions, centres, texts, high):
    """(size, angle) of the largest fit of every text in its region, along or across the strip
    (cap heights below ``MIN_CAP`` are kept: the caller reports them)."""
    n = len(texts)
    if n == 0:
        return np.zeros(0), np.zeros(0)
    reps = len(ANGLES)
    shapes = turn(unit_corners(texts)[None], np.asarray(ANGLES)[:, None, None]).reshape(-1, 4, 2)
    fits = largest_fit(np.tile(np.asarray(regions, dtype=object), reps), shapes,
                       np.tile(np.asarray(centres), (reps, 1)), 0.2,
                       np.tile(np.broadcast_to(np.asarray(high, float), (n,)), reps))
    sizes = np.nan_to_num(fits.reshape(reps, n).T, nan=0.0)
    pick = snap(sizes).argmax(axis=1)  # the first angle of equal sizes
    return sizes[np.arange(n), pick], np.asarray(ANGLES)[pick]
