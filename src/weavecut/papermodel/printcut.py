"""Print-and-cut: strip pages a desktop cutter (Cricut, Silhouette, Brother ScanNCut) cuts.

The home printer prints the strip page with the registration marks of the cutter's family; the
cutter's optical eye (or scanner) finds the marks and cuts the outlines of the page's cut file.
The cut file of a page has the page's size and the page's coordinates (millimetres, origin at
the bottom-left corner), so the page transform between them is the identity: every strip's cut
outline lies exactly on its printed strip's edge. No cut line is printed: the strips' colours
bleed ``BLEED`` past it, so a cut a little off the page leaves neither a line nor white paper.

A cutter preset (``templates/cutters``) gives the marks as plain values: their kind, ``inset``
from the page's edges, ``length`` (the square's side, an L's arm, the frame's line) and
``thickness``, the ``clearance`` strips keep from them, the largest area the cutter reads
(``max_width`` x ``max_height``, centred on the page) and the smallest feature its drag knife
cuts cleanly (``min_feature``).
Strips are packed inside the marks, ``clearance`` clear of them, and inside that area. The
book's words on marks, cut files and the cutter's software are ``cutter_words``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import shapely
from numpy.typing import NDArray

from .. import presets
from ..errors import WeaveCutError
from ..layout import cutpaths
from ..layout.drawing import Drawing, Layer, Polygons, Sheet, Style, polygons_from_shapely
from ..numeric import offsets_of
from ..units import to_mm
from .pages import CUT
from .strips import MIN_PIECE, narrowest_feature

PRINTER_EDGE = 6.35  # mm (1/4 in): the widest unprintable edge of common home printers
MARK_INK = Style(None, 0.0, "#000000")
WASTE = MIN_PIECE  # mm of paper between two strips a machine cuts: the waste between them is a
# strip of paper too, and a drag knife drags a thinner one along (or tears it) instead of
# cutting past it; the packer's 2 mm gap is for scissors, which cut each strip out on its own
BLEED = 1.0  # mm the strips' colours are printed past their cut lines (no cut line printed):
# a print-and-cut machine cuts up to 0.3-0.5 mm off the printed page (its eye's reading of the
# marks, the paper shifting on the mat), so twice that keeps white paper and a printed edge
# off every strip; two strips WASTE (3 mm) apart keep 3 - 2 * 1 = 1 mm of blank paper between
# their bleeds, and the marks' clearance (3 mm) keeps them 2 mm clear of the marks


class CutterError(WeaveCutError, ValueError):
    """A cutter preset that cannot work (marks off the printable page, no room for strips)."""


@dataclass(frozen=True)
class Cutter:
    """A print-and-cut machine family's registration marks and readable area (mm).

    Parameters
    ----------
    name : preset name
    marks : "square-and-corners" (a filled square top-left, L corners top-right and
        bottom-left: Silhouette Type 1), "corners" (four L corners) or "frame" (a rectangle
        outline: Cricut)
    inset : distance of the marks' outer edges from the page's edges
    length : the square's side and an L's arm (a frame's line width for "frame")
    thickness : an L's (or the frame's) line width
    clearance : blank paper between the marks and any strip
    max_size : (width, height) of the largest area the cutter reads, centred, or None
    min_feature : the narrowest neck or notch the drag knife cuts cleanly in paper
    brand : the machine's name as its maker writes it ("Brother ScanNCut"); the preset's name
        where the preset gives none
    """

    name: str
    marks: str
    inset: float
    length: float
    thickness: float
    clearance: float
    max_size: tuple[float, float] | None = None
    min_feature: float = 1.0
    brand: str = ""

    @property
    def title(self) -> str:
        """What the instructions call the machine: its brand, else the preset's name."""
        return self.brand or self.name

    @property
    def own_marks(self) -> bool:
        """Whether the cutter's software prints the marks itself: Cricut Design Space sends the
        image it is given to the printer with its own sensor frame round it, and cuts only a
        page it printed so (help.cricut.com, "How to Print Then Cut in Design Space",
        article 360009387274); a page printed with a frame of ours cannot be cut."""
        return self.marks == "frame"

    @property
    def reach(self) -> float:
        """How far from the page's edges the marks reach."""
        return self.inset + (self.thickness if self.marks == "frame" else self.length)

    @property
    def margin(self) -> float:
        """The page margin that keeps strips and page furniture clear of the marks."""
        return self.reach + self.clearance

    def limit(self, width: float, height: float) -> tuple[float, float, float, float] | None:
        """The readable area (x0, y0, x1, y1) on a ``width`` x ``height`` page, or None."""
        if self.max_size is None:
            return None
        w, h = self.max_size
        return ((width - w) / 2, (height - h) / 2, (width + w) / 2, (height + h) / 2)

    def mark_polygons(self, width: float, height: float) -> NDArray[np.object_]:
        """The marks on a ``width`` x ``height`` page as filled shapely polygons (y up)."""
        i, n, t = self.inset, self.length, self.thickness
        if self.marks == "frame":
            outer = shapely.box(i, i, width - i, height - i)
            return np.array([outer.difference(shapely.box(i + t, i + t, width - i - t,
                                                          height - i - t))], dtype=object)

        def rect(x, y, dx, dy):  # the box from (x, y) to (x + dx, y + dy), either way
            return shapely.box(min(x, x + dx), min(y, y + dy), max(x, x + dx), max(y, y + dy))

        def corner(x, y, sx, sy):  # an L with its outer corner at (x, y), arms towards (sx, sy)
            arms = shapely.union(rect(x, y, sx * n, sy * t), rect(x, y, sx * t, sy * n))
            return arms.normalize()

        def square(x, y, sx, sy):
            return rect(x, y, sx * n, sy * n)

        top_left = (square if self.marks == "square-and-corners" else corner)(i, height - i, 1, -1)
        marks = [top_left, corner(width - i, height - i, -1, -1), corner(i, i, 1, 1)]
        if self.marks == "corners":
            marks.append(corner(width - i, i, -1, 1))
        return np.array(marks, dtype=object)

    def check(self, width: float, height: float) -> None:
        """Refuse marks where home printers do not print, or marks that leave no room."""
        if self.inset < PRINTER_EDGE - 1e-9:
            raise CutterError(f"cutter {self.name!r}: marks {self.inset:g} mm from the edge fall "
                              f"where home printers do not print; use an inset of "
                              f"{PRINTER_EDGE:g} mm or more")
        if min(width, height) < 2 * self.margin + 40:
            raise CutterError(f"cutter {self.name!r}: a {width:g} x {height:g} mm page leaves no "
                              f"room inside its marks")


def cutter(name: str) -> Cutter:
    """The cutter preset ``name`` (``templates/cutters``) or a path to a .toml file."""
    doc = presets.load("cutters", name)
    size = None
    if "max_width" in doc or "max_height" in doc:
        size = (to_mm(doc.get("max_width", "10000mm")), to_mm(doc.get("max_height", "10000mm")))
    return Cutter(str(doc.get("name", name)), doc["marks"], to_mm(doc["inset"]),
                  to_mm(doc["length"]), to_mm(doc["thickness"]), to_mm(doc["clearance"]), size,
                  to_mm(doc["min_feature"]), str(doc.get("brand", "")))


def with_marks(book, machine: Cutter):
    """``book`` with the cutter's registration marks printed on every strip page (none where
    the cutter's software prints its own, :attr:`Cutter.own_marks`)."""
    if machine.own_marks:
        return book
    sheets = list(book.drawing.sheets)
    for n in book.strip_pages:
        s = sheets[n - 1]
        marks = polygons_from_shapely(machine.mark_polygons(s.width, s.height), MARK_INK)
        sheets[n - 1] = replace(s, layers=s.layers + (Layer("registration", "paint", (marks,)),))
    return replace(book, drawing=replace(book.drawing, sheets=tuple(sheets)))


@dataclass(frozen=True)
class CutReport:
    """How ready a set of outlines is to cut (lengths in mm).

    Parameters
    ----------
    length : total cut length
    n_outlines : closed outlines
    simple : every outline is one closed, simple ring without holes
    duplicates : segments cut twice (shared by two outlines)
    min_feature : the narrowest neck, sliver or notch of any outline
        (:func:`.strips.narrowest_feature`): the least width of paper a knife cuts round or
        clears
    """

    length: float
    n_outlines: int
    simple: bool
    duplicates: int
    min_feature: float

    def __add__(self, other: CutReport) -> CutReport:
        return CutReport(self.length + other.length, self.n_outlines + other.n_outlines,
                         self.simple and other.simple, self.duplicates + other.duplicates,
                         min(self.min_feature, other.min_feature))

    def as_dict(self) -> dict:
        return {"cut_length_mm": round(self.length, 1), "outlines": self.n_outlines,
                "closed_simple": self.simple, "duplicate_segments": self.duplicates,
                "min_feature_mm": round(self.min_feature, 2)}


def cut_report(outlines) -> CutReport:
    """Cut length, closedness, duplicate segments and the smallest feature of ``outlines``."""
    polys = np.asarray(outlines, dtype=object)
    if not len(polys):
        return CutReport(0.0, 0, True, 0, float("inf"))
    rings = shapely.get_exterior_ring(polys)
    simple = bool((shapely.is_valid(polys) & shapely.is_simple(rings)
                   & (shapely.get_num_interior_rings(polys) == 0)).all())
    coords, index = shapely.get_coordinates(rings, return_index=True)
    last = np.r_[np.flatnonzero(np.diff(index)), len(index) - 1]  # the repeated closing points
    keep = np.ones(len(coords), dtype=bool)
    keep[last] = False
    offsets = offsets_of(np.bincount(index[keep]))
    graph = cutpaths.shared_edges(coords[keep], offsets, decimals=4)
    return CutReport(float(shapely.length(rings).sum()), len(polys), simple,
                     int((graph.uses > 1).sum()),
                     float(narrowest_feature(polys).min()))


def ordered_outlines(outlines, home) -> list[NDArray[np.float64]]:
    """Closed rings of ``outlines`` (shapely polygons) in cutting order from ``home``: nearest
    next, each entered at its nearest corner (no holes: strips have none)."""
    rings = [np.asarray(p.exterior.coords) for p in outlines]
    ordered, _ = cutpaths.order_paths(rings, home)
    return ordered


def cut_layer(rings: list[NDArray[np.float64]], style: Style = CUT, name: str = "cut") -> Layer:
    """A cut layer of closed rings (their repeated last points dropped), in the given order."""
    rings = [r[:-1] if cutpaths.is_closed(r) else r for r in rings]
    coords = np.concatenate(rings) if rings else np.zeros((0, 2))
    offsets = offsets_of([len(r) for r in rings])
    return Layer(name, "cut", (Polygons(coords, offsets, style),))


CUT_SUFFIXES = (".svg", ".dxf")


def cut_file_paths(output: Path, n: int) -> list[Path]:
    """The cut files of strip page ``n`` of the PDF ``output``: PAGE-pNN-cut.svg and .dxf."""
    return [output.with_name(f"{output.stem}-p{n:02d}-cut{s}") for s in CUT_SUFFIXES]


def print_file_path(output: Path, n: int) -> Path:
    """The print image of strip page ``n`` of the PDF ``output``: PAGE-pNN-print.svg."""
    return output.with_name(f"{output.stem}-p{n:02d}-print.svg")


def existing_cut_files(output: Path) -> list[Path]:
    """The cut files and print images of any page of ``output`` that exist beside it."""
    pattern = f"{output.stem}-p[0-9][0-9]*-"
    return sorted(p for s in (*(f"cut{s}" for s in CUT_SUFFIXES), "print.svg")
                  for p in output.parent.glob(pattern + s))


def print_files(book) -> list[tuple[int, Drawing]]:
    """(page number, print image) for every strip page: the page's strips as printed (tiles,
    labels, arrows), at the page's size and place, without its cut lines, marks, title or
    legend: the image Cricut Design Space prints with its own sensor marks and cuts round
    (its cut line is the outline of what the image covers: the strips' outlines, so without the
    page's bleed; Design Space bleeds the image itself)."""
    out = []
    for n in book.strip_pages:
        page = book.drawing.sheets[n - 1]
        layers = tuple(x for x in page.layers
                       if x.name not in ("page", "cut", "bleed", "registration"))
        sheet = Sheet(page.width, page.height, layers, f"page {n}: print image")
        out.append((n, Drawing((sheet,), f"{book.drawing.title}: print image of page {n}",
                               (*book.drawing.metadata, ("print_image", str(n))))))
    return out


def cut_files(book) -> list[tuple[int, Drawing]]:
    """(page number, cut Drawing) for every strip page: the page's size, the strips' outlines
    at their printed place, cut from the top-left corner (where cutters start) onwards; the
    metadata item ``printed_page`` names the page (the kit page draws the cuts over it)."""
    out = []
    for n in book.strip_pages:
        page = book.drawing.sheets[n - 1]
        outlines = [p.cut for k, p in book.pieces if k == n]
        rings = ordered_outlines(outlines, (0.0, page.height))
        sheet = Sheet(page.width, page.height, (cut_layer(rings),), f"page {n}: cut")
        out.append((n, Drawing((sheet,), f"{book.drawing.title}: cut file of page {n}",
                               (*book.drawing.metadata, ("printed_page", str(n))))))
    return out
