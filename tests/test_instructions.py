"""Every product's PDF read back as a maker reads it (poppler's pdftotext, page by page): every
page reference in it ("page 2", "p. 3-4", "pages 4-5", the footer "page 1 / 3", a painting
guide's "row 1/2, column 3/3") names a page of that file, and each product speaks of what the
maker holds: the laser card's words are of card, a laser and engraving, the printed strips'
of paper, print and scissors. The products are made by the command, as a maker runs it."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner

from weavecut.cli import cli as main

from .test_readback import program

GRID = ["square-grid:2x2", "--tile-size", "20mm"]
FLOWER = ["pentagon-flower", "--levels", "2", "--size", "10cm"]  # crossings on a page of their own
# (product, command, the PDFs it writes)
PRODUCTS = {
    "printed": (["strands", *GRID, "-o", "sq.pdf"], ["sq.pdf"]),
    "printed, crossing pages": (["strands", *FLOWER, "-o", "pf.pdf"], ["pf.pdf"]),
    "print and cut": (["strands", *GRID, "--cutter", "silhouette", "-o", "cut.pdf"],
                      ["cut.pdf"]),
    "laser card": (["strands", *GRID, "--laser-card", "-o", "card"],
                   ["card/strands-assembly.pdf"]),
    "laser card, crossing pages": (["strands", *FLOWER, "--laser-card", "-o", "pfcard"],
                                   ["pfcard/strands-assembly.pdf"]),
    "ball": (["strands", "dodecahedron", "--levels", "1", "--project", "sphere", "--size",
              "12cm", "-o", "ball.pdf"], ["ball.pdf"]),
    "puzzle": (["puzzle", "--levels", "3", "-o", "pz"],
               ["pz/puzzle-front-guide-a4.pdf", "pz/puzzle-back-guide-a4.pdf"]),
}
FOOTER = re.compile(r"\bpage (\d+) / (\d+)\b")
REFERENCE = re.compile(r"\b(?:p\.|pages?) (\d+)(?: ?- ?(\d+))?")
# what a page points at on the page it stands on, or names the page of ("the sizes above")
PAGELESS = re.compile(r"\b(?:sizes?|list|table|figures|values|settings|marks) (?:above|below)\b")
TILE = re.compile(r"\brow (\d+)/(\d+), column (\d+)/(\d+)\b")
CARD_SHEET = re.compile(r"\bstrands-card-(\d\d)-([0-9a-f]{6})\b")
# words that belong to one product only
PRINTED_ONLY = ("red line", "printed light", "Print the strip pages", "Print at 100 %",
                "printed pages", "scissors", "coloured side up", "grey band")
CARD_ONLY = ("engrave", "score line", "laser", "card sheet")


@pytest.fixture(scope="module")
def made(tmp_path_factory) -> Path:
    """The folder every product is made in (``-o`` of each command inside it)."""
    folder = tmp_path_factory.mktemp("products")
    for command, _ in PRODUCTS.values():
        out = command.index("-o") + 1
        args = [*command[:out], str(folder / command[out]), *command[out + 1:]]
        res = CliRunner().invoke(main, ["-q", *args])
        assert res.exit_code == 0, res.output
    return folder


def pages_of(path: Path) -> list[str]:
    """The text of every page of ``path``, whitespace made single spaces."""
    text = subprocess.run([program("pdftotext"), "-layout", str(path), "-"], check=True,
                          capture_output=True, text=True).stdout
    pages = text.split("\f")
    if pages and not pages[-1].strip():
        pages = pages[:-1]
    return [" ".join(p.split()) for p in pages]


def reference_problems(pages: list[str]) -> list[str]:
    """Every page reference in ``pages`` that names no page of them: a footer that is not
    "page i / n" on page i of n, "p. N", "page N", "pages N-M" outside 1..n, a painting
    guide's "row r/R, column c/C" outside its grid or twice, more grid cells than pages."""
    n, out, cells = len(pages), [], []
    for i, text in enumerate(pages, start=1):
        feet = FOOTER.findall(text)
        out += [f"page {i}: footer {a} / {b}" for a, b in feet if (int(a), int(b)) != (i, n)]
        for m in REFERENCE.finditer(FOOTER.sub("", text)):
            out += [f"page {i}: {m[0]!r} of {n} pages" for g in m.groups()
                    if g is not None and not 1 <= int(g) <= n]
        out += [f"page {i}: {m[0]!r} names no page" for m in PAGELESS.finditer(text)]
        for m in TILE.finditer(text):
            r, rows, c, cols = map(int, m.groups())
            cells.append((r, c))
            if not (1 <= r <= rows and 1 <= c <= cols and rows * cols <= n):
                out.append(f"page {i}: {m[0]!r} of {n} pages")
    if len(set(cells)) != len(cells):
        out.append(f"a guide's tile named twice: {sorted(cells)}")
    return out


def test_the_reference_check_finds_what_the_laser_card_used_to_say():
    """The check itself, on the laser card's pages as they were (the printed book's words on a
    3-page file), and on a guide with a tile named twice; well-formed pages pass."""
    old = ["weave-cut strands page 1 / 8 Print the strip pages once (p. 3-8). Where each strip "
           "is: p. 3: A1; p. 4: A2. Weaving steps: page 2.",
           "page 2 / 8 check every crossing against page 1, marks with the sizes above",
           "Card colours"]
    assert reference_problems(old) == [
        "page 1: footer 1 / 8", "page 1: 'p. 3-8' of 3 pages", "page 1: 'p. 4' of 3 pages",
        "page 2: footer 2 / 8", "page 2: 'sizes above' names no page"]
    good = ["page 1 / 3 steps: page 2; crossings: pages 2-3", "page 2 / 3 see p. 1",
            "page 3 / 3"]
    assert reference_problems(good) == []
    guide = ["key", "row 1/1, column 1/2", "row 1/1, column 1/2"]
    assert reference_problems(guide) == ["a guide's tile named twice: [(1, 1), (1, 1)]"]


@pytest.mark.slow
@pytest.mark.parametrize("product", PRODUCTS)
def test_every_page_reference_names_a_page_of_its_file(made, product):
    for name in PRODUCTS[product][1]:
        pages = pages_of(made / name)
        assert len(pages) >= 2
        assert reference_problems(pages) == [], name
        if product != "puzzle":  # a strand book numbers every page
            assert all(len(FOOTER.findall(p)) == 1 for p in pages), name


@pytest.mark.parametrize("product", [p for p in PRODUCTS if p.startswith("laser card")])
def test_the_laser_card_speaks_of_card_and_names_its_own_files(made, product):
    """The card's instructions use none of the printed strips' words and name the card, the
    laser, engraving and scoring; every card sheet they name ("strands-card-03-0f7173",
    "sheet 3") is a file in the folder, as .svg and .dxf, and page 1 names them all."""
    path = made / PRODUCTS[product][1][0]
    text = " ".join(pages_of(path))
    assert [w for w in PRINTED_ONLY if w in text] == []
    assert all(w in text for w in ("engraved", "score", "laser", "card"))
    files = {f.stem for f in path.parent.glob("strands-card-*.svg")}
    assert files == {f.stem for f in path.parent.glob("strands-card-*.dxf")} and files
    named = {f"strands-card-{n}-{c}" for n, c in CARD_SHEET.findall(text)}
    assert named and named <= files
    sheets = {int(n) for n in re.findall(r"\bsheets? (\d+)", text)}
    assert sheets == set(range(1, len(files) + 1))


@pytest.mark.parametrize("product", ["printed", "printed, crossing pages", "ball"])
def test_the_printed_strips_speak_of_paper(made, product):
    text = " ".join(pages_of(made / PRODUCTS[product][1][0]))
    assert [w for w in CARD_ONLY if w in text] == []
    assert "Print" in text


CUT_FILE = re.compile(r"\b(cut-p\d\d-cut)\.svg\b")


def test_print_and_cut_says_where_its_cut_files_are_and_how_the_cutter_uses_them(made):
    """The print-and-cut book is no printed book with marks added: it says the cut files lie
    beside it, every strip page names its own cut file (which is there, as .svg and .dxf), and
    it says how print and cut works: registration marks the cutter reads, the page's cut file
    opened in the cutter's software (the DXF, which the free editions open), the machine named
    as its maker writes it. No scissors, no red line to cut along."""
    path = made / PRODUCTS["print and cut"][1][0]
    pages = pages_of(path)
    text = " ".join(pages)
    files = {f.stem for f in path.parent.glob("cut-p*-cut.svg")}
    assert files and files == {f.stem for f in path.parent.glob("cut-p*-cut.dxf")}
    strip_pages = [i for i, p in enumerate(pages, start=1) if "Strips:" in p]
    for i in strip_pages:  # each strip page names its own cut file
        assert CUT_FILE.findall(pages[i - 1]) == [f"cut-p{i:02d}-cut"]
    assert {f"cut-p{i:02d}-cut" for i in strip_pages} == files
    assert "beside this PDF" in pages[0] and "cut-p03-cut.svg or .dxf" in pages[0]
    for words in ("registration marks", "5 mm square top-left", "10 mm from the page's edges",
                  "open its cut file (cut-pNN-cut.dxf", "Basic Edition",
                  "your Silhouette cutter", "Print and cut (Silhouette)",
                  "let the cutter read the marks"):
        assert words in text, words
    # walk of issue #29: page 2 set the marks "with the sizes above", which stand on page 1
    marks = "a 5 mm square top-left and L corners top-right and bottom-left, 10 mm from the " \
            "page's edges"
    assert marks in pages[0] and f"registration marks as page 1 gives them ({marks})" in pages[1]
    assert "The DXF's origin (0, 0) is the page's bottom-left corner" in pages[1]
    assert re.findall(r"\bsilhouette\b", text) == []  # the preset's name, not the brand
    assert [w for w in ("red line", "scissors", "Print the strip pages") if w in text] == []


def test_every_dxf_has_its_pages_limits_and_extents_and_nothing_outside(made):
    """Walk of issue #29: the cut files said ezdxf's default limits (420 x 297 mm) and no
    extents, though page 2 says a cut file is the page. Every DXF the products write (cut
    pages, card sheets, puzzle sheets) passes ezdxf's audit, its limits and extents start at
    the origin and hold every entity; a print-and-cut page's are its printed page's size."""
    import ezdxf
    from ezdxf import bbox

    found = sorted(made.rglob("*.dxf"))
    assert {f.parent.name for f in found} >= {"card", "pz"} and any(
        f.name.startswith("cut-p") for f in found)
    for path in found:
        doc = ezdxf.readfile(path)
        assert not doc.audit().has_errors, path
        low, high = doc.header["$LIMMIN"], doc.header["$LIMMAX"]
        assert tuple(low) == (0, 0) and tuple(doc.header["$EXTMIN"]) == (0, 0, 0), path
        assert tuple(doc.header["$EXTMAX"])[:2] == tuple(high), path
        box = bbox.extents(doc.modelspace())
        assert box.has_data and min(box.extmin.x, box.extmin.y) >= -1e-6, path
        assert box.extmax.x <= high[0] + 1e-6 and box.extmax.y <= high[1] + 1e-6, path
        if path.name.startswith("cut-p"):
            assert tuple(high) == (210, 297), path  # the A4 strip page it cuts


def test_a_cricut_strip_page_names_its_files_whole(tmp_path):
    """Walk of issue #29: on a Cricut kit's strip pages the subtitle stopped at "cut file:
    ..." (the recipe's output name): every strip page names its print image and its cut file
    in full, whatever its strips' list leaves out."""
    stem = "square-grid-strands"  # recipe square-grid-cut-by-machine
    res = CliRunner().invoke(main, ["-q", "strands", *GRID, "--cutter", "cricut", "--page",
                                    "letter", "-o", str(tmp_path / f"{stem}.pdf")])
    assert res.exit_code == 0, res.output
    pages = pages_of(tmp_path / f"{stem}.pdf")
    for i in range(3, len(pages) + 1):  # the strip pages
        assert (f"Print image: {stem}-p{i:02d}-print.svg; cut file: {stem}-p{i:02d}-cut.svg "
                "/ .dxf.") in pages[i - 1], pages[i - 1][:300]
