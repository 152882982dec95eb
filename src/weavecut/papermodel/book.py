"""The strand book: an assembly sheet, then the strip pages of every module copy and extras.

Page 1 shows the finished pattern in colour with every strand's ID and direction, what to
print and where each copy's strips are. Then, per copy A, B, ... of the module, the same
packed layout (so a stack of prints can be cut at once), coloured and labelled for that copy;
then the strands that a rotation fixes, printed once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from ..weave.colour import Palette
from ..weave.model import Weave
from ..layout.drawing import Drawing, Fit, Layer, Sheet, Style, Text, polygons_from_shapely
from .pages import (
    GAP,
    PageArea,
    pack,
    page_layers,
    placed_strip,
    placement,
    split_strip,
    strip_layers,
)
from .strips import (
    ModulePlan,
    arrow_polygon,
    build_strips,
    copy_colours,
    copy_letter,
    ink_for,
    model_tiles,
    octagon_size,
    orbit_colours,
    plan_modules,
)
from .symmetry import rotate, tile_centres

OVERLAP = 8.0  # mm of glue overlap where a long strip is split


@dataclass(frozen=True, eq=False)
class StrandBook:
    """The drawing plus what the tests and the CLI report need.

    Parameters
    ----------
    drawing : every page
    plan : the module plan (symmetry, copies, extras, labels)
    colours : (S,) strand colours
    copy_pages : per copy, its page numbers (1-based); the module's pages are copy A's
    extra_pages : page numbers of the strands printed once
    strip_pages : strand label -> page numbers of its strip (pieces)
    scale : mm per model unit
    """

    drawing: Drawing
    plan: ModulePlan
    colours: tuple[str, ...]
    copy_pages: tuple[tuple[int, ...], ...]
    extra_pages: tuple[int, ...]
    strip_pages: dict[str, tuple[int, ...]]
    scale: float
    area: PageArea


def strand_book(weaves: list[Weave], pal: Palette, page: tuple[float, float] = (210.0, 297.0),
                tile_size: float = 20.0, margin: float = 10.0, turn: float = 0.0,
                title: str = "weave-cut strands") -> StrandBook:
    """Lay out every strand of ``weaves[-1]`` as printable strips.

    Parameters
    ----------
    weaves : snub weaves of levels 1..N (the last is printed; the one before gives the
        braided-pair colours)
    pal : palette; with shade families every copy of a module strand has the same colour,
        a flat palette gives one colour per copy
    page : (width, height) mm
    tile_size : mm across a typical octagon (the print's true scale)
    margin : mm of blank paper round the page
    turn : radians the pattern is turned on the assembly sheet (module strands head "down"
        in the turned frame)
    """
    weave = weaves[-1]
    area = PageArea(page[0], page[1], margin)
    area.check()
    plan = plan_modules(weave, heading=-np.pi / 2 - turn)
    colours = orbit_colours(weaves, plan, pal) if pal.shaded else copy_colours(plan, pal)
    scale = tile_size / octagon_size(weave)
    k = plan.k

    # module layout from copy A; every copy reuses it
    def pieces(strands, copy):
        strips = build_strips(weave, plan, colours, scale, strands, copy)
        return [p for s in strips for p in split_strip(s, area.long, OVERLAP)]

    module = pieces(plan.copies[0], 0)
    module_bins = pack([p.outline for p in module], area.long, area.short, GAP)
    extra = pieces(plan.extras, 0) if len(plan.extras) else []
    extra_bins = pack([p.outline for p in extra], area.long, area.short, GAP)

    jobs = []  # (kind, copy, pieces, bin)
    for j in range(k):  # copies
        strips = module if j == 0 else pieces(plan.copies[0], j)
        jobs.extend(("copy", j, strips, b) for b in module_bins)
    jobs.extend(("extra", -1, extra, b) for b in extra_bins)
    total = len(jobs) + 1

    sheets, copy_pages, extra_pages = [], [[] for _ in range(k)], []
    strip_pages: dict[str, list[int]] = {}
    for n, (kind, j, strips, b) in enumerate(jobs, start=2):
        placed = []
        for i, turned, u, v in b:
            p = strips[i]
            f, angle = placement(area, p.outline.bounds, turned, u, v)
            placed.append(placed_strip(p, f, angle))
            strip_pages.setdefault(p.label.split(" ")[0], []).append(n)
        names = _runs(sorted({p.label.split(" ")[0] for p in placed}, key=_label_key))
        if kind == "copy":
            copy_pages[j].append(n)
            sub = (f"Copy {copy_letter(j)} of {k}: the module turned by {j * 360 / k:g} deg "
                   f"(all copies share this layout). Strips: {names}")
        else:
            extra_pages.append(n)
            sub = f"Printed once (fixed by a rotation). Strips: {names}"
        sample = colours[placed[0].strand]
        layers = strip_layers(placed) + page_layers(
            area, title, sub, n, total, sample, glue=any(p.glue is not None for p in placed))
        sheets.append(Sheet(area.width, area.height, tuple(layers),
                            f"page {n}: copy {copy_letter(j)}" if kind == "copy"
                            else f"page {n}: extras"))
    book = StrandBook(Drawing((), title), plan, tuple(colours),
                      tuple(tuple(c) for c in copy_pages), tuple(extra_pages),
                      {key: tuple(v) for key, v in strip_pages.items()}, scale, area)
    cover = assembly_sheet(weave, book, tile_size, turn, title, total)
    return StrandBook(Drawing((cover, *sheets), title), plan, tuple(colours), book.copy_pages,
                      book.extra_pages, book.strip_pages, scale, area)


def _label_key(label: str):
    head = label.rstrip("0123456789")
    return (head, int(label[len(head):] or 0))


def _runs(labels: list[str]) -> str:
    """"A1-A4, A6, X1" from sorted labels."""
    out, start, prev = [], None, None
    for lab in labels + [None]:
        key = None if lab is None else _label_key(lab)
        if prev is not None and key is not None and key[0] == prev[0] and key[1] == prev[1] + 1:
            prev = key
            continue
        if start is not None:
            out.append(f"{start[0]}{start[1]}" if start == prev
                       else f"{start[0]}{start[1]}-{prev[0]}{prev[1]}")
        start = prev = key
    return ", ".join(out)


def _ranges(pages) -> str:
    pages = list(pages)
    if not pages:
        return "-"
    return f"{pages[0]}" if len(pages) == 1 else f"{pages[0]}-{pages[-1]}"


def assembly_sheet(weave: Weave, book: StrandBook, tile_size: float, turn: float, title: str,
                   total: int) -> Sheet:
    """Page 1: the finished pattern in colour with strand IDs and directions, and what to print."""
    plan, area = book.plan, book.area
    k, m = plan.k, plan.copies.shape[1]
    x0, y0, x1, y1 = area.box
    size_mm = np.ptp(weave.mesh.vertices, axis=0) * book.scale
    lines = [
        f"{weave.n_strands} strands = {k} copies (A-{copy_letter(k - 1)}) of a module of {m} "
        f"strips" + (f" + {len(plan.extras)} extras printed once" if len(plan.extras) else "")
        + f". Symmetry C{k}: copy j is the module turned by j x {360 / k:g} deg.",
        "Print every page once at 100 % (no fit to page): "
        + "; ".join(f"copy {copy_letter(j)} p. {_ranges(p)}" for j, p in enumerate(book.copy_pages))
        + (f"; extras p. {_ranges(book.extra_pages)}" if book.extra_pages else "") + ".",
        f"Finished model about {size_mm[0] / 10:.0f} x {size_mm[1] / 10:.0f} cm, octagons "
        f"{tile_size:g} mm across. Weave each strand along its arrow;",
        "where a strip is printed light it goes under the strand named there.",
    ]
    texts = [Text(x0, y1 - 3.0 - 4.2 * i, line, 2.5) for i, line in enumerate(lines)]
    fig_top = y1 - 4.2 * len(lines) - 2.0

    tiles = model_tiles(weave)
    centre = weave.mesh.vertices.mean(axis=0)
    turned = shapely.transform(tiles, lambda xy: rotate(xy, turn, centre))
    bx0, by0, bx1, by1 = shapely.total_bounds(turned)
    fit = Fit.into((bx0, by0, bx1, by1), x1 - x0, fig_top - y0, 0.0)
    fit = Fit(fit.scale, (fit.offset[0] + x0, fit.offset[1] + y0))
    on_sheet = shapely.transform(turned, fit)
    colours = book.colours
    over = weave.tile_over
    fills = [colours[s] if s >= 0 else "#ffffff" for s in over.tolist()]
    tile_mm = octagon_size(weave) * fit.scale
    shapes: list = [polygons_from_shapely(list(on_sheet), Style("#333333", 0.1), fills)]
    # IDs and arrows at every strand's first own tile (in printed direction)
    centres = fit(rotate(tile_centres(weave), turn, centre))
    label_size = float(np.clip(0.2 * tile_mm, 1.2, 3.5))
    arrows: dict[str, list] = {}
    for s in range(weave.n_strands):  # strands, not mesh elements
        visits, own = weave.strand(s)
        if plan.reversed[s]:
            visits, own = visits[::-1], own[::-1]
        i = int(np.flatnonzero(own)[0])
        j = i + 1 if i + 1 < len(visits) else i - 1
        d = centres[visits[j]] - centres[visits[i]]
        d = d if j > i else -d
        ink = ink_for(colours[s])
        p = centres[visits[i]]
        texts.append(Text(p[0], p[1] - label_size / 2, plan.labels[s], label_size, "middle",
                          0.0, ink))
        arrows.setdefault(ink, []).append(
            arrow_polygon(p + d / max(np.hypot(*d), 1e-12) * 0.45 * tile_mm, d, 0.3 * tile_mm))
    shapes += [polygons_from_shapely(a, Style(None, 0.0, ink)) for ink, a in sorted(arrows.items())]
    scale_note = f"pattern drawn at {100 * fit.scale / book.scale:.0f} % of its printed size"
    texts.append(Text(x1, y0 - 1.0 - 2.2, scale_note, 2.0, "end"))
    layers = [Layer("pattern", "paint", tuple(shapes)), Layer("ids", "label", tuple(texts))]
    layers += page_layers(area, title, "Assembly sheet: the finished pattern, strand IDs "
                          "(copy letter + module number) and directions", 1, total,
                          colours[int(plan.copies[0, 0])] if m else "#3e9fb0")
    return Sheet(area.width, area.height, tuple(layers), "page 1: assembly")



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
