"""A kit page's cards and data block read back (#34: mutants of kitpage no test killed): a laser
file's settings as the puzzle's JSON gives them, the summary without its list of files, a PDF's
thumbnails alone in a card as wide as the row past four pages, a cut sheet's picture opening a
file a browser or CAD opens, and the index's words of a kit of no known kind."""

from __future__ import annotations

import json
import tomllib
from dataclasses import replace
from pathlib import Path

import html5lib
import pytest
from click.testing import CliRunner

from weavecut import export, kitpage
from weavecut.cli import cli
from weavecut.fileio import recording
from weavecut.kitpage import document, overview
from weavecut.layout.drawing import Drawing, Layer, Sheet, Style, polygons_from_rings
from weavecut.layout.lasersetup import laser_job, material

ROOT = Path(__file__).resolve().parents[1]

SQUARE = [(10, 10), (60, 10), (60, 60), (10, 60)]
COLOUR = {"#ff0000": "red", "#0000ff": "blue", "#000000": "black"}  # LightBurn's layers


def parse(text: str):
    return html5lib.HTMLParser(strict=True, namespaceHTMLElements=False).parse(text)


def cards(text: str) -> dict[str, object]:
    """The file cards of a page by their heading."""
    return {"".join(li.find("h3").itertext()): li for li in parse(text).iter("li")
            if "card" in li.get("class", "").split() and li.find("h3") is not None}


def said(card) -> str:
    return "".join(next(p for p in card.iter("p") if p.get("class") == "for").itertext())


def square(sheets: int = 1, role: str = "paint", metadata=()) -> Drawing:
    layer = Layer("shapes", role, (polygons_from_rings([SQUARE], Style("#ff0000", 0.5)),))
    return Drawing(tuple(Sheet(210.0, 297.0, (layer,), f"page {n}") for n in range(sheets)),
                   "test", metadata=tuple(metadata))


@pytest.fixture
def puzzle(tmp_path):
    """A small puzzle kit: its folder, what the command printed and its run as recorded (each
    test makes the page itself: mutation testing credits a function to the test that calls
    it, not to a fixture)."""
    folder = tmp_path / "kit"
    with recording() as record:
        result = CliRunner().invoke(cli, ["puzzle", "--levels", "2", "--size", "20cm", "--mode",
                                          "shared", "-o", str(folder)])
        assert result.exit_code == 0, result.output
    return folder, result.stdout, kitpage.Run.of(record, "weave-cut puzzle", "puzzle")


def test_a_puzzle_laser_files_card_gives_each_operations_settings_from_its_json(puzzle):
    """Each operation of the cut in the order the JSON says its layers run, in its colour in
    the laser preset, at the speed and power of the JSON's operations."""
    folder, _, run = puzzle
    text = document.page("kit", [run], folder.parent)
    figures = json.loads((folder / "puzzle-summary.json").read_text())
    ops, layers = figures["operations"], figures["modes"]["shared"]["layers"]
    roles = list(dict.fromkeys(layer.split("-")[0] for layer in layers))
    assert roles == ["score", "cut"] and ops["cut"]["speed_mm_s"] != ops["score"]["speed_mm_s"]
    laser = tomllib.loads((ROOT / "templates" / "laser" / "lightburn.toml").read_text())
    settings = "; ".join(f"{role} {COLOUR[laser[role]['colour'].lower()]} at "
                         f"{ops[role]['speed_mm_s']:g} mm/s, {ops[role]['power_pct']:g} %"
                         for role in roles)
    assert said(cards(text)["puzzle-shared-cut"]) == f"LightBurn: {settings} (SVG or DXF)"


def test_the_page_says_the_commands_summary_but_its_list_of_files(puzzle):
    """The cards list the files: the summary's "files: ..." line is left out, every other line
    is said as the command printed it."""
    folder, printed, run = puzzle
    text = document.page("kit", [run], folder.parent)
    lines = [li.text for ul in parse(text).iter("ul") if ul.get("class") == "said" for li in ul]
    assert any(line.startswith("files: ") for line in printed.splitlines())
    assert lines == [line for line in printed.splitlines() if not line.startswith("files: ")]


@pytest.mark.parametrize("pages, wide", [(4, False), (5, True)])
def test_a_pdf_card_spans_the_row_past_four_pages_its_thumbnails_alone(tmp_path, pages, wide):
    with recording() as record:
        export.write(square(pages), tmp_path / "book.pdf")
    text = document.page("kit", [kitpage.Run.of(record, "weave-cut strands")], tmp_path)
    card = cards(text)["book"]
    assert ("wide" in card.get("class").split()) == wide
    (link,) = [a for a in card.iter("a") if a.get("class") == "pages"]
    assert [img.get("alt") for img in link] == [f"page {n} of {pages} of book.pdf"
                                                for n in range(1, pages + 1)]
    assert not "".join(link.itertext()).strip() and all(not (img.tail or "").strip()
                                                         for img in link)


def test_a_cut_sheets_picture_opens_its_dxf_where_it_has_no_svg(tmp_path):
    """A LightBurn project first, then the DXF: the picture links the DXF (a browser or a CAD
    program opens it), as the alt text names it."""
    cut = square(role="cut", metadata=(("card", "#0b3c5d"),))
    with recording() as record:
        export.write(cut, tmp_path / "sheet.lbrn2", job=laser_job(material("card-300gsm")))
        export.write(cut, tmp_path / "sheet.dxf")
    text = document.page("kit", [kitpage.Run.of(record, "weave-cut strands")], tmp_path)
    card = cards(text)["sheet"]
    picture = next(a for a in card.iter("a") if a.find("img") is not None)
    assert picture.get("href") == "sheet.dxf"
    assert picture.find("img").get("alt") == "sheet.dxf: card #0b3c5d"


def test_a_kit_of_no_known_kind_names_none_on_its_index_card(tmp_path):
    """A command the index has no words for (levels): its page's data block gives the kind as
    "" and the index card says no kind (not "None")."""
    (tmp_path / "k").mkdir()
    with recording() as record:
        export.write(square(), tmp_path / "k" / "picture.svg")
    page = tmp_path / "k" / "index.html"
    kitpage.write(page, "k", [kitpage.Run.of(record, "weave-cut levels pentagon", "levels")])
    assert overview.read(page)["items"] == [{"kind": "", "facts": []}]
    index = document.index("builds", [page], tmp_path)
    (card,) = [li for li in parse(index).iter("li") if li.get("class") == "card"]
    assert [p.text for p in card.iter("p") if p.get("class") == "for"] == [None]


def test_a_modes_figures_missing_from_its_json_are_said_as_none(tmp_path):
    """A cut mode whose JSON lacks its length, sheets or time (a JSON of another version): the
    index's figures say none of them, not a length of its own."""
    (tmp_path / "s.json").write_text('{"modes": {"shared": {}}}')
    run = kitpage.Run("weave-cut puzzle", {tmp_path / "s.json": None}, (), "puzzle")
    (item,) = overview.items([run], len)
    assert item == {"kind": overview.COMMANDS["puzzle"],
                    "facts": ["shared cut: 0.0 m on 0 sheets, about 0 min"]}
    run = replace(run, name="levels")
    assert overview.items([run], len)[0]["kind"] == ""
