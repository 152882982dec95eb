"""The laser-card kit: the strips laser-cut from coloured card and the instructions for them.

Only what the card needs is built: the labelled strip pieces (split to fit the card sheet, not
a printed page), packed onto the card sheets by colour (:mod:`.lasercard`), then a PDF of its
own words on the printer's page size (``page``, not the card's): page 1 the assembly sheet
(which sheet holds which strip), page 2 the weaving steps, page 3 the card colours, the laser's
layers and a strip as it comes off the laser, then any pages of crossings too small to name.
Where the sheets are mostly empty, page 3 and the summary name the palette presets that need
fewer colours of card.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import shapely

from .. import presets
from ..layout.contrast import text_colour_on
from ..layout.drawing import (Drawing, Layer, Sheet, Style, Text, polygons_from_shapely,
                              polylines_from_lines)
from ..layout.labels import MIN_CAP
from ..layout.lasersetup import Laser
from ..numeric import affine
from ..weave.colour import palette
from ..weave.model import Weave
from .book import StrandBook, front_pages, strip_set
from .crossings import left_out_crossings, too_small
from .lasercard import (SHEET_MARGIN, CardCut, card_sheets, dot_centres, engraved_labels, marks,
                        rings, score_lines)
from .modules import ModulePlan, book_colours
from .pages import GAP, PageArea, page_layers, page_span
from .strips import Strip, flat_angle
from .wording import CARD, LINE, Words, paragraphs, strip_runs

FULL = 0.5  # sheets covered less than this on average get the fewer-colours hint
COLOURS_PAGE = 3


@dataclass(frozen=True, eq=False)
class CardKit:
    """The card sheets, the instructions and what the summary needs.

    Parameters
    ----------
    cut : the card sheets (:class:`.lasercard.CardCut`)
    book : the instructions' pages (assembly, weaving, card colours, crossings) as a book
        whose pieces are the strips by card sheet (no strip pages)
    files : the card sheets' file names without suffix, one per sheet
    fewer : (palette preset, card colours) of the presets that need fewer colours of card,
        when the sheets are mostly empty; else empty
    warnings : things the maker should know (thin strips)
    """

    cut: CardCut
    book: StrandBook
    files: tuple[str, ...]
    fewer: tuple[tuple[str, int], ...]
    warnings: tuple[str, ...]

    @property
    def instructions(self) -> Drawing:
        return self.book.drawing


def sheet_names(cut: CardCut) -> tuple[str, ...]:
    """The file name (no suffix) of every card sheet: strands-card-01-0b3c5d."""
    return tuple(f"strands-card-{n:02d}-{c.lstrip('#')}" for n, c in enumerate(cut.colours, 1))


def fewer_colours(weaves: list[Weave], plan: ModulePlan, n_colours: int
                  ) -> tuple[tuple[str, int], ...]:
    """(name, card colours) of every palette preset whose colours for this model are fewer
    than ``n_colours`` but no fewer than its copies (no two copies share a colour), fewest
    first."""
    out = []
    for name in presets.names("palettes"):  # a few presets
        count = len(set(book_colours(weaves, plan, palette(name), "mixed")))
        if plan.k <= count < n_colours:
            out.append((name, count))
    return tuple(sorted(out, key=lambda e: (e[1], e[0])))


def card_words(cut: CardCut, files: tuple[str, ...]) -> Words:
    """The card's words, with page 1's sentence on the sheets and which strips each holds."""
    where = "; ".join(f"sheet {n}: " + strip_runs({p.label for p in pieces})
                      for n, pieces in enumerate(cut.pieces, start=1))
    names = files[0] if len(files) == 1 else f"{files[0]} to {files[-1]}"
    count = "the card sheet" if len(files) == 1 else f"the {len(files)} card sheets"
    return replace(CARD, sources=(
        f"Laser-cut {count} ({names}, .svg or .dxf), each from card of its colour (page "
        f"{COLOURS_PAGE}). Where each strip is: {where}."))


def hint(kit_fill: float, n_sheets: int, fewer) -> str:
    """The fewer-colours hint for the colours page ("" without ``fewer``)."""
    if not fewer:
        return ""
    least = fewer[0][1]
    names = " or ".join(f"--palette {name}" for name, count in fewer if count == least)
    sheets = "The card sheet is" if n_sheets == 1 else f"The {n_sheets} card sheets are"
    return (f"{sheets} {100 * kit_fill:.0f} % covered on average, one colour of card each. A "
            f"palette with fewer colours needs fewer colours of card: {names} cuts these strips "
            f"from {least} colours.")


def card_kit(weaves: list[Weave], pal_name: str, mat: dict, las: Laser,
             page: tuple[float, float], margin: float, tile_size: float, turn: float,
             title: str) -> CardKit:
    """The laser-card kit of ``weaves[-1]``: strips cut from the card ``mat`` (a material
    preset: sheet, kerf), the instructions on ``page`` with ``margin``.

    Raises
    ------
    SizeError when strips would be narrower than 8 mm or a label smaller than 2.5 mm
    """
    weave = weaves[-1]
    sheet = PageArea(*mat["sheet"], SHEET_MARGIN, furniture=False)
    paper = PageArea(page[0], page[1], margin)
    paper.check()
    pal = palette(pal_name)
    made = strip_set(weaves, pal, sheet, tile_size, turn)
    cut = card_sheets(made.pieces, made.colours, las, mat["kerf"], mat["sheet"], title)
    files = sheet_names(cut)
    placed = tuple((n, p) for n, pieces in enumerate(cut.pieces, start=1) for p in pieces)
    crossings = (left_out_crossings(weave, made.plan, [p for _, p in placed], "mixed")
                 if any(p.left_out for _, p in placed) else [])
    n_colours = len(set(cut.colours))
    fewer = fewer_colours(weaves, made.plan, n_colours) if cut.fill < FULL else ()
    words = card_words(cut, files)

    def book_for(own: int, ids: int = 0, shared: bool = False) -> tuple[StrandBook, int, int]:
        first = COLOURS_PAGE + 1
        return (StrandBook(Drawing((), title), made.plan, made.colours, "mixed", placed, (),
                           (1, 2, *range(first, first + own + ids)), made.scale, paper,
                           made.strip_width, tile_size, made.warnings,
                           tuple(range(first + (0 if shared else own), first + own + ids)),
                           tuple(range(first, first + own))),
                COLOURS_PAGE + own + ids, first)

    book, front = front_pages(weave, made.plan, made.colours, paper, crossings, book_for,
                              tile_size, turn, title, words)
    total = len(front) + 1
    colours = card_colour_sheet(cut, paper, title, las, hint(cut.fill, len(cut.sheets), fewer),
                                COLOURS_PAGE, total, pal.called)
    book = replace(book, drawing=Drawing((*front[:2], colours, *front[2:]), title))
    return CardKit(cut, book, files, fewer, made.warnings + _left_out(crossings, book))


def _left_out(crossings, book: StrandBook) -> tuple[str, ...]:
    """The warning on crossings no strip names, with the pages that call them out."""
    if not crossings:
        return ()
    where = page_span(book.callout_pages or [1])
    return (f"{too_small(len(crossings), 'an engraved name')} (an "
            f"engraved dot there): {'it is' if len(crossings) == 1 else 'they are'} called out on "
            f"{where} of strands-assembly.pdf",)


ROW = 14.0  # mm between two card colours on the colours page
SWATCH = Style("#333333", 0.2)


def card_colour_sheet(cut: CardCut, area: PageArea, title: str, las: Laser, note: str = "",
                      number: int = COLOURS_PAGE, total: int = COLOURS_PAGE,
                      called=lambda colour: colour) -> Sheet:
    """Page ``number``: how to cut the sheets (the laser's layers in order), ``note`` (the
    fewer-colours hint), which card colour every strand is cut from (``called``: its name in
    the palette) and on which sheets, where on them its strips lie, and a strip as it comes off
    the laser."""
    x0, y0, x1, y1 = area.box
    role = {r: las.style(r).stroke for r in ("engrave", "score", "cut")}
    lines = [f"Cut every sheet from card of its colour; its file name says which "
             f"({sheet_names(cut)[0]}.svg: card {called(cut.colours[0])}). Each file has three layers "
             f"in the colours of the {las.name} preset, to be run in this order: engrave "
             f"({role['engrave']}), then score ({role['score']}) with little power, so that it "
             f"marks and creases the card without cutting through, then cut ({role['cut']}). "
             "Try the settings on a scrap of the card first."] + ([note] if note else [])
    texts, y = paragraphs(lines, x0, y1, x1 - x0)
    swatches, fills = [], []
    names = dict.fromkeys(cut.colours)  # card colours, in order
    pitch = max(9.0, min(ROW, (y - y0) / max(len(names), 1)))
    y -= GAP
    for colour in names:  # card colours
        numbers = [n + 1 for n, c in enumerate(cut.colours) if c == colour]
        labels = {p.label.split(" ")[0] for n in numbers for p in cut.pieces[n - 1]}
        y -= pitch
        swatches.append(shapely.box(x0, y, x0 + 14.0, y + 8.0))
        fills.append(colour)
        word = "sheet" if len(numbers) == 1 else "sheets"
        texts.append(Text(x0 + 18.0, y + 4.5, f"card {called(colour)}: {word} "
                          f"{', '.join(map(str, numbers))}", 4.0))
        texts.append(Text(x0 + 18.0, y, f"strands {strip_runs(labels)}; {used_card(cut, numbers)}",
                          MIN_CAP))
    shapes = [polygons_from_shapely(swatches, SWATCH, fills)]
    figure, true_size = strip_figure(cut, (x0, y0, x1, y - 2 * GAP))
    shapes += figure
    layers = (Layer("card colours", "label", tuple(shapes) + tuple(texts)),
              *page_layers(area, title, "Card and laser: the card colour of every sheet, the "
                           "laser's layers, a strip as it comes off the laser", number, total,
                           legend=False, bar=true_size))
    return Sheet(area.width, area.height, layers, f"page {number}: card colours")


def used_card(cut: CardCut, numbers: list[int]) -> str:
    """Where the strips of sheets ``numbers`` (1-based) lie: the width x height from each
    sheet's top-left corner that holds them (its margin included), so that a maker can cut a
    piece of card that size instead of spending a whole sheet on a few strips."""
    sizes = []
    for n in numbers:
        height = cut.sheets[n - 1].sheets[0].height
        x0, y0, x1, y1 = shapely.total_bounds([p.cut for p in cut.pieces[n - 1]])
        sizes.append(f"{x1 + SHEET_MARGIN:.0f} x {height - y0 + SHEET_MARGIN:.0f} mm")
    return f"the strips fill {' and '.join(sizes)} at the top left"


def strip_figure(cut: CardCut, box) -> tuple[list, bool]:
    """(shapes, whether at 100 %): a strip as it comes off the laser, drawn in ``box`` (at
    100 % where it fits) with a caption below: the card in its colour, the engraving and the score lines in the ink that
    reads on it. The whole strip (not a part of a split one) with the most tiles that fits at
    100 % is drawn (else the one with the most tiles, smaller); nothing where ``box`` is too
    low."""
    x0, y0, x1, y1 = box
    pieces = [p for group in cut.pieces for p in group]
    caption_room = 3 * LINE + GAP
    if not pieces or y1 - y0 - caption_room < 15.0:
        return [], False
    rects = np.array([_long_short(p.cut) for p in pieces])
    fits = (rects[:, 0] <= x1 - x0) & (rects[:, 1] <= y1 - y0 - caption_room)
    pick = min(range(len(pieces)), key=lambda i: (  # a whole strip, as long as fits
        not fits[i], " " in pieces[i].label, -len(pieces[i].tiles), pieces[i].label))
    piece = _laid_flat(pieces[pick])
    length, width = piece.cut.bounds[2:]
    scale = min(1.0, (x1 - x0) / length, (y1 - y0 - caption_room) / width)
    engraved = engraved_labels([piece])[0]
    lines = [engraved.coords[a:b] for a, b in zip(engraved.offsets[:-1], engraved.offsets[1:])]
    lines += marks(piece) + rings(dot_centres(piece, piece.left_out))
    scores = score_lines([piece], [engraved])[0]
    at = np.array([x0, y1 - width * scale])

    def place(xy):
        return np.asarray(xy) * scale + at

    colour = cut.colours[next(n for n, group in enumerate(cut.pieces) for p in group
                              if p is pieces[pick])]
    ink = text_colour_on(colour)
    outline = shapely.transform(piece.cut, place)
    label = piece.label.split(" ")[0]
    caption, _ = paragraphs([f"Strip {label} as it comes off the laser, drawn at "
                             f"{100 * scale:.0f} %: its ID, the arrows the way it reads, score "
                             "lines between its tiles; the tiles lie on top and under in turn, "
                             "and a small ID in a tile names the strand on top there, where "
                             "the strip goes under."], x0, at[1] - GAP, x1 - x0)
    return [polygons_from_shapely([outline], SWATCH, [colour]),
            polylines_from_lines([place(s) for s in scores], Style(ink, 0.15)),
            polylines_from_lines([place(s) for s in lines], Style(ink, 0.3)), *caption], \
        scale == 1.0


def _long_short(polygon) -> tuple[float, float]:
    """The long and the short side of ``polygon``'s smallest rectangle."""
    rect = np.asarray(shapely.minimum_rotated_rectangle(polygon).exterior.coords)[:3]
    sides = np.hypot(*np.diff(rect, axis=0).T)
    return float(sides.max()), float(sides.min())


def _laid_flat(piece: Strip) -> Strip:
    """``piece`` turned so that its long side lies along x, its corner at the origin."""
    flat = piece.moved(affine(flat_angle(piece.outline)))
    x, y = flat.cut.bounds[:2]
    return flat.moved(affine(0.0, (-x, -y)))
