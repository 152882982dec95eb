"""The strand book: an assembly sheet, a weaving page, then the strip pages.

Two layouts (paper section 5.2):

- ``mixed`` (the default): the strips of every module copy and the extras packed together, as
  densely as the packer goes; every strip says its copy and number ("B7"); each copy has its own
  shade family, so the copies can be told apart on the table and on the assembly sheet.
- ``module`` (the paper's own way): the module's strips once, labelled by number only, in colours
  that are the same for every copy; the maker prints these pages once per direction (k times) and
  the assembly sheet says how each print is turned.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..numeric import affine, matmul
from ..errors import WeaveCutError
from ..layout.drawing import Drawing, Sheet
from ..layout.labels import MIN_CAP
from ..weave.colour import Palette
from ..weave.model import Weave
from .crossings import left_out_crossings
from .front import front_pages
from .header import header_lines, strips_subtitle
from .packing import pack
from .pages import (GAP, GLUE_MARKS, PageArea, page_layers, page_span, split_strip,
                    strip_layers)
from .modules import ModulePlan, book_colours, copy_family_colours, plan_modules
from .strip_labels import label_strips
from .strips import (MIN_PIECE, Strip, build_copies, build_strips, holds, moved_strips,
                     octagon_size, strip_width)
from .wording import PRINTED, Words, left_out_note

CURL = 0.45  # a strip wider than this share of the page (a curl) is cut into pieces
MIN_STRIP = 8.0  # mm: narrower strips tear (paper section 5.2)
WARN_STRIP = 11.0  # mm: fiddly below (the paper's 23 cm pentagon was woven from 11.1 mm strips)
LAYOUTS = ("mixed", "module")


class SizeError(WeaveCutError, ValueError):
    """The strips would be too thin to cut and weave, or their labels too small to read."""


@dataclass(frozen=True, eq=False)
class StrandBook:
    """The drawing plus what the tests and the CLI report need.

    Parameters
    ----------
    drawing : every page
    plan : the module plan (symmetry, copies, extras, labels)
    colours : (S,) strand colours
    layout : "mixed" or "module"
    pieces : every strip piece on its page (page coordinates; ``frame`` maps the weave's model
        units onto the page), with its page number (1-based)
    strip_pages : page numbers of the strip pages
    extra_pages : page numbers of the other pages (assembly, weaving)
    scale : mm per model unit
    area : the page and its printable box
    strip_width : mm, the median strip width
    tile_size : mm across a typical octagon
    warnings : things the maker should know (thin strips)
    id_pages : page numbers of the pages naming the strands page 1 has no room for (the
        crossing pages, else the last extra pages)
    callout_pages : page numbers of the pages calling out the crossings the strips leave
        unnamed
    diagram_colours : (S,) strand colours of the weaving page's diagrams where ``colours`` do
        not tell the copies apart (a four-copy module layout in shade families: every copy
        printed in the module's colours), else empty (the diagrams in ``colours``)
    """

    drawing: Drawing
    plan: ModulePlan
    colours: tuple[str, ...]
    layout: str
    pieces: tuple[tuple[int, Strip], ...]
    strip_pages: tuple[int, ...]
    extra_pages: tuple[int, ...]
    scale: float
    area: PageArea
    strip_width: float
    tile_size: float
    warnings: tuple[str, ...] = ()
    id_pages: tuple[int, ...] = ()
    callout_pages: tuple[int, ...] = ()
    diagram_colours: tuple[str, ...] = ()

    @property
    def ink(self) -> float:
        """Share of the strip pages' printable area covered by strips."""
        x0, y0, x1, y1 = self.area.box
        covered = sum(p.cut.area for _, p in self.pieces)
        return covered / max(len(self.strip_pages) * (x1 - x0) * (y1 - y0), 1e-12)

    def pages_of(self, label: str) -> tuple[int, ...]:
        """Pages holding (pieces of) the strip ``label``."""
        return tuple(sorted({n for n, p in self.pieces if p.label.split(" ")[0] == label}))


def tile_size_for(weave: Weave, width: float) -> float:
    """The tile size (mm across an octagon) that makes the model ``width`` mm wide."""
    return width / float(np.ptp(weave.mesh.vertices[:, 0])) * octagon_size(weave)


def strip_need(weave: Weave) -> float:
    """The smallest tile size (mm, in half mm) whose strips are ``MIN_STRIP`` wide."""
    return math.ceil(MIN_STRIP / (strip_width(weave) / octagon_size(weave)) * 2) / 2


def check_strip_width(weave: Weave, tile_size: float,
                      passes=None) -> tuple[float, tuple[str, ...]]:
    """(strip width mm, warnings); raises SizeError below ``MIN_STRIP``, naming the smallest tile
    size whose strips are wide enough, or ``passes(that size)`` (the size where the other checks
    pass too)."""
    width = tile_size * strip_width(weave) / octagon_size(weave)
    if width < MIN_STRIP - 1e-9:
        hold = strip_need(weave)
        need = hold if passes is None else passes(hold)
        why = "" if need == hold else (f"; strips hold from {hold:g}mm, labels reach "
                                        f"{MIN_CAP:g} mm from {need:g}mm")
        raise SizeError(f"strips would be {width:.1f} mm wide and tear (paper section 5.2): "
                        f"{_use(weave, need)}{why}")
    if width < WARN_STRIP:
        return width, (f"strips are {width:.1f} mm wide: thin strips tear easily; "
                       f"{WARN_STRIP:g} mm or more is easier to weave",)
    return width, ()


def _use(weave: Weave, need: float) -> str:
    return (f"use --tile-size {need:g}mm or more "
            f"(--size {math.ceil(tile_size_width(weave, need) / 10)}cm or more)")


def tile_size_width(weave: Weave, tile_size: float) -> float:
    """The model's width (mm) at ``tile_size``."""
    return tile_size / octagon_size(weave) * float(np.ptp(weave.mesh.vertices[:, 0]))


@dataclass(frozen=True, eq=False)
class StripSet:
    """Every strip piece of a model, labelled and checked, before any page or sheet is laid
    out: what the printed book and the card sheets share.

    Parameters
    ----------
    plan : the module plan (symmetry, copies, extras, labels)
    colours : (S,) strand colours
    pieces : every strip piece, labelled, each in its own frame (long axis along x)
    kinds : per piece, equal for congruent pieces (the packer places them alike)
    scale : mm per model unit
    strip_width : mm, the median strip width
    warnings : things the maker should know (thin strips)
    area : the page area the pieces are cut to fit, its header holding the subtitle's head
    """

    plan: ModulePlan
    colours: tuple[str, ...]
    pieces: list[Strip]
    kinds: list[int]
    scale: float
    strip_width: float
    warnings: tuple[str, ...]
    area: PageArea


def strip_set(weaves: list[Weave], pal: Palette, area: PageArea, tile_size: float,
              turn: float = 0.0, layout: str = "mixed", head=None) -> StripSet:
    """The labelled strip pieces of ``weaves[-1]`` at ``tile_size``, each short enough for
    ``area``'s box (see :func:`strand_book` for the parameters), its header given the lines
    ``head(plan)`` needs, the strip pages' subtitle before their list of strips, if given.

    Raises
    ------
    SizeError when strips would be narrower than 8 mm, a label smaller than 2.5 mm or a part of
    a strip narrower than ``MIN_PIECE`` (see :func:`.slim.holds`)
    """
    if layout not in LAYOUTS:
        raise ValueError(f"layout must be one of {LAYOUTS}, got {layout!r}")
    weave = weaves[-1]
    plan = plan_modules(weave, heading=-np.pi / 2 - turn)
    if head is not None:
        area = replace(area, header_lines=header_lines(head(plan), area.width - 2 * area.margin))
    area.check()
    colours = book_colours(weaves, plan, pal, layout)
    width, warnings = check_strip_width(weave, tile_size, lambda t: smallest_tile_size(
        weave, plan, colours, t, layout, area))
    pieces, kinds = labelled_pieces(weave, plan, colours, tile_size, layout, area)
    if not _reads(pieces):
        small = min(t.size for p in pieces for t in p.texts)
        need = smallest_tile_size(weave, plan, colours, tile_size, layout, area)
        raise SizeError(f"some labels would be {small:.1f} mm tall at --tile-size {tile_size:.1f}mm"
                        f"; labels need {MIN_CAP:g} mm: {_use(weave, need)}")
    slim = ~holds([p.cut for p in pieces], MIN_PIECE, slivers=False)
    if slim.any():  # a neck no widening or thickening mends (see .slim.thickened)
        worst = pieces[int(np.flatnonzero(slim)[0])]
        neck = (f"strip {worst.label} would have a neck narrower than {MIN_PIECE:g} mm, too "
                f"thin to cut, at --tile-size {tile_size:.1f}mm")
        try:
            need = smallest_tile_size(weave, plan, colours, tile_size, layout, area)
        except SizeError:  # tiles that touch at a corner: no size widens them
            warnings += (f"{neck}, and at any size (tiles that meet at a corner): cut round "
                         "it with care, or tape it",)
        else:
            raise SizeError(f"{neck}: {_use(weave, need)}")
    return StripSet(plan, tuple(colours), pieces, kinds, tile_size / octagon_size(weave), width,
                    warnings, area)


def strand_book(weaves: list[Weave], pal: Palette, page: tuple[float, float] = (210.0, 297.0),
                tile_size: float = 20.0, margin: float = 10.0, turn: float = 0.0,
                title: str = "weave-cut strands", layout: str = "mixed",
                limit: tuple[float, float, float, float] | None = None,
                words: Words = PRINTED, page_note=None, gap: float = GAP,
                bleed: float = 0.0) -> StrandBook:
    """Lay out every strand of ``weaves[-1]`` as printable strips.

    Parameters
    ----------
    weaves : snub weaves of levels 1..N (the last is printed; the one before gives the
        braided-pair colours of the module layout)
    pal : palette; shade families give every copy its family (mixed) or every module strand
        its braided-pair shade (module); a flat palette gives one colour per copy
    page : (width, height) mm
    tile_size : mm across a typical octagon (the print's true scale)
    margin : mm of blank paper round the page
    turn : radians the pattern is turned on the assembly sheet (module strands head "down"
        in the turned frame)
    layout : "mixed" (all copies packed together) or "module" (print the module once per
        direction)
    limit : (x0, y0, x1, y1) mm, the part of the page strips may use besides the margins (the
        area a print-and-cut machine reads), or None
    words : what page 1 and the weaving page say the maker holds (print and cut:
        ``cutter_words.cutter_words``)
    page_note : a function of a strip page's number giving a note put before its list of strips
        (print and cut: the page's cut file), or None
    gap : mm of paper left between two strips (print and cut: ``printcut.WASTE``)
    bleed : mm the strips' colours reach past their cut lines, printed without them (print
        and cut: ``printcut.BLEED``), or 0: cut lines printed

    Raises
    ------
    SizeError when strips would be narrower than 8 mm or a label smaller than 2.5 mm
    """
    weave = weaves[-1]

    def head(plan: ModulePlan, n: int = 0) -> str:  # strip page n's subtitle before its strips
        return (f"{page_note(n)} " if page_note else "") + (
            f"Print this page {plan.k} times, once per direction (see page 1). "
            if layout == "module" else "")
    made = strip_set(weaves, pal, PageArea(page[0], page[1], margin, limit), tile_size, turn,
                     layout, head)
    area = made.area
    plan, colours, pieces, kinds = made.plan, made.colours, made.pieces, made.kinds
    width, warnings, scale = made.strip_width, made.warnings, made.scale
    left_out = sum(len(p.left_out) for p in pieces)
    crossings = left_out_crossings(weave, plan, pieces, layout) if left_out else []
    # the warp (copies A, C) and the weft (B, D) told apart on the weaving page, as the mixed
    # layout's colours tell them: one shade family per copy
    diagram_colours = tuple(copy_family_colours(weave, plan, pal)) if (
        layout == "module" and pal.shaded and plan.k == 4) else ()
    x0, y0, x1, y1 = area.box
    places = pack([p.cut for p in pieces], x1 - x0, y1 - y0, gap, kinds=kinds)

    def pages(own: int, ids: int, shared: bool) -> tuple[StrandBook, list[Sheet], int]:
        """The book laid out with ``own`` pages of unnamed crossings after the weaving page
        (naming the strands page 1 has no room for too where ``shared``), then ``ids`` pages of
        those strands."""
        first = 3 + own + ids  # pages 1, 2: assembly and weaving
        placed, sheets = strip_sheets(pieces, kinds, area, title, colours, first, places,
                                      lambda n: head(plan, n), bleed)
        where = page_span(range(3, 3 + own) if own else [1])
        strips = f"each print's strips ({len(crossings)} on the model)" if (
            layout == "module") else None
        notes = warnings + ((left_out_note(left_out, strips, where),) if left_out else ())
        return (StrandBook(Drawing((), title), plan, tuple(colours), layout, placed,
                           tuple(range(first, first + len(sheets))), tuple(range(1, first)),
                           scale, area, width, tile_size, notes,
                           tuple(range(3, first) if shared else range(3 + own, first)),
                           tuple(range(3, 3 + own)), diagram_colours),
                sheets, len(sheets) + first - 1)

    laid: dict = {}

    def book_for(own: int, ids: int = 0, shared: bool = False) -> tuple[StrandBook, int, int]:
        book, laid["sheets"], total = pages(own, ids, shared)
        return book, total, 3

    book, extra = front_pages(weave, plan, colours, area, crossings, book_for, tile_size, turn,
                              title, words)
    return replace(book, drawing=Drawing((*extra, *laid["sheets"]), title))


def strip_sheets(pieces: list[Strip], kinds, area: PageArea, title: str, colours, first: int,
                 places=None, head=None, bleed: float = 0.0
                 ) -> tuple[tuple[tuple[int, Strip], ...], list[Sheet]]:
    """(placed, sheets): ``pieces`` packed onto pages numbered from ``first`` on (or placed at
    ``places``, the packer's answer), each page with its strips, title, a subtitle
    (``head(page number)`` if given, then the list of its strips), scale bar and legend (with
    a ``bleed``, print and cut: no cut lines, colour bled past them); placed holds (page
    number, piece on the page)."""
    x0, y0, x1, y1 = area.box
    if places is None:
        places = pack([p.cut for p in pieces], x1 - x0, y1 - y0, GAP, kinds=kinds)
    n_strip = max(pl.page for pl in places) + 1 if places else 0
    moved = moved_strips(pieces, [matmul(affine(0.0, (x0, y0)), pl.matrix()) for pl in places],
                         [pl.angle for pl in places])
    placed = tuple((first + pl.page, p) for p, pl in zip(moved, places))
    total = n_strip + first - 1
    sheets = []
    for n in range(first, first + n_strip):  # pages
        on_page = [p for k, p in placed if k == n]
        subtitle = strips_subtitle(head(n) if head else "", {p.label for p in on_page},
                                   area.width - 2 * area.margin, area.header_lines)
        layers = strip_layers(on_page, bleed) + page_layers(
            area, title, subtitle, n, total,
            colours[on_page[0].strand],
            glue=any(p.glue is not None for p in on_page),
            folds=any(len(p.folds) for p in on_page),
            tabs=any(p.flap is not None for p in on_page), cut=not bleed)
        sheets.append(Sheet(area.width, area.height, tuple(layers), f"page {n}: strips"))
    return placed, sheets


def _module_names(plan: ModulePlan) -> tuple[str, ...]:
    """Strand IDs without the copy letter: the module number ("7"), extras keep "X1"."""
    names = list(plan.labels)
    for row in plan.copies.tolist():  # copies
        for i, s in enumerate(row):
            names[s] = str(i + 1)
    return tuple(names)


def labelled_pieces(weave: Weave, plan: ModulePlan, colours, tile_size: float, layout: str,
                    area: PageArea) -> tuple[list[Strip], list[int]]:
    """Every strip piece to print, labelled, and its kind (equal for congruent pieces)."""
    scale = tile_size / octagon_size(weave)
    x0, y0, x1, y1 = area.box
    longest, widest = max(x1 - x0, y1 - y0), CURL * min(x1 - x0, y1 - y0)
    m = plan.copies.shape[1]
    pieces, kinds = [], []
    names = None if layout == "mixed" else _module_names(plan)
    for strips in build_copies(weave, plan, colours, scale, plan.copies[0],
                               range(plan.k) if layout == "mixed" else [0], names):
        for i, s in enumerate(strips):
            parts = split_strip(s, longest, widest, GLUE_MARKS[layout])
            pieces += parts
            kinds += [i * 64 + n for n in range(len(parts))]
    if len(plan.extras):
        for i, s in enumerate(build_strips(weave, plan, colours, scale, plan.extras, 0, names)):
            parts = split_strip(s, longest, widest, GLUE_MARKS[layout])
            pieces += parts
            kinds += [(m + i) * 64 + n for n in range(len(parts))]
    return label_strips(pieces, tile_size), kinds


def _reads(pieces: list[Strip]) -> bool:
    return min((x.size for p in pieces for x in p.texts), default=MIN_CAP) >= MIN_CAP - 1e-6


def smallest_tile_size(weave: Weave, plan: ModulePlan, colours, start: float, layout: str,
                       area: PageArea) -> float:
    """The smallest tile size, ``start`` or a whole mm above it, at which every label reaches
    ``MIN_CAP`` and every strip holds ``MIN_PIECE``: grown by a quarter until it works, then
    bisected."""
    def reads(t: float) -> bool:
        pieces = labelled_pieces(weave, plan, colours, t, layout, area)[0]
        return _reads(pieces) and bool(holds([p.cut for p in pieces], MIN_PIECE, False).all())

    if reads(start):
        return start
    low, high = math.floor(start), math.ceil(start * 1.25)
    while not reads(high):  # a few sizes
        if high > 8 * start:  # a sharp corner or a sliver fails at any size
            raise SizeError(f"no --tile-size up to {high}mm makes every label "
                            f"{MIN_CAP:g} mm tall and every part of a strip {MIN_PIECE:g} mm "
                            "wide; try another --cell or input")
        low, high = high, math.ceil(high * 1.25)
    while high - low > 1:
        mid = (low + high) // 2
        low, high = (low, mid) if reads(mid) else (mid, high)
    return float(high)


# The paper's two models (section 5.2): levels, how the assembly sheet is turned (radians),
# palette. Other inputs get DEFAULT.
PRESETS = {
    "square-grid": {"levels": 2, "turn": np.pi / 4, "palette": "maritime-12"},
    "pentagon-flower": {"levels": 3, "turn": 0.0, "palette": "maritime-12"},
}
DEFAULT = {"levels": 2, "turn": 0.0, "palette": "maritime-12"}


def preset_for(input_name: str) -> dict:
    """Defaults for an input spec (``name`` or ``name:param``)."""
    return dict(PRESETS.get(input_name.partition(":")[0], DEFAULT))

