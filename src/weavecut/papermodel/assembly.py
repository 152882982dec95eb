"""The two pages a maker reads before cutting: the assembly sheet and the weaving steps.

The assembly sheet shows the finished pattern at the largest scale that fits, each strand's ID at
both ends and every few tiles along it (inside its own tiles, sized to fit), and a label on a
white box with a leader line where a tile is too small; the strands it finds no room for are
named on a page of their own (:func:`.crossings.id_pages`). The weaving page turns the paper's
section 5.2 experience into numbered steps with small diagrams of the weave growing.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..layout.contrast import text_colour_on
from ..layout.drawing import Layer, Polylines, Sheet, Style, Text, polygons_from_shapely
from ..layout.labels import (
    MIN_CAP,
    centred_text,
    inner_centres,
    largest_fit,
    text_box,
    unit_boxes,
)
from ..weave.model import Weave
from ..text import counted
from ..numeric import median
from .crossings import DOT, callout_shapes, crossing_label, crossing_meaning, too_small
from .pages import GAP, GLUE_MARKS, page_layers, page_span
from .modules import copy_letter
from .pattern import label_spots, pattern
from .strip_labels import unit_arrows
from .plates import Obstacles, free_spot
from .symmetry import rotate, tile_centres
from .wording import LINE, PRINTED, TEXT, Words, page_index, paragraphs

ALONG = 6  # an extra ID every this many own tiles along a strand


def finished_size(weave: Weave, book) -> np.ndarray:
    """(width, height) in mm of the woven model as printed at ``book``'s scale."""
    return np.ptp(weave.mesh.vertices, axis=0) * book.scale


def assembly_sheet(weave: Weave, book, tile_size: float, turn: float, title: str,
                   total: int, crossings=(), words: Words = PRINTED
                   ) -> tuple[Sheet, int, list[tuple[int, int]]]:
    """(page 1, how many of ``crossings`` found no room, (strand, its largest own tile) of every
    strand it names nowhere): what to print (or cut), where each strip is, and the finished
    pattern with IDs; with ``crossings`` (tile, strand on top, strand below) those the strips
    leave unnamed are called out on it too (:mod:`.crossings`); ``words`` name what the maker
    holds."""

    plan, area = book.plan, book.area.plain
    k, m = plan.k, plan.copies.shape[1]
    x0, y0, x1, y1 = area.box
    size_mm = finished_size(weave, book)
    strips = page_span(book.strip_pages, short=True)
    copies = (f": {k} copies (A-{copy_letter(k - 1)}) of a module of {counted(m, 'strip')}"
              + (f" + {counted(len(plan.extras), 'extra')} (X)" if len(plan.extras) else "")
              + f"; copy j is the module turned by j x {360 / k:g} deg" if k > 1
              else ", one strip each")  # no turn maps the pattern onto itself: no copies
    lines = [f"{counted(weave.n_strands, 'strand')}{copies}. Finished model about "
             f"{size_mm[0] / 10:.1f} x {size_mm[1] / 10:.1f} cm, octagons {tile_size:.1f} mm "
             f"across.{words.scale}"]
    if words.sources is not None:
        lines.append(words.sources(book) if callable(words.sources) else words.sources)
    elif book.layout == "module" and k > 1:
        turns = "; ".join(f"print {j + 1} = copy {copy_letter(j)}: turned by {j * 360 / k:g} deg"
                          for j in range(k))
        lines.append(f"Print the strip pages ({strips}) {k} times, once per direction, and write "
                     f"the copy letter on the back of each strip: {turns}. Where each strip "
                     f"is: {page_index(book)}.")
    else:
        lines.append(f"Print the strip pages once ({strips}). Where each strip is: "
                     + page_index(book) + ".")
    lines.append(words.ids)
    shared = book.id_pages and book.id_pages == book.callout_pages  # one sentence for both
    if book.id_pages and not shared:
        lines.append(f"The strands this page has no room to name are named on "
                     f"{page_span(book.id_pages)}.")
    if crossings:
        lines.append(f"{too_small(len(crossings))} ({words.unnamed_mark}): called out below, "
                     f"{crossing_meaning(plan.labels, crossings[0])}.")
    elif book.callout_pages:
        lines.append("Crossings too small to carry a name on their strips"
                     + (", and the strands this page has no room to name," if shared else "")
                     + f" are called out on {page_span(book.callout_pages)}.")
    texts, bottom = paragraphs(lines, x0, y1, x1 - x0)
    box = (x0, y0, x1, bottom - GAP)
    on_sheet, fit, paint, fills = pattern(weave, turn, box, book.colours)
    centres = label_spots(on_sheet)
    ids, boxes, leaders, arrows, obstacles, found = _strand_labels(weave, book, on_sheet,
                                                                   centres, fills, box)
    called, at, size = [], [], tile_mm(on_sheet)
    for tile, over, under in crossings:  # callouts
        spot = _crossing_spot(on_sheet[tile], obstacles)
        placed = None if spot is None else free_spot(
            spot, crossing_label(plan.labels, over, under), obstacles, shapely.box(*box), size,
            lead=DOT)  # a callout's plate off its dot, with a leader to it
        if placed is not None:
            called.append((placed[0], placed[1], np.asarray(placed[2].coords)))
            at.append(spot)
            obstacles += [placed[1], shapely.buffer(placed[2], 0.3), shapely.buffer(
                shapely.Point(spot), DOT)]
    callouts, named = callout_shapes(called, at) if called else ([], [])
    note = f"pattern drawn at {100 * fit.scale / book.scale:.0f} % of {words.drawn}"
    texts.append(Text(x1, y0 - GAP - TEXT, note, TEXT, "end"))
    shapes = [paint]
    if boxes:
        shapes.append(polygons_from_shapely(boxes, Style("#333333", 0.15, "#ffffff")))
    if leaders:
        coords = np.concatenate(leaders)
        shapes.append(Polylines(coords, np.arange(0, len(coords) + 1, 2, dtype=np.int64),
                                Style("#000000", 0.2)))
    shapes += [polygons_from_shapely(a, Style(None, 0.0, ink)) for ink, a in sorted(arrows.items())]
    layers = [Layer("pattern", "paint", (*shapes, *callouts)), Layer("ids", "label", tuple(ids)),
              Layer("crossings", "label", tuple(named)), Layer("notes", "label", tuple(texts))]
    layers += page_layers(area, title, "Assembly sheet: the finished pattern with every "
                          "strand's ID" + (" (copy letter + number)" if k > 1 else ""), 1, total,
                          book.colours[int(plan.copies[0, 0])] if m else "#3e9fb0",
                          legend=words.legend, cut=words.cut_line)
    area_of = shapely.area(on_sheet)
    unnamed = [(s, max(_own_tiles(weave, s), key=lambda t: (area_of[t], -t)))
               for s in range(weave.n_strands) if s not in found]  # strands, not mesh elements
    return (Sheet(area.width, area.height, tuple(layers), "page 1: assembly"),
            len(crossings) - len(called), unnamed)


def _own_tiles(weave: Weave, s: int) -> list[int]:
    """The tiles where strand ``s`` lies on top."""
    visits, own = weave.strand(s)
    return [int(t) for t in visits[own]]


def tile_mm(on_sheet) -> float:
    """A typical tile's size on the sheet (mm): the root of the median tile area."""
    return float(np.sqrt(median(shapely.area(on_sheet))))


def _strand_labels(weave: Weave, book, on_sheet, centres, fills, box):
    """IDs at both ends of every strand and every ``ALONG`` own tiles, inside own tiles where
    they fit; an end that has no room gets its ID on a white box with a leader line, unless
    the strand is short (``ALONG`` own tiles or fewer: both ends in view of one ID) and its ID
    is already on it or on a box (one box, not two side by side). Returns (IDs, white boxes,
    leader lines, arrows by ink, everything later labels keep clear of, the strands named)."""
    plan = book.plan
    regions = shapely.buffer(on_sheet, -0.4, join_style="mitre")
    across = tile_mm(on_sheet)
    wanted, order, short = [], [], set()  # (tile, strand, end?) per candidate
    own_count: dict[int, int] = {}  # own tiles per strand
    for s in range(weave.n_strands):  # strands, not mesh elements
        visits, own = weave.strand(s)
        if plan.reversed[s]:
            visits, own = visits[::-1], own[::-1]
        mine = visits[own]
        own_count[s] = len(mine)
        if len(mine) <= ALONG:
            short.add(s)
        picks = {0: True, len(mine) - 1: True}
        picks.update({i: False for i in range(ALONG, len(mine) - ALONG // 2, ALONG)})
        for i, end in sorted(picks.items()):
            wanted.append((int(mine[i]), s, end))
            order.append(0 if end else 1)
    tiles = np.array([w[0] for w in wanted], dtype=np.int64)
    text = [plan.labels[w[1]] for w in wanted]
    size = largest_fit(regions[tiles], unit_boxes(text, np.zeros(len(text))), centres[tiles],
                       MIN_CAP, 3.5)
    ids, taken, boxes, leaders = [], [], [], []
    arrow_tiles: dict[int, tuple] = {}
    missing = []
    used, named = set(), set()  # tiles taken; short strands whose ID is placed or boxed
    for c in np.lexsort((np.arange(len(wanted)), order)).tolist():  # candidates
        t, s, end = wanted[c]
        if t in used:
            continue
        if np.isfinite(size[c]):
            used.add(t)
            label = centred_text(centres[t], text[c], float(size[c]), 0.0,
                                 text_colour_on(fills[t]))
            ids.append(label)
            taken.append(text_box(label))
            named.add(s)
        elif end:
            missing.append((t, s, text[c]))
    # arrows: the second own tile of every strand, when free
    for s in range(weave.n_strands):  # strands, not mesh elements
        visits, own = weave.strand(s)
        if plan.reversed[s]:
            visits, own = visits[::-1], own[::-1]
        mine = visits[own]
        free = [int(t) for t in mine[1:-1] if int(t) not in used]
        if free:
            t = free[0]
            i = int(np.flatnonzero(visits == t)[0])
            d = centres[visits[min(i + 1, len(visits) - 1)]] - centres[visits[max(i - 1, 0)]]
            arrow_tiles[t] = d
            used.add(t)
    ts = list(arrow_tiles)
    unit = unit_arrows([arrow_tiles[t] for t in ts])
    length = largest_fit(regions[ts], unit, centres[ts], 1.5, 0.6 * across) if ts else []
    arrows: dict[str, list] = {}
    for t, u, z in zip(ts, unit, list(length)):
        if np.isfinite(z):
            arrows.setdefault(text_colour_on(fills[t]), []).append(
                shapely.Polygon(u * z + centres[t]))
    obstacles = Obstacles(taken + [a for v in arrows.values() for a in v])
    frame = shapely.box(*box)
    # leader lines: first a box for every strand not named yet, then the other ends of long
    # strands (a short strand's one ID is in view of both its ends)
    first, rest, seen = [], [], set(named)
    for m in missing:  # ends
        (rest if m[1] in seen else first).append(m)
        seen.add(m[1])
    first.sort(key=lambda m: own_count[m[1]])  # the shortest first: the fewest tiles to point at
    def place(t, s, label, **search):
        spot = free_spot(centres[t], label, obstacles, frame, across, **search)
        if spot is not None:
            named.add(s)
            text_at, plate, leader = spot
            ids.append(text_at)
            boxes.append(plate)
            obstacles.extend([plate, shapely.buffer(leader, 0.3)])
            leaders.append(np.asarray(leader.coords))

    for t, s, label in first + rest:
        if not (s in short and s in named):  # else its one ID is placed
            place(t, s, label)
    for t, s, label in first + rest:  # a strand still unnamed: a finer, wider search
        if s not in named:
            place(t, s, label, step=7.5, reach=16.0)
    return ids, boxes, leaders, arrows, obstacles, named


def _crossing_spot(tile, obstacles):
    """Where a callout's dot goes in ``tile``: the centre of the largest circle in the part of
    the tile (shrunk by 0.4 mm) where the dot keeps 0.3 mm clear of the labels, arrows and
    leaders already there (an ID's leader often ends in the same small tile), or None if none
    is left."""
    tile = shapely.make_valid(tile, method="structure", keep_collapsed=False)
    near = [o for o in obstacles if o.intersects(tile)]
    free = shapely.buffer(tile, -0.4, join_style="mitre")
    if near:
        free = shapely.difference(free, shapely.buffer(shapely.union_all(near), DOT + 0.3))
    return None if free.is_empty else inner_centres([free])[0]


def weaving_steps(weave: Weave, book, turn: float,
                  words: Words = PRINTED) -> tuple[list[str], list[np.ndarray]]:
    """(numbered steps, groups of strands in the order they are woven in), ``words`` naming
    what the maker holds."""
    plan = book.plan
    k = plan.k
    centres = tile_centres(weave)
    centre = plan.symmetry.centre
    glue = any(p.glue is not None for _, p in book.pieces)
    ids = plan.labels
    steps = [words.need, words.cut]
    if any(p.flap is not None for _, p in book.pieces):
        steps.append(words.tab)
    if any(p.left_out for _, p in book.pieces):
        from .crossings import crossing_meaning, left_out_crossings
        first = left_out_crossings(weave, plan, [p for _, p in book.pieces], book.layout)[0]
        steps.append(words.unnamed.format(where=page_span(book.callout_pages or [1]),
                                          meaning=crossing_meaning(ids, first)))
    if glue:
        name, _, part = next(p.label for _, p in book.pieces if p.glue is not None).partition(" ")
        n = part.partition("/")[2]
        mark = GLUE_MARKS.get(book.layout, "{}")
        steps.append(words.glue.format(name=name, n=n, one=mark.format(1), two=mark.format(2)))
    if k == 4:
        heads = plan.copies
        warp = np.concatenate([heads[0], heads[2]])
        weft = np.concatenate([heads[1], heads[3], plan.extras])
        y = np.array([_mean_y(weave, centres, s, turn) for s in weft.tolist()])
        weft = weft[np.argsort(-y, kind="stable")]
        pairs = [weft[i:i + 2] for i in range(0, len(weft), 2)]
        order = "; ".join("+".join(ids[s] for s in p) for p in pairs)
        steps += [
            "Lay page 1 in front of you: it is turned by 45 degrees, so the strands run up-down "
            "(the warp: copies A and C) and left-right (the weft: copies B and D).",
            f"Warp: lay the A and C strips side by side on the cardboard, {words.face_up}, in "
            "the order page 1 shows, arrows as on page 1. Tape the top end of each one down."
            + (" The diagrams below colour each copy in a hue of its own (A and C the warp, B "
               "and D the weft); the strips are printed in the module's colours."
               if book.diagram_colours else ""),
            "Weft: take the next two B or D strips from the top and weave them across the warp "
            f"together, one beside the other: {words.weft_under}. Push the "
            "pair up against the strips above. Do not twist two strips round each other first "
            "and add the rest later: that does not hold.",
            f"Repeat step {len(steps) + 3} until every strip is in. Weft pairs from the top: "
            f"{order}.",
        ]
        groups = [warp] + pairs
    else:
        dist = np.array([np.hypot(*(centres[weave.strand(s)[0]] - centre).T).min()
                         for s in range(weave.n_strands)])
        orbit_of = np.full(weave.n_strands, -1)
        for i in range(plan.copies.shape[1]):  # module strands
            orbit_of[plan.copies[:, i]] = i
        orbit_of[plan.extras] = plan.copies.shape[1] + np.arange(len(plan.extras))
        key = np.array([dist[orbit_of == o].min() for o in range(orbit_of.max() + 1)])
        size = k if k >= 3 else 3
        if k >= 3:
            groups = [np.flatnonzero(orbit_of == o) for o in np.argsort(key, kind="stable")]
        else:
            flat = np.argsort(dist, kind="stable")
            groups = [flat[i:i + size] for i in range(0, len(flat), size)]
        order = "; ".join(f"{n}: " + ", ".join(ids[s] for s in g)
                          for n, g in enumerate(groups, start=1))
        steps += [
            (f"This pattern has {k} directions{'' if k % 4 == 0 else ' and no right angles'}, "
             "so it is best woven by two people: one holds the strands already joined while the "
             "other threads the next. " if k >= 3 else "")
            + "Work from the centre outwards on the cardboard, page 1 beside you.",
            "Start with the strands of group 1 (they cross the centre): lay them as page 1 shows "
            f"and weave them through each other. {words.strip_under} Tape or clip every "
            "crossing as you make it so the first strands cannot slide apart.",
            "Add the next group: weave each new strand through every strand it crosses that is "
            "already in, then tape its ends. Join every strand of a group to its neighbours "
            "before starting the next, so the structure holds.",
            f"Groups, centre outwards: {order}.",
        ]
    steps += ["Close the border: check every crossing against page 1, then put a dot of glue "
              "under each strand end at the edge and press it onto the strip below it. Let it "
              "dry, then remove the tape.",
              "No glue anywhere else: a woven model holds by its crossings."]
    return steps, groups


def _mean_y(weave, centres, s, turn) -> float:
    visits, _ = weave.strand(s)
    return float(rotate(centres[visits], turn, weave.mesh.vertices.mean(axis=0))[:, 1].mean())


def weaving_sheet(weave: Weave, book, turn: float, title: str, total: int,
                  words: Words = PRINTED) -> Sheet:
    """Page 2: how to weave, as numbered steps, with diagrams of the weave growing."""
    area = book.area.plain
    x0, y0, x1, y1 = area.box
    steps, groups = weaving_steps(weave, book, turn, words)
    texts, bottom = paragraphs(steps, x0, y1, x1 - x0, numbered=True)
    picks = sorted({0, 1, len(groups) // 2, len(groups) - 1}) if len(groups) > 1 else [0]
    n = len(picks)
    cols = 2 if n > 2 else n
    rows = int(np.ceil(n / cols))
    cell_w = (x1 - x0 - GAP * (cols - 1)) / cols
    cell_h = (bottom - GAP - y0 - GAP * (rows - 1)) / rows
    shapes = []
    shown = np.zeros(weave.n_strands, dtype=bool)
    done = 0
    for p, g in enumerate(picks):
        for grp in groups[done:g + 1]:
            shown[grp] = True
        done = g + 1
        r, c = divmod(p, cols)
        bx = x0 + c * (cell_w + GAP)
        by = bottom - GAP - (r + 1) * cell_h - r * GAP
        caption = (f"after group {g + 1}" if book.plan.k != 4 else
                   ("warp laid" if g == 0 else f"after weft pair {g}"))
        texts.append(Text(bx, by + cell_h - TEXT, caption, TEXT))
        if cell_h - LINE > 10:
            box = (bx, by, bx + cell_w, by + cell_h - LINE)
            shapes.append(pattern(weave, turn, box, book.diagram_colours or book.colours,
                                  shown.copy())[2])
    layers = [Layer("diagrams", "paint", tuple(shapes)), Layer("steps", "label", tuple(texts))]
    layers += page_layers(area, title, "How to weave: numbered steps; the diagrams show the "
                          "weave growing", 2, total, legend=words.legend, cut=words.cut_line)
    return Sheet(area.width, area.height, tuple(layers), "page 2: weaving")

