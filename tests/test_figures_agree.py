"""A figure printed in the wrong unit: the figures a maker reads on the kit page, in the
command's summary line and on the printed assembly page (read back by poppler's pdftotext)
equal the ``--json`` summary's, each converted from the unit the JSON key states (``_m``,
``_mm``, ``_min``) to the unit printed beside it."""

from __future__ import annotations

import json
import re
import subprocess

import html5lib
import pytest
from click.testing import CliRunner

from weavecut import kitpage
from weavecut.cli import cli

from .test_readback import program

PUZZLE = ["puzzle", "--levels", "2", "--size", "20cm"]
STRANDS = ["strands", "square-grid:2x2", "--tile-size", "20mm", "--cutter", "silhouette"]


def run(*args) -> str:
    result = CliRunner().invoke(cli, [str(a) for a in args])
    assert result.exit_code == 0, result.output
    return result.output


def texts(page) -> tuple[str, str]:
    """The visible text of the kit page ``page`` and of an index page linking it (the card
    with the figures a maker plans with)."""
    index = page.with_name("index.html")
    kitpage.write_index(index, "builds", [page])
    return page_text(page), page_text(index)


def page_text(path) -> str:
    tree = html5lib.parse(path.read_text(encoding="utf-8"), namespaceHTMLElements=False)
    body = tree.find("body")
    return " ".join(" ".join(body.itertext()).split())


@pytest.fixture(scope="module")
def puzzle(tmp_path_factory):
    root = tmp_path_factory.mktemp("figures")
    (root / "a").mkdir()
    figures = json.loads(run("-q", *PUZZLE, "-o", root / "a", "--json", "--html",
                             root / "a" / "page.html"))
    said = run(*PUZZLE, "-o", root / "b")
    return figures, said, *texts(root / "a" / "page.html")


@pytest.fixture(scope="module")
def strands(tmp_path_factory):
    root = tmp_path_factory.mktemp("figures")
    for sub in "ab":
        (root / sub).mkdir()
    figures = json.loads(run("-q", *STRANDS, "-o", root / "a" / "s.pdf", "--json", "--html",
                             root / "a" / "page.html"))
    said = run(*STRANDS, "-o", root / "b" / "s.pdf")
    return figures, said, *texts(root / "a" / "page.html"), root / "a" / "s.pdf"


def test_the_puzzles_kit_page_states_the_json_figures(puzzle):
    """The index card: per way of cutting its length (m), sheets and time (min), and the
    finished size (mm); the kit page: each cut file's size and cut length."""
    figures, _, text, card = puzzle
    found = re.findall(r"(\w+) cut: ([\d.]+) m on (\d+) sheets?, about (\d+) min", card)
    assert sorted(m for m, *_ in found) == sorted(figures["modes"])
    for mode, metres, sheets, minutes in found:
        f = figures["modes"][mode]
        assert float(metres) == pytest.approx(f["cut_length_m"], abs=0.05 + 1e-9), mode
        assert int(sheets) == f["sheets"]
        assert int(minutes) == pytest.approx(f["time_min"], abs=0.5 + 1e-9), mode
    (w, h), = re.findall(r"(\d+) × (\d+) mm finished", card)
    assert [int(w), int(h)] == pytest.approx(figures["frame_mm"], abs=0.5 + 1e-9)
    for mode, name in (("shared", "puzzle-shared-cut"), ("separate", "puzzle-separate-sheet-1")):
        (w, h, metres), = re.findall(
            rf"{name} LightBurn: .*? ([\d.]+) × ([\d.]+) mm · cut ([\d.]+) m ", text)
        assert float(metres) == pytest.approx(figures["modes"][mode]["cut_length_m"],
                                              abs=0.005 + 1e-9)
    assert [float(w), float(h)] == figures["sheet_mm"]


def test_the_puzzles_summary_states_the_json_figures(puzzle):
    figures, said, *_ = puzzle
    for mode, f in figures["modes"].items():
        (cut, paths, travel, sheets, minutes), = re.findall(
            rf"{mode}: cut ([\d.]+) m in (\d+) paths, travel ([\d.]+) m, (\d+) sheets?, "
            r"about ([\d.]+) min", said)
        assert float(cut) == pytest.approx(f["cut_length_m"], abs=0.005 + 1e-9)
        assert float(travel) == pytest.approx(f["travel_m"], abs=0.005 + 1e-9)
        assert (int(paths), int(sheets)) == (f["paths"], f["sheets"])
        assert float(minutes) == pytest.approx(f["time_min"], abs=0.05 + 1e-9)
    (diagonal, w, h), = re.findall(r"frame: ([\d.]+) mm diagonal, ([\d.]+) x ([\d.]+) mm", said)
    assert float(diagonal) == pytest.approx(figures["frame_diagonal_mm"], abs=0.5)
    assert [float(w), float(h)] == pytest.approx(figures["frame_mm"], abs=0.05 + 1e-9)


def test_the_strand_books_figures_agree_on_the_page_the_summary_and_the_pdf(strands):
    figures, said, text, card, pdf = strands
    cutter = figures["cutter"]
    (sheets, metres), = re.findall(r"(\d+) cut sheets?, ([\d.]+) m of cuts", card)
    assert int(sheets) == figures["pages"]["strip"]
    assert f"{sheets} cut sheet{'s' * (int(sheets) != 1)}," in card  # "1 cut sheet"
    assert float(metres) == pytest.approx(cutter["cut_length_mm"] / 1000, abs=0.05 + 1e-9)
    (metres,) = re.findall(r"s-p03-cut .*? mm · cut ([\d.]+) m ", text)
    assert float(metres) == pytest.approx(cutter["cut_length_mm"] / 1000, abs=0.005 + 1e-9)
    (metres, feature), = re.findall(r"([\d.]+) m of cuts, smallest feature ([\d.]+) mm", said)
    assert float(metres) == pytest.approx(cutter["cut_length_mm"] / 1000, abs=0.05 + 1e-9)
    assert float(feature) == pytest.approx(cutter["min_feature_mm"], abs=0.05 + 1e-9)
    printed = subprocess.run([program("pdftotext"), "-f", "1", "-l", "1", str(pdf), "-"],
                             check=True, capture_output=True, text=True).stdout
    printed = " ".join(printed.split())
    (w, h, across), = re.findall(
        r"Finished model about ([\d.]+) x ([\d.]+) cm, octagons ([\d.]+) mm across", printed)
    assert [float(w) * 10, float(h) * 10] == pytest.approx(figures["model_mm"], abs=0.5 + 1e-9)
    assert float(across) == pytest.approx(figures["tile_size_mm"], abs=0.05 + 1e-9)
