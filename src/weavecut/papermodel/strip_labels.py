"""Labels on a paper strip: its ID, the names in its under tiles, direction arrows, label tabs.

Every label is fitted into its tile (less ``PAD``) as large as it goes up to a cap, or spread
over the neighbouring tiles on a plate; an ID that no own tile holds goes on a label tab cut
with the strip (``label_flap``). ``strips`` makes the unlabelled strips.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import shapely
from numpy.typing import NDArray

from ..numeric import affine_matrix, dot, snap, transform
from ..layout.contrast import text_colour_on
from ..layout.drawing import Text
from ..layout.labels import (
    MIN_CAP,
    centred_text,
    inner_centres,
    largest_fit,
    text_box,
    unit_box,
)
from .strips import Strip


PAD = 0.3  # mm between a label and its tile's edge
PLATE = 0.4  # mm a label's plate reaches beyond its text
ANGLES = tuple(np.arange(0.0, 180.0, 15.0).tolist())  # label turns tried (strip frame)
ID_SIZE = 6.0  # largest cap height of a strip's ID (mm)
NAME_SIZE = 3.0  # largest cap height of the ID printed in an under tile (well below an ID)


def label_strip(strip: Strip, tile_mm: float) -> Strip:
    """``strip`` with its labels: its ID in its largest own tile (and in the other half of a
    long strip), the ID of the strand on top in every under tile, and direction arrows in own
    tiles that hold no ID. Every label is fitted into its tile (less ``PAD``) as large as it goes
    up to a cap, or spread over the neighbouring tiles on a plate; a name that still cannot
    reach ``MIN_CAP`` is left out (the assembly sheet shows that crossing); an ID no own tile
    holds goes on a label tab (:func:`label_flap`), or is kept at the size that fits (so the
    caller can name the tile size that works)."""
    band = None if strip.glue is None else shapely.union_all(strip.glue)
    regions = shapely.intersection(strip.tiles, strip.outline)
    if band is not None:
        regions = shapely.difference(regions, band)
    regions = shapely.buffer(regions, -PAD, join_style="mitre")
    centres = inner_centres(regions)
    own = np.flatnonzero(strip.over & ~shapely.is_empty(regions))
    under = np.flatnonzero(~strip.over & ~shapely.is_empty(regions))
    # the strip's ID: largest own tile; a long strip also in the largest of its other half
    id_tiles: list[int] = []
    # the first tile of a piece with a mark keeps its room for the mark
    cand = own[own != 0] if strip.mark and (own != 0).any() else own
    if len(cand):
        id_size, _ = _fit_text(regions[cand], centres[cand],
                               [strip.label.partition(" ")[0]] * len(cand), ID_SIZE)
        rank = np.lexsort((np.arange(len(cand)), -snap(shapely.area(regions[cand]))))
        first = rank[0] if id_size[rank[0]] >= MIN_CAP else int(np.argmax(snap(id_size)))
        id_tiles = [int(cand[first])]
        if len(cand) >= 6:
            half = cand > cand[first] if cand[first] < cand[len(cand) // 2] else cand < cand[first]
            id_tiles += [int(cand[r]) for r in rank.tolist() if half[r]
                         and id_size[r] >= MIN_CAP][:1]
    # IDs first (spread onto the neighbours if they must), a piece's number ("2/3") in another
    # own tile, then the names round them
    name, _, part = strip.label.partition(" ")
    wanted = [(i, name, ID_SIZE) for i in id_tiles]
    if part and id_tiles:
        spare = [int(cand[r]) for r in rank.tolist() if int(cand[r]) not in id_tiles]
        if spare:
            wanted.append((spare[0], part, NAME_SIZE))
        else:  # one own tile: it says both ("B 2/3")
            wanted[0] = (id_tiles[0], strip.label, ID_SIZE)
    if strip.mark:
        wanted.append((0, strip.mark, NAME_SIZE))
    texts, plates, plate_fills = _place(strip, wanted[:1], regions, centres, band)
    if len(wanted) > 1:
        more = _place(strip, wanted[1:], regions, centres, band,
                      [*plates, *(text_box(t) for t in texts)])
        texts += more[0]
        plates = np.array([*plates, *more[1]], dtype=object)
        plate_fills += more[2]
    id_wanted = wanted
    taken = [*plates, *(text_box(t) for t in texts)]
    if taken:
        regions = shapely.difference(regions, shapely.buffer(shapely.union_all(taken), PAD))
        centres = inner_centres(regions)
    wanted = [(int(i), strip.names[i], NAME_SIZE) for i in under
              if strip.names[i] and not shapely.is_empty(regions[i])]
    more, more_plates, more_fills = _place(strip, wanted, regions, centres, band, taken)
    texts += more
    plates = np.array([*plates, *more_plates], dtype=object)
    plate_fills += more_fills
    wanted = id_wanted + wanted
    # an under tile too small for the name (a border tile at 23 cm): the assembly sheet shows
    # that crossing, the strip leaves it out
    left_out = tuple(w[0] for t, w in zip(texts, wanted) if t.size < MIN_CAP
                     and w not in id_wanted)
    texts = [t for t, w in zip(texts, wanted) if t.size >= MIN_CAP or w in id_wanted]
    if len(plates):
        regions = shapely.difference(regions, shapely.buffer(shapely.union_all(plates), PAD))
    # arrows: the first and the last own tile without an ID, pointing the way the strand goes
    arrows = []
    free = [i for i in own.tolist() if i not in id_tiles and not shapely.is_empty(regions[i])]
    ends = sorted({free[0], free[-1]}) if free else []
    if ends:
        pts = np.array([(c.x, c.y) for c in shapely.centroid(strip.tiles)])
        dirs = [pts[min(i + 1, len(pts) - 1)] - pts[max(i - 1, 0)] for i in ends]
        unit = [arrow_polygon((0.5, 0.0), (1.0, 0.0), 1.0) for _ in ends]
        unit = [shapely.transform(u, transform(turn_to(d))) for u, d in zip(unit, dirs)]
        length = largest_fit(regions[ends], unit, centres[ends], 2.0, 0.45 * tile_mm)
        arrows = [shapely.transform(u, lambda xy, z=z, c=centres[i]: xy * z + c)
                  for u, z, i in zip(unit, length.tolist(), ends) if np.isfinite(z)]
    if texts and texts[0].size < MIN_CAP and id_wanted:  # no own tile reads: a label tab
        tabbed = label_flap(strip, texts[0].text)
        if tabbed is not None:
            strip, texts[0] = tabbed
    if band is not None:  # "glue" on the band, where it fits
        zone = shapely.buffer(shapely.intersection(band, strip.outline), -PAD, join_style="mitre")
        c = inner_centres([zone])
        size, angle = _fit_text([zone], c, [strip.tab], NAME_SIZE)
        if size[0] >= MIN_CAP:
            texts.append(centred_text(c[0], strip.tab, float(size[0]), float(angle[0])))
    return replace(strip, texts=tuple(texts), arrows=np.array(arrows, dtype=object),
                   plates=plates, plate_fills=plate_fills, left_out=left_out)


FLAP_MARGIN = 0.6  # mm between a label tab's text and its edges
FLAP_STEP = 1.5  # mm, the least step between a label tab's corner and its edge's end
FLAP_REACH = 1.5  # a label tab's base may reach past its edge (along its line) up to this share
END_FACING = 0.9  # cosine: a strand's end edge faces the way the strand leaves its last tile


def label_flap(strip: Strip, text: str) -> tuple[Strip, Text] | None:
    """(``strip`` with a label tab, the tab's ``text`` at ``MIN_CAP``), or None where no end
    edge takes one. The tab is a rectangle on a free end edge of the strip's first or last tile
    (the edge the strand leaves by, shared with no other tile of the strip; not a glue band's),
    just large enough for the text along or across the edge plus ``FLAP_MARGIN``, outside every
    tile of the strip; the smallest tab that fits wins."""
    x0, y0, x1, y1 = unit_box(text, 0.0).bounds
    along, high = (x1 - x0) * MIN_CAP, (y1 - y0) * MIN_CAP
    n = len(strip.tiles)
    ends = [i for i in sorted({0, n - 1}) if not (strip.glue is not None and i == n - 1)]
    body = shapely.union_all(strip.tiles)
    best = None
    for i in ends:  # two ends
        tile = strip.tiles[i]
        if tile.geom_type != "Polygon":
            continue
        ring = np.asarray(tile.exterior.coords)
        a, b = ring[:-1], ring[1:]
        mid = (a + b) / 2
        length = np.hypot(*(b - a).T)
        unit = (b - a) / np.maximum(length, 1e-12)[:, None]
        normal = np.column_stack([unit[:, 1], -unit[:, 0]])
        centre = np.asarray(tile.centroid.coords[0])
        normal *= np.sign(dot(normal, mid - centre))[:, None]
        others = shapely.union_all(np.delete(strip.tiles, i))
        free = shapely.distance(shapely.points(mid), others) > 1e-6 * max(strip.length, 1.0) \
            if n > 1 else np.ones(len(mid), dtype=bool)
        if n > 1:
            nb = np.asarray(strip.tiles[1 if i == 0 else n - 2].centroid.coords[0])
            away = (centre - nb) / max(float(np.hypot(*(centre - nb))), 1e-12)
            facing = dot(normal, away) >= END_FACING
        else:
            facing = np.ones(len(mid), dtype=bool)
        for e in np.flatnonzero(free & facing).tolist():  # an edge or two
            # text along the edge, or across it: (base on the edge, depth, text angle)
            for base, depth, direction in ((along, high, unit[e]), (high, along, normal[e])):
                base, depth = base + 2 * FLAP_MARGIN, depth + 2 * FLAP_MARGIN
                if base > FLAP_REACH * length[e]:
                    continue
                base = _tab_base(base, float(length[e]))
                p, q = mid[e] - unit[e] * base / 2, mid[e] + unit[e] * base / 2
                flap = shapely.Polygon([p, q, q + normal[e] * depth, p + normal[e] * depth])
                if shapely.intersection(flap, body).area > 1e-6 * flap.area:
                    continue
                if best is None or flap.area < best[0].area - 1e-9:
                    angle = float(np.degrees(np.arctan2(direction[1], direction[0])))
                    best = (flap, shapely.LineString([p, q]), mid[e] + normal[e] * depth / 2,
                            angle)
    if best is None:
        return None
    flap, edge, centre, angle = best
    fill = next((f for f, o in zip(strip.fills, strip.over.tolist()) if o), "#ffffff")
    label = centred_text(centre, text, MIN_CAP, angle, text_colour_on(fill))
    return replace(strip, flap=flap, flap_edge=edge, flap_fill=fill), label


def _tab_base(base: float, edge: float) -> float:
    """A label tab's ``base`` widened so that its corners meet its ``edge``'s ends, or pass them
    by at least ``FLAP_STEP``: no step a cutter's knife tears at."""
    if base <= edge:
        return edge if base > edge - 2 * FLAP_STEP else base
    return max(base, edge + 2 * FLAP_STEP)


def _place(strip: Strip, wanted, regions, centres, band, taken=()):
    """(texts, plates, plate fills) for ``wanted`` (tile, text, largest size) labels: each
    fitted into its tile; one that does not reach ``MIN_CAP`` there, or lies on something in
    ``taken``, is spread over its neighbouring tiles on a plate of its tile's fill, clear of
    ``taken`` and of the labels placed before it."""
    if not wanted:
        return [], np.zeros(0, dtype=object), ()
    idx = np.array([w[0] for w in wanted])
    size, angle = _fit_text(regions[idx], centres[idx], [w[1] for w in wanted],
                            np.array([w[2] for w in wanted]))
    texts = [centred_text(centres[i], t, float(z), float(a), text_colour_on(strip.fills[i]))
             for (i, t, _), z, a in zip(wanted, size, angle)]
    plates, fills = [], []
    clash = shapely.intersects(np.array([text_box(t) for t in texts], dtype=object)[:, None],
                               np.array([*taken, None], dtype=object)[None, :]).any(axis=1)
    for k in np.flatnonzero((size < MIN_CAP) | clash).tolist():  # the few cramped labels
        i, text, _ = wanted[k]
        wide = shapely.intersection(shapely.union_all(strip.tiles[max(i - 1, 0):i + 2]),
                                    strip.outline)
        blocked = [band, *taken, *plates, *(text_box(t) for j, t in enumerate(texts)
                                            if j != k and t.size >= MIN_CAP)]
        blocked = [g for g in blocked if g is not None]
        if blocked:
            wide = shapely.difference(wide, shapely.buffer(shapely.union_all(blocked), PAD))
        wide = shapely.buffer(wide, -PAD - PLATE, join_style="mitre")
        zone = shapely.intersection(wide, shapely.buffer(strip.tiles[i], 2 * MIN_CAP))
        inner = inner_centres([zone])[0]
        mid = shapely.get_coordinates(shapely.centroid(zone)).reshape(-1, 2)[:1]
        spots = np.vstack([inner, mid, (inner + mid) / 2]) if len(mid) else inner[None]
        z, a = _fit_text([wide] * len(spots), spots, [text] * len(spots), MIN_CAP)
        best = int(np.argmax(snap(z)))
        near, z, a = spots[best:best + 1], z[best:best + 1], a[best:best + 1]
        if z[0] >= MIN_CAP - 1e-9:
            texts[k] = centred_text(near[0], text, float(z[0]), float(a[0]),
                                    text_colour_on(strip.fills[i]))
            plates.append(shapely.buffer(text_box(texts[k]), PLATE, join_style="mitre"))
            fills.append(strip.fills[i])
    return texts, np.array(plates, dtype=object), tuple(fills)


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


def turn_to(d) -> NDArray[np.float64]:
    """(3, 3) the turn taking the x axis to the direction ``d``."""
    d = np.asarray(d, dtype=float) / max(float(np.hypot(*d)), 1e-12)
    return affine_matrix(d[0], -d[1], d[1], d[0])


def _fit_text(regions, centres, texts, high: float):
    """(size, angle) of the largest fit of every text in its region, along or across the strip
    (cap heights below ``MIN_CAP`` are kept: the caller reports them)."""
    n = len(texts)
    if n == 0:
        return np.zeros(0), np.zeros(0)
    regions = np.asarray(regions, dtype=object)
    reps = len(ANGLES)
    shapes = [unit_box(t, a) for a in ANGLES for t in texts]
    fits = largest_fit(np.tile(regions, reps), shapes, np.tile(np.asarray(centres), (reps, 1)),
                       0.2, np.tile(np.broadcast_to(np.asarray(high, float), (n,)), reps), 10)
    sizes = np.nan_to_num(fits.reshape(reps, n).T, nan=0.0)
    pick = snap(sizes).argmax(axis=1)  # the first angle of equal sizes
    return sizes[np.arange(n), pick], np.asarray(ANGLES)[pick]
