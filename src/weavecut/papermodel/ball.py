"""The paper model of a woven ball: every strand of a weave on a closed surface unfolded into
strips (:mod:`.unfold`), packed onto pages as the flat models' strips are, after an assembly
sheet with views of the ball from six sides and a page of weaving steps.

Strands are named by letters (A, B, ...); a strip cut into pieces names them "A 1/2", "A 2/2".
Every piece ends with a glue band "glue j" that goes under the tile marked "j" (the first tile
of the next piece, or of the first piece where the loop closes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import shapely

from ..layout.contrast import text_colour_on
from ..layout.drawing import Drawing, Layer, Sheet, Text, polygons_from_shapely
from ..layout.labels import MIN_CAP, centred_text, inner_centres, largest_fit, unit_boxes
from ..layout.weave_figure import tile_rings
from ..surface import face_normals
from ..weave.colour import Palette, strand_colours
from ..weave.model import Weave
from .book import MIN_STRIP, WARN_STRIP, SizeError, StrandBook, strip_sheets
from .packing import pack
from .pages import GAP, PageArea, page_layers, page_span
from .pattern import OUTLINE
from ..numeric import dot, median, snap
from .modules import copy_letter
from .ball_pieces import MIN_FOLD, PageTooSmall, strand_pieces, too_large
from .notches import MIN_CUT, NotchError
from .strip_labels import label_strips
from .strips import Strip, tint
from .unfold import Unfolding, UnfoldError, flatten, unfold
from .wording import TEXT, page_index, paragraphs

GROWING = 4  # views in the row of the ball growing on a one-page guide (two stages, two sides)
PREVIEW, PREVIEW_MARGIN = 200.0, 5.0  # mm: the width of the quick look's two views, margin
# (name, towards the viewer, up): six views, every tile seen head-on in one of them
VIEWS = (("front", (0, 0, 1), (0, 1, 0)), ("right", (1, 0, 0), (0, 1, 0)),
         ("back", (0, 0, -1), (0, 1, 0)), ("left", (-1, 0, 0), (0, 1, 0)),
         ("top", (0, 1, 0), (0, 0, -1)), ("bottom", (0, -1, 0), (0, 0, 1)))


@dataclass(frozen=True)
class BallPlan:
    """What a ball's book says of its strands: their IDs, by strand (a ball has no modules)."""

    labels: tuple[str, ...]


@dataclass(frozen=True, eq=False)
class BallBook(StrandBook):
    """A :class:`StrandBook` of a ball (``plan`` a :class:`BallPlan`) plus what flattening cost.

    Parameters
    ----------
    unfoldings : (S,) every strand's unfolding (mesh units)
    diameter : mm across the finished ball
    non_planarity : (T,) every tile's largest pentagon non-planarity (share of its diameter)
    """

    unfoldings: tuple[Unfolding, ...] = ()
    diameter: float = 0.0
    non_planarity: np.ndarray | None = None

    @property
    def stretch(self) -> float:
        """Largest change of an unfolded edge's length against its length in space (share)."""
        return max(float(np.abs(u.stretch).max()) for u in self.unfoldings)

    def flattening(self) -> dict:
        """The figures ``strands --json`` reports for a ball."""
        return {"diameter_mm": round(self.diameter, 1),
                "largest_edge_change_pct": round(100 * self.stretch, 3),
                "largest_non_planarity_pct": round(100 * float(self.non_planarity.max()), 3),
                "tile_non_planarity_pct": np.round(100 * self.non_planarity, 3).tolist(),
                "pieces": len(self.pieces)}


def radius(weave: Weave) -> float:
    """Largest distance of a vertex from the vertices' mean (mesh units)."""
    v = weave.mesh.vertices
    return float(np.linalg.norm(v - v.mean(axis=0), axis=1).max())


def tile_size_of(weave: Weave) -> float:
    """Median distance across an octagon (farthest corners, in space), mesh units."""
    coords, offsets = tile_rings(weave)
    octs = coords.reshape(-1, 8, 3)
    return float(median(np.linalg.norm(octs[:, :, None] - octs[:, None], axis=-1)
                           .max(axis=(1, 2))))


def diameter_for(weave: Weave, tile_size: float) -> float:
    """The ball's diameter (mm) at which octagons are ``tile_size`` mm across."""
    return tile_size / tile_size_of(weave) * 2 * radius(weave)


def ball_book(weaves: list[Weave], pal: Palette, page=(210.0, 297.0),
              diameter: float | None = None, margin: float = 10.0,
              title: str = "weave-cut strands", tile_size: float = 40.0) -> BallBook:
    """Every strand of ``weaves[-1]`` (a snub weave on a closed surface) as printable strips,
    the ball ``diameter`` mm across (None: octagons ``tile_size`` mm across).

    Raises
    ------
    SizeError when strips would be narrower than 8 mm or a label smaller than 2.5 mm;
    UnfoldError for a surface with a boundary, or a strip that cannot be unfolded onto the page
    """
    weave = weaves[-1]
    if (np.diff(weave.tile_offsets) != 2).any() or not weave.strand_closed.all():
        raise UnfoldError("the strips of a surface in space need a closed surface (every "
                          "strand a loop, every tile an octagon); this one has a boundary")
    area = PageArea(page[0], page[1], margin)
    area.check()
    diameter = diameter_for(weave, tile_size) if diameter is None else diameter
    scale = diameter / (2 * radius(weave))
    tile_mm = tile_size_of(weave) * scale
    colours = strand_colours(weaves, pal)
    labels = tuple(copy_letter(i) for i in range(weave.n_strands))
    flat = flatten(weave)
    unfoldings = tuple(unfold(weave, s, flat) for s in range(weave.n_strands))
    try:
        pieces = [p for u in unfoldings
                  for p in strand_pieces(weave, u, colours, labels, scale, area)]
    except NotchError as exc:  # notches widen with the ball: one this much larger needs none
        raise SizeError(f"{exc} on a {diameter / 10:g} cm ball (scissors need {MIN_CUT:g} mm):"
                        f" use --size {math.ceil(diameter * MIN_CUT / exc.mouth / 10)}cm or "
                        "more") from None
    except PageTooSmall as exc:  # pieces grow with the ball: the largest whose pieces fit
        raise SizeError(too_large(exc.need, diameter, page, margin)) from None
    widths = shapely.minimum_rotated_rectangle(np.concatenate([p.tiles for p in pieces]))
    rect = shapely.get_coordinates(shapely.get_exterior_ring(widths)).reshape(-1, 5, 2)
    sides = np.linalg.norm(rect[:, 1:3] - rect[:, 0:2], axis=-1)
    width = float(median(sides.min(axis=1)))
    if width < MIN_STRIP - 1e-9:
        raise SizeError(f"strips would be {width:.1f} mm wide and tear (paper section 5.2): "
                        f"use --size {math.ceil(diameter * MIN_STRIP / width / 10)}cm or more")
    warnings = () if width >= WARN_STRIP else (
        f"strips are {width:.1f} mm wide: thin strips tear easily; {WARN_STRIP:g} mm or more "
        "is easier to weave",)
    pieces = label_strips(pieces, tile_mm)
    small = min((t.size for p in pieces for t in p.texts), default=MIN_CAP)
    if small < MIN_CAP - 1e-6:
        raise SizeError(f"some labels would be {small:.1f} mm tall on a {diameter / 10:g} cm "
                        f"ball; labels need {MIN_CAP:g} mm: use --size "
                        f"{math.ceil(diameter * MIN_CAP / small / 10)}cm or more")
    x0, y0, x1, y1 = area.box
    places = pack([p.cut for p in pieces], x1 - x0, y1 - y0, GAP, kinds=_kinds(pieces))
    tile_planes = flat.non_planarity[weave.tile_faces].reshape(-1, 2).max(axis=1)

    def book_from(first: int) -> tuple[BallBook, list[Sheet], int]:
        placed, sheets = strip_sheets(pieces, None, area, title, colours, first, places)
        book = BallBook(Drawing((), title), BallPlan(labels), tuple(colours), "ball", placed,
                        tuple(range(first, first + len(sheets))), tuple(range(1, first)), scale,
                        area, width, tile_mm, warnings, unfoldings=unfoldings,
                        diameter=diameter, non_planarity=tile_planes)
        return book, sheets, len(sheets) + first - 1

    # one page of notes, steps and views before the strips when every view keeps its IDs
    # there, else the assembly sheet and the weaving steps on pages of their own
    book, sheets, total = book_from(2)
    guide = (guide_sheet(weave, book, labels, title, total),)
    if guide[0] is None:
        book, sheets, total = book_from(3)
        guide = (assembly_sheet(weave, book, labels, title, total),
                 weaving_sheet(weave, book, labels, title, total))
    return replace(book, drawing=Drawing((*guide, *sheets), title))


def _kinds(pieces: list[Strip]) -> list[int]:
    """Equal numbers for pieces whose outlines agree to 0.01 mm (congruent pieces, which the
    packer nests)."""
    keys = [np.round(shapely.get_coordinates(p.outline), 2).tobytes() for p in pieces]
    index: dict[bytes, int] = {}
    return [index.setdefault(k, len(index)) for k in keys]


def _views(weave: Weave, colours, labels, box, cells, columns: int = 3, rows: int = 2):
    """(painted tiles, fills, IDs, captions): views of the ball in a ``columns`` x ``rows``
    grid inside ``box``, one per cell (caption, towards the viewer, up, shown (S,) bool):
    every tile that faces the viewer in the colour of the strand on top if that strand is
    shown, light where a shown strand passes under a hidden one, white elsewhere."""
    coords, _ = tile_rings(weave)
    rings = coords.reshape(-1, 8, 3) - weave.mesh.vertices.mean(axis=0)
    normals = np.add.reduceat(face_normals(weave.mesh)[weave.tile_faces], weave.tile_offsets[:-1])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    top, under = weave.tile_over, weave.tile_under
    own = np.asarray(colours, dtype=object)[top]
    light = np.array([tint(c) for c in np.asarray(colours)[under]], dtype=object)
    x0, y0, x1, y1 = box
    cell = min((x1 - x0) / columns, (y1 - y0 - rows * (TEXT + 2)) / rows)
    scale = (cell - 2 * GAP) / (2 * radius(weave))
    polys, fills, ids, captions, missing = [], [], [], [], 0
    for k, (name, toward, up, shown) in enumerate(cells):  # six views
        d, u = np.array(toward, float), np.array(up, float)
        r = np.cross(u, d)
        cx = x0 + (k % columns + 0.5) * (x1 - x0) / columns
        cy = y1 - (k // columns) * (cell + TEXT + 2) - cell / 2
        facing = dot(normals, d)
        keep = np.flatnonzero(facing > 0.05)
        keep = keep[np.argsort(snap(dot(rings[keep].mean(axis=1), d)), kind="stable")]  # far first
        shapes = shapely.polygons(np.stack([dot(rings[keep], r), dot(rings[keep], u)], axis=-1)
                                  * scale + [cx, cy])
        fill = np.where(shown[top], own, np.where(shown[under], light, "#ffffff"))[keep]
        polys += shapes.tolist()
        fills += fill.tolist()
        # the strand on top named in every tile that faces the viewer well
        good = (facing[keep] > 0.5) & shown[top[keep]]
        regions = shapely.buffer(shapes[good], -0.4, join_style="mitre")
        at = inner_centres(regions)
        text = [labels[t] for t in top[keep][good].tolist()]
        size = largest_fit(regions, unit_boxes(text, np.zeros(len(text))), at, MIN_CAP, 5.0)
        ids += [centred_text(c, t, float(z), 0.0, text_colour_on(f))
                for c, t, z, f in zip(at, text, size, fill[good].tolist()) if np.isfinite(z)]
        missing += int((~np.isfinite(size)).sum())
        captions.append(Text(cx, cy - cell / 2 - TEXT - 0.5, name, TEXT, "middle"))
    return polys, fills, ids, captions, missing


def _view_layers(weave, colours, labels, box, cells, columns: int = 3,
                 rows: int = 2) -> list[Layer]:
    return _view_shapes(weave, colours, labels, [(box, cells, columns, rows)])[0]


def _view_shapes(weave, colours, labels, grids) -> tuple[list[Layer], int]:
    """(layers, IDs missing): the views of every grid (box, cells, columns, rows) in one set
    of layers, and how many tiles that face the viewer well found no room for their ID."""
    polys, fills, ids, captions, missing = [], [], [], [], 0
    for grid in grids:
        more = _views(weave, colours, labels, *grid)
        for have, new in zip((polys, fills, ids, captions), more):
            have += new
        missing += more[4]
    return [Layer("views", "paint", (polygons_from_shapely(polys, OUTLINE, fills),)),
            Layer("ids", "label", tuple(ids)),
            Layer("captions", "label", tuple(captions))], missing


def ball_preview(weaves: list[Weave], pal: Palette,
                 title: str = "weave-cut strands: preview") -> Drawing:
    """A quick look at a woven ball (``strands --preview``): the front and the back views of
    the assembly sheet, large, every tile in the colour of the strand on top there, with its
    ID; no unfolding, no strips, no pages."""
    weave = weaves[-1]
    labels = tuple(copy_letter(i) for i in range(weave.n_strands))
    every = np.ones(weave.n_strands, dtype=bool)
    side = PREVIEW / 2
    box = (PREVIEW_MARGIN, PREVIEW_MARGIN, PREVIEW_MARGIN + PREVIEW,
           PREVIEW_MARGIN + side + TEXT + 2)
    layers = _view_layers(weave, strand_colours(weaves, pal), labels, box,
                          [(*VIEWS[0], every), (*VIEWS[2], every)], columns=2, rows=1)
    sheet = Sheet(PREVIEW + 2 * PREVIEW_MARGIN, box[3] + PREVIEW_MARGIN, tuple(layers),
                  "preview")
    return Drawing((sheet,), title)


def assembly_sheet(weave: Weave, book: BallBook, labels, title: str, total: int) -> Sheet:
    """Page 1: what to print, where each strip is, and the ball from six sides."""
    area = book.area
    x0, y0, x1, y1 = area.box
    texts, bottom = paragraphs(_notes(weave, book, labels, "Weaving steps: page 2."), x0, y1,
                               x1 - x0)
    every = np.ones(weave.n_strands, dtype=bool)
    layers = _view_layers(weave, book.colours, labels, (x0, y0, x1, bottom - GAP),
                          [(*v, every) for v in VIEWS])
    layers.append(Layer("notes", "label", tuple(texts)))
    layers += page_layers(area, title, "Assembly sheet: the woven ball from six sides, every "
                          "tile with the ID of the strand on top", 1, total, book.colours[0])
    return Sheet(area.width, area.height, tuple(layers), "page 1: assembly")


def _notes(weave: Weave, book: BallBook, labels, steps: str) -> list[str]:
    """The assembly notes: what to print, where each strip is, lengths, what flattening cost,
    and where the weaving ``steps`` are."""
    n = weave.n_strands
    lengths = weave.strand_lengths() * book.scale
    strips = page_span(book.strip_pages, short=True)
    return [f"{n} strands, each a closed loop: {n} strips ({labels[0]}-{labels[-1]}) in "
             f"{len(book.pieces)} pieces. Finished ball {book.diameter / 10:.1f} cm across, "
             f"octagons {book.tile_size:.1f} mm across. Print the strip pages ({strips}) once, "
             "at 100 % (no fit to page).",
             "Where each strip is: " + page_index(book) + ".",
             "Strand lengths (centre line): " + ", ".join(
                 f"{lab} {x / 10:.1f} cm" for lab, x in zip(labels, lengths.tolist())) + ".",
             f"Unfolding bends every pentagon flat: corners up to "
             f"{100 * float(book.non_planarity.max()):.1f} % of its size off its plane, edges "
             f"longer or shorter by at most {100 * book.stretch:.2f} %.",
             "The views show each tile in the colour of the strand on top there, with its "
             f"ID. {steps}"]


def weaving_sheet(weave: Weave, book: BallBook, labels, title: str, total: int) -> Sheet:
    """Page 2: numbered weaving steps, and the ball growing: front and back after a third,
    two thirds and all of the strips are in."""
    area = book.area
    x0, y0, x1, y1 = area.box
    texts, bottom = paragraphs(_steps(book, labels, "the views below (front above, back "
                                      "below) and page 1 show"), x0, y1, x1 - x0, numbered=True)
    cells = [c for side in (VIEWS[0], VIEWS[2]) for c in _stages(weave, labels, side)]
    layers = _view_layers(weave, book.colours, labels, (x0, y0, x1, bottom - GAP), cells)
    layers.append(Layer("steps", "label", tuple(texts)))
    layers += page_layers(area, title, "Weaving steps", 2, total, book.colours[0])
    return Sheet(area.width, area.height, tuple(layers), "page 2: weaving")


def guide_sheet(weave: Weave, book: BallBook, labels, title: str, total: int) -> Sheet | None:
    """Page 1 of a ball whose strips start on page 2: the assembly notes, the weaving steps,
    the ball from six sides and, in a row below, growing (front and back after a third and
    two thirds of the strips: all of them in is the front and back above); None when a
    tile there would lose its ID (the views too small: the two pages of their own)."""
    area = book.area
    x0, y0, x1, y1 = area.box
    notes, bottom = paragraphs(_notes(weave, book, labels, "Weaving steps: below."), x0, y1,
                               x1 - x0)
    steps, bottom = paragraphs(_steps(book, labels, "the bottom row of views shows (the ball "
                                      "growing, front then back)"), x0, bottom - GAP, x1 - x0,
                               numbered=True)
    growing = [c for side in (VIEWS[0], VIEWS[2]) for c in _stages(weave, labels, side)[:-1]]
    row = TEXT + 2  # a view's caption under it
    cell = min((x1 - x0) / GROWING, (bottom - GAP - y0) / 3 - row)
    if cell <= 2 * GAP:
        return None
    every = np.ones(weave.n_strands, dtype=bool)
    split = bottom - GAP - 2 * (cell + row)
    grids = [((x0, split, x1, bottom - GAP), [(*v, every) for v in VIEWS], 3, 2)]
    if growing:
        grids.append(((x0, split - cell - row, x1, split), growing, GROWING, 1))
    layers, missing = _view_shapes(weave, book.colours, labels, grids)
    if missing:
        return None
    layers += [Layer("notes", "label", tuple(notes)), Layer("steps", "label", tuple(steps))]
    layers += page_layers(area, title, "Assembly and weaving: the woven ball from six sides, "
                          "every tile with the ID of the strand on top", 1, total,
                          book.colours[0])
    return Sheet(area.width, area.height, tuple(layers), "page 1: assembly and weaving")


def _steps(book: BallBook, labels, views: str) -> list[str]:
    """The numbered weaving steps; the fifth points to the ``views`` of the ball growing."""
    valleys = any((u.fold_angles < -MIN_FOLD).any() for u in book.unfoldings)
    return [
        "Cut out every strip along its red outline, the narrow V-shaped notches between "
        "tiles too: they let the strip curve round the ball.",
        "Crease every dashed line with the coloured side outwards (mountain folds): each "
        "octagon folds along its middle, and the strip bends where tiles meet."
        + (" Dotted lines fold the other way (valley folds: the coloured side inwards)."
           if valleys else ""),
        "A strip in pieces: glue the grey band 'glue j' of each piece under the tile marked "
        "'j' of the next, coloured sides out, outlines matching.",
        "A strip's own tiles (its colour) lie on top; a light tile names the strip on top "
        "of it there: slide it under that strip.",
        f"Start with {labels[0]}; add the others in order, one at a time, over and under as "
        f"printed, as {views}.",
        "Close every loop last: glue its band 'glue j' under its own tile marked 'j'.",
    ]


def _stages(weave: Weave, labels, side) -> list[tuple]:
    """View cells of the ball from ``side`` (a VIEWS row) after a third, two thirds and all
    of its strands are in (fewer for fewer than three strands)."""
    n = weave.n_strands
    cells = []
    for m in sorted({max(1, math.ceil(k * n / 3)) for k in (1, 2, 3)}):
        name = f"{labels[0]}-{labels[m - 1]}" if m > 1 else labels[0]
        cells.append((f"{name}, {side[0]}", side[1], side[2], np.arange(n) < m))
    return cells
