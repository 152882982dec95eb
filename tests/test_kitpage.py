"""The kit page (weavecut.kitpage): strict HTML5 (html5lib), alt text and heading order,
contrast, links to files that exist, PDF thumbnails per page (pdftoppm or weave-cut's own PNG
writer), what each file is for, the same bytes twice; written by build, refused where it would
replace a file weave-cut did not write, and by --html."""

from __future__ import annotations

import base64
import io
import json
import re
from dataclasses import replace
from pathlib import Path
from urllib.parse import unquote

import html5lib
import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from PIL import Image

from weavecut import export, kitpage
from weavecut.cli import cli
from weavecut.cli.recipe import PAGE
from weavecut.manifest import MANIFEST
from weavecut.fileio import recording, write_atomic
from weavecut.kitpage import document as kp
from weavecut.kitpage import previews
from weavecut.layout.contrast import MIN_CONTRAST, contrast_ratio, rgb
from weavecut.layout.drawing import (Drawing, Layer, Sheet, Style, polygons_from_rings,
                                     polylines_from_lines)

from .test_readback import pdfinfo, program

SQUARE = [(10, 10), (60, 10), (60, 60), (10, 60)]


def drawing(sheets: int = 1, hairline: bool = False, role: str = "paint") -> Drawing:
    style = Style("#ff0000", 0.0) if hairline else Style("#000000", 0.5, "#1b4f72")
    layer = Layer("shapes", role, (polygons_from_rings([SQUARE], style),))
    return Drawing(tuple(Sheet(210.0, 297.0, (layer,), f"page {n}") for n in range(sheets)),
                   "test")


def run_of(folder: Path) -> kitpage.Run:
    """One run writing every kind of output into ``folder``."""
    with recording() as record:
        export.write(drawing(), folder / "picture.svg")
        export.write(drawing(hairline=True, role="cut"), folder / "cut.svg")
        export.write(drawing(hairline=True, role="cut"), folder / "cut.dxf")
        export.write(drawing(3), folder / "pages.pdf")
        export.write(drawing(), folder / "raster.png")
        write_atomic(folder / "summary.json", b'{"laser": "lightburn", "speed_mm_s": 20}\n')
    return kitpage.Run.of(record, "weave-cut test --o <x&y>")


def parse(text: str):
    """The page as an element tree; html5lib in strict mode raises on any parse error."""
    return html5lib.HTMLParser(strict=True, namespaceHTMLElements=False).parse(text)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    folder = tmp_path_factory.mktemp("kit")
    runs = [run_of(folder)]
    kitpage.write(folder / "index.html", "test & <kit>", runs)
    return folder, runs, (folder / "index.html").read_text(encoding="utf-8")


def test_page_is_strict_html5_with_escaped_text(built):
    _, _, text = built
    assert text.startswith("<!DOCTYPE html>\n")
    tree = parse(text)
    assert tree.find("head/title").text == "test & <kit>"
    assert "weave-cut test --o <x&y>" in "".join(tree.find(".//code").itertext())


def test_the_parser_is_strict():
    """Plant the bug: a page without a doctype or with a stray end tag is refused."""
    with pytest.raises(html5lib.html5parser.ParseError):
        parse("<html><head><title>x</title></head><body></body></html>")
    with pytest.raises(html5lib.html5parser.ParseError):
        parse("<!DOCTYPE html><html><head><title>x</title></head><body></p></body></html>")


def test_every_image_has_alt_text_and_headings_are_in_order(built):
    tree = parse(built[2])
    images = tree.findall(".//img")
    assert len(images) == 1 + 1 + 3 + 1  # picture.svg, cut (svg+dxf: one card), 3 pages, png
    assert all(img.get("alt", "").strip() for img in images)
    levels = [int(el.tag[1]) for el in tree.iter() if re.fullmatch(r"h[1-6]", str(el.tag))]
    assert levels[0] == 1 and levels.count(1) == 1
    assert all(b <= a + 1 for a, b in zip(levels, levels[1:])), levels


def test_colours_have_contrast():
    """Every text colour of the style sheet is one of PAIRS, and every pair reads (WCAG AA)."""
    assert all(contrast_ratio(fg, bg) >= MIN_CONTRAST for fg, bg in kp.PAIRS)
    used = set(re.findall(r"(?<![-\w])color:(#[0-9a-f]{6})", kp.STYLE))
    assert used and used <= {fg for fg, _ in kp.PAIRS}
    backgrounds = set(re.findall(r"background:(#[0-9a-f]{6})", kp.STYLE))
    assert backgrounds <= {bg for _, bg in kp.PAIRS}


def test_links_and_pictures_point_to_the_files(built):
    folder, runs, text = built
    tree = parse(text)
    refs = [a.get("href") for a in tree.iter("a")] + [i.get("src") for i in tree.iter("img")]
    local = {unquote(r) for r in refs if not r.startswith("data:")}
    assert local == {p.name for p in runs[0].files}  # every output linked, nothing else
    assert all((folder / r).is_file() for r in local)


def test_a_pdf_shows_every_page_with_pdftoppm_or_without(built, monkeypatch):
    folder, runs, _ = built
    program("pdftoppm")
    pdf = folder / "pages.pdf"
    shown, by = previews.pdf_thumbnails(pdf, runs[0].files[pdf])
    monkeypatch.setattr(previews.shutil, "which", lambda name: None)
    drawn, by_us = previews.pdf_thumbnails(pdf, runs[0].files[pdf])
    assert (by, by_us) == ("pdftoppm", "weave-cut")
    for thumbs in (shown, drawn):
        assert len(thumbs) == 3
        for t in thumbs:
            w, h = Image.open(io.BytesIO(t)).size
            assert h == previews.THUMB_PX and abs(w / h - 210 / 297) < 0.01


def test_what_each_file_is_for(built):
    text = built[2]
    assert "print at 100 % on A4" in text
    assert "LightBurn: cut red at 20 mm/s (SVG or DXF)" in text
    assert "3 pages of 210 × 297 mm" in text


def test_hairlines_are_thickened_in_previews_only():
    d = drawing(hairline=True, role="cut")
    seen = previews.visible(d).sheets[0].layers[0].shapes[0].style.stroke_width
    assert seen == pytest.approx(210 / previews.PREVIEW_PX)
    assert d.sheets[0].layers[0].shapes[0].style.stroke_width == 0.0


@pytest.mark.parametrize("seed", range(5))
def test_cut_length_matches_shapely(seed):
    rng = np.random.default_rng(seed)
    rings = [rng.uniform(0, 100, (rng.integers(3, 8), 2)) for _ in range(rng.integers(1, 6))]
    lines = [rng.uniform(0, 100, (rng.integers(2, 8), 2)) for _ in range(rng.integers(1, 6))]
    expected = (sum(shapely.LinearRing(r).length for r in rings)
                + sum(shapely.LineString(line).length for line in lines))
    got = kp._length(polygons_from_rings(rings)) + kp._length(polylines_from_lines(lines))
    assert got == pytest.approx(expected)


def test_same_runs_same_bytes(built):
    folder, runs, text = built
    assert kp.page("test & <kit>", runs, folder) == text


def pixels(data: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))


def near_outline(image: np.ndarray, ring, sheet_height: float, px: float) -> np.ndarray:
    """(H, W) whether each pixel centre lies within ``px`` pixels of ``ring`` (mm, y up)."""
    scale = image.shape[0] / sheet_height
    y, x = np.mgrid[: image.shape[0], : image.shape[1]] + 0.5
    centres = shapely.points(x / scale, sheet_height - y / scale)
    return (shapely.distance(centres, shapely.LinearRing(ring)) <= px / scale).reshape(x.shape)


def cut_file_pictures(tmp_path, metadata, pages: int = 1) -> tuple[dict, Drawing, str]:
    """The kit page of a printed PDF and a cut file of the square with ``metadata``: the
    pictures by alt text, the printed drawing, the page."""
    printed = drawing(pages)
    cut = replace(drawing(hairline=True, role="cut"), metadata=metadata)
    with recording() as record:
        export.write(printed, tmp_path / "strips.pdf")
        export.write(cut, tmp_path / "strips-p01-cut.svg")
        export.write(cut, tmp_path / "strips-p01-cut.dxf")
    text = kp.page("cuts", [kitpage.Run.of(record, "weave-cut strands")], tmp_path)
    pictures = {img.get("alt"): img.get("src") for img in parse(text).iter("img")}
    return pictures, printed, text


def png_of(src: str) -> bytes:
    return base64.b64decode(src.removeprefix("data:image/png;base64,"))


def test_a_print_and_cut_file_is_shown_over_its_printed_page(tmp_path):
    pictures, printed, text = cut_file_pictures(tmp_path, (("printed_page", "1"),))
    over = pixels(png_of(pictures["strips-p01-cut.svg: page 1 as printed"]))
    plain = pixels(previews.sheet_png(printed.sheets[0], previews.CUT_PX))
    assert over.shape == plain.shape and over.shape[0] == previews.CUT_PX
    changed = (np.abs(over.astype(int) - plain) > 8).any(axis=2)  # beyond smoothing noise
    red = near_colour(over, previews.CUT_OVER)
    assert red.sum() > 4 * 50 * over.shape[0] / 297  # both pixels of every side's length
    assert not (changed & ~near_outline(over, SQUARE, 297, 2.5)).any()  # nothing else moved
    assert red[near_outline(over, SQUARE, 297, 0.5)].mean() > 0.9  # the cut over the outline
    assert "the desktop cutter cuts this on page 1 as printed (SVG or DXF)" in text


def test_a_card_sheet_is_shown_on_its_card_colour(tmp_path):
    pictures, _, text = cut_file_pictures(tmp_path, (("card", "#0b3c5d"),))
    card = pixels(png_of(pictures["strips-p01-cut.svg: card #0b3c5d"]))
    lines = near_outline(card, SQUARE, 297, 0.5)
    assert near_colour(card[~near_outline(card, SQUARE, 297, 2.5)], "#0b3c5d", 8).all()
    assert near_colour(card[lines], "#ffffff").mean() > 0.9  # white cuts read on dark card
    assert "laser-cut from card #0b3c5d (SVG or DXF)" in text


@pytest.mark.parametrize("metadata", [(("printed_page", "4"),), (("card", "navy\"/>"),)])
def test_a_cut_file_without_its_page_or_colour_gets_the_plain_preview(tmp_path, metadata):
    pictures, _, _ = cut_file_pictures(tmp_path, metadata, pages=3)
    cut = [src for alt, src in pictures.items() if alt.startswith("strips-p01-cut")]
    assert len(cut) == 1 and cut[0].startswith("data:image/svg+xml")


def near_colour(image: np.ndarray, colour: str, tolerance: int = 60) -> np.ndarray:
    """Whether each pixel is ``colour`` within ``tolerance`` per channel (lines are smoothed)."""
    want = np.round(255 * np.array(rgb(colour)))
    return (np.abs(image.astype(float) - want) <= tolerance).all(axis=-1)


def cli_run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


RECIPE = """[recipe]
name = "little"
[[job]]
command = "weave"
input = "square-grid"
levels = 1
output = "weave.svg"
[[job]]
command = "stats"
input = "square-grid"
levels = 1
json = true
output = "stats.json"
"""


def test_build_writes_its_page_into_the_manifest(tmp_path):
    (tmp_path / "r.toml").write_text(RECIPE)
    out = tmp_path / "out"
    assert cli_run("build", tmp_path / "r.toml", "-o", out).exit_code == 0
    text = (out / PAGE).read_text(encoding="utf-8")
    tree = parse(text)
    assert tree.find("body//h1").text == "little"
    assert [h.text for h in tree.iter("h2")] == ["weave square-grid", "stats square-grid"]
    hrefs = {a.get("href") for a in tree.iter("a")}
    assert {"weave.svg", "stats.json"} <= hrefs
    assert PAGE in json.loads((out / MANIFEST).read_text())["files"]
    first = (out / PAGE).read_bytes()
    assert cli_run("build", tmp_path / "r.toml", "-o", out).exit_code == 0  # ours: replaced
    assert (out / PAGE).read_bytes() == first


def test_build_does_not_replace_a_page_it_did_not_write(tmp_path):
    (tmp_path / "r.toml").write_text(RECIPE)
    out = tmp_path / "out"
    out.mkdir()
    (out / PAGE).write_text("mine")
    result = cli_run("build", tmp_path / "r.toml", "-o", out)
    assert result.exit_code == 1 and "did not write it" in result.output
    assert (out / PAGE).read_text() == "mine" and not (out / "weave.svg").exists()
    assert cli_run("build", tmp_path / "r.toml", "-o", out, "--force").exit_code == 0


@pytest.mark.parametrize("job, message", [
    ('output = "index.html"', "page of the build"),
    ('output = "w.svg"\nhtml = "/tmp/elsewhere.html"', "unknown key 'html'"),
])
def test_a_recipe_cannot_write_pages(tmp_path, job, message):
    (tmp_path / "r.toml").write_text(
        f'[[job]]\ncommand = "weave"\ninput = "square-grid"\nlevels = 1\n{job}\n')
    result = cli_run("build", tmp_path / "r.toml", "-o", tmp_path / "out")
    assert result.exit_code == 1 and message in result.output, result.output


def test_html_option_writes_the_page_of_one_command(tmp_path):
    out = tmp_path / "w.svg"
    assert cli_run("weave", "square-grid", "--levels", "1", "-o", out).exit_code == 0
    assert not list(tmp_path.glob("*.html"))
    result = cli_run("weave", "square-grid", "--levels", "1", "-o", out, "--html",
                     tmp_path / "w.html")
    assert result.exit_code == 0, result.output
    tree = parse((tmp_path / "w.html").read_text(encoding="utf-8"))
    assert [a.get("href") for a in tree.iter("a")] == ["w.svg", "w.svg"]
    result = cli_run("weave", "square-grid", "--levels", "1", "-o", out, "--html", out)
    assert result.exit_code == 2 and "-o writes" in result.output, result.output


def test_the_index_links_every_page(built, tmp_path):
    folder = built[0]
    kitpage.write_index(tmp_path / "index.html", "builds", [folder / "index.html"])
    tree = parse((tmp_path / "index.html").read_text(encoding="utf-8"))
    (href,) = {a.get("href") for a in tree.iter("a")}  # its picture and its name
    assert (tmp_path / unquote(href)).resolve() == (folder / "index.html").resolve()


@pytest.mark.parametrize("args", [
    ["puzzle", "--levels", "2", "--size", "20cm", "-o", "{out}"],
    ["strands", "square-grid", "-o", "{out}/strands.pdf"],
    ["strands", "square-grid:2x2", "--tile-size", "20mm", "--cutter", "silhouette", "-o",
     "{out}/strands.pdf"],
])
def test_every_file_a_command_wrote_is_on_its_page(tmp_path, args):
    out = tmp_path / "kit"
    out.mkdir()
    result = cli_run(*[a.format(out=out) for a in args], "--html", out / "page.html")
    assert result.exit_code == 0, result.output
    tree = parse((out / "page.html").read_text(encoding="utf-8"))
    linked = {unquote(a.get("href")) for a in tree.iter("a")}
    assert linked == {p.name for p in out.iterdir()} - {"page.html", MANIFEST}
    assert all(img.get("alt") for img in tree.iter("img"))


def test_the_index_shows_each_build_as_a_card(tmp_path):
    """build/index.html: per build its picture (one that loads), what it makes and the figures
    a maker plans with, read from each kit page's data block and checked here against the files
    themselves (pdfinfo's page count, the puzzle's summary); a page without a block still gets
    its link."""
    pz, sq, bare = tmp_path / "pz", tmp_path / "sq", tmp_path / "bare"
    for folder in (pz, sq, bare):
        folder.mkdir()
    assert cli_run("puzzle", "--levels", "2", "--size", "20cm", "-o", pz,
                   "--html", pz / "index.html").exit_code == 0
    assert cli_run("strands", "square-grid", "-o", sq / "strands.pdf",
                   "--html", sq / "index.html").exit_code == 0
    (bare / "index.html").write_text("<!DOCTYPE html><title>old</title>")
    out = tmp_path / "site"
    out.mkdir()
    kitpage.write_index(out / "index.html", "builds",
                        [pz / "index.html", sq / "index.html", bare / "index.html"])
    tree = parse((out / "index.html").read_text(encoding="utf-8"))
    cards = {}
    for li in tree.iter("li"):
        (link,) = {a.get("href") for a in li.iter("a")}
        cards[(out / unquote(link)).resolve().parent.name] = li
        for img in li.iter("img"):
            src = img.get("src")
            if src.startswith("data:"):
                head, data = src.split(",", 1)
                assert head in ("data:image/png;base64", "data:image/svg+xml;base64")
                assert base64.b64decode(data)[:5] in (b"\x89PNG\r", b"<svg ", b"<?xml")
            else:
                assert (out / unquote(src)).is_file(), src
            assert img.get("alt")
    assert set(cards) == {"pz", "sq", "bare"}

    def said(name):
        return [" ".join("".join(p.itertext()).split()) for p in cards[name].iter("p")]

    pages = lambda folder: sum(int(pdfinfo(p)["Pages"]) for p in folder.glob("*.pdf"))  # noqa
    summary = json.loads((pz / "puzzle-summary.json").read_text())
    shared = summary["modes"]["shared"]
    assert said("pz")[0] == "two-sided jigsaw puzzle to laser-cut"
    assert f"{pages(pz)} printed pages" in said("pz")[1]
    assert (f"shared cut: {shared['cut_length_m']:.1f} m on {shared['sheets']} sheet"
            in said("pz")[1])
    assert said("sq") == ["woven paper model", f"{pages(sq)} printed pages"]
    assert list(cards["pz"].iter("img")) and not said("bare")


ODD_FOLDER = "kit #1 at 100% (a b)"
ODD_FILES = ("tile #2 50% off.svg", "pages %41 #.pdf", "cut #1.dxf", "raster 100%.png")


def odd_kit(root: Path) -> Path:
    """A kit page, itself named with a space and ``#``, in a folder whose name has a space,
    ``#`` and ``%``, linking files whose names have them too (``%41`` would read as "A" if it
    were left unescaped)."""
    folder = root / ODD_FOLDER
    folder.mkdir()
    with recording() as record:
        for name in ODD_FILES:
            kind = {"tile": drawing(), "pages": drawing(3), "cut": drawing(True, "cut"),
                    "raster": drawing()}[name.split()[0]]
            export.write(kind, folder / name)
    page = folder / "kit #1.html"
    kitpage.write(page, "odd names", [kitpage.Run.of(record, "weave-cut test")])
    return page


def opened(page: Path, ref: str) -> Path:
    """The file a browser opens for ``ref`` on ``page``: the reference resolved against the
    page's file: URL (a bare ``#`` starts a fragment, ``%XX`` is an escape), then the URL's
    path unescaped."""
    from urllib.parse import urljoin, urlparse
    from urllib.request import url2pathname
    return Path(url2pathname(urlparse(urljoin(page.as_uri(), ref)).path))


def test_links_open_files_named_with_a_space_hash_or_percent(tmp_path):
    page = odd_kit(tmp_path)
    tree = parse(page.read_text(encoding="utf-8"))
    refs = [a.get("href") for a in tree.iter("a")] + [i.get("src") for i in tree.iter("img")]
    files = {opened(page, r) for r in refs if not r.startswith("data:")}
    assert files == {page.parent / name for name in ODD_FILES}
    assert all(f.is_file() for f in files)
    index = tmp_path / "index.html"
    kitpage.write_index(index, "builds", [page])
    tree = parse(index.read_text(encoding="utf-8"))
    assert {opened(index, a.get("href")) for a in tree.iter("a")} == {page}


def cards(text: str) -> dict[str, dict]:
    """Per file card (by its name): what it is for, its facts, its links' texts and its
    pictures' alt texts, as a reader sees them."""
    out = {}
    for li in parse(text).iter("li"):
        if "card" not in li.get("class", "").split() or li.find("h3") is None:
            continue
        ps = {p.get("class"): "".join(p.itertext()) for p in li.iter("p")}
        out["".join(li.find("h3").itertext())] = {
            "for": ps.get("for"), "facts": ps.get("facts", "").split(" · "),
            "links": [a.text for a in li.iter("a") if a.text],
            "alts": [i.get("alt") for i in li.iter("img")]}
    return out


def test_each_card_says_what_its_files_are_for_and_links_each_format(built, tmp_path):
    """Every card of the test run: its purpose word for word, one link per file named by its
    format, a one-colour drawing without a colour count; and alone, a DXF (for CAD) and a
    drawing of two fills (its count)."""
    found = cards(built[2])
    assert {k: (v["for"], v["links"]) for k, v in found.items()} == {
        "picture": ("test: 1:1 in mm, to view, print or edit", ["SVG"]),
        "cut": ("LightBurn: cut red at 20 mm/s (SVG or DXF)",
                ["SVG", "DXF"]),
        "pages": ("print at 100 % on A4", ["PDF"]),
        "raster": ("test: picture for a screen", ["PNG"]),
        "summary": ("figures for scripts (JSON)", ["JSON"])}
    assert found["picture"]["alts"] == ["picture.svg: test"]
    assert not [f for f in found["picture"]["facts"] if "colours" in f]
    two = Drawing((Sheet(100.0, 100.0, (Layer("shapes", "paint", (polygons_from_rings(
        [SQUARE, [(x + 60, y) for x, y in SQUARE]], Style(None, 0.0),
        ["#1b4f72", "#f5b041"]),)),)),), "two")
    with recording() as record:
        export.write(drawing(), tmp_path / "plan.dxf")
        export.write(two, tmp_path / "two.svg")
    kitpage.write(tmp_path / "k.html", "alone", [kitpage.Run.of(record, "weave-cut test")])
    alone = cards((tmp_path / "k.html").read_text(encoding="utf-8"))
    assert alone["plan"]["for"] == kp.DXF_FOR and alone["plan"]["links"] == ["DXF"]
    assert "2 colours" in alone["two"]["facts"]


@pytest.mark.parametrize("name", ["epilog-uls", "lightburn", "ponoko"])
def test_a_laser_files_card_names_the_laser_by_its_presets_description(tmp_path, name):
    """Called in the test (the module's kit is built once, in a fixture, which mutation
    testing credits to the first test only): the description as the preset's TOML says it."""
    import tomllib

    from weavecut.kitpage import document

    preset = Path(__file__).resolve().parents[1] / "templates" / "laser" / f"{name}.toml"
    wanted = tomllib.loads(preset.read_text(encoding="utf-8"))["description"]
    assert document._laser_description(name) == wanted
    assert document._laser_description("no-such-laser") == "no-such-laser"


def test_the_page_counts_its_files_and_commands_in_words(tmp_path):
    """"7 files from 1 command", "14 files from 2 commands": a page of one run and of two,
    written in the test (not the module's fixture)."""
    from weavecut import __version__

    runs = [run_of(tmp_path)]
    n = len(runs[0].files)
    one = kitpage.document.page("kit", runs, tmp_path)
    assert f"{n} files from 1 command, made by weave-cut {__version__}." in one
    two = kitpage.document.page("kit", runs * 2, tmp_path)
    assert f"{2 * n} files from 2 commands, made by weave-cut {__version__}." in two


def test_every_kind_of_output_is_described_by_what_it_is():
    """Issue 29: the woven ball's OBJ was described as "text". Each suffix a recipe writes
    gets its own words; "text" is left for a file of no known kind."""
    from weavecut.kitpage.document import _purpose

    for suffix in (".obj", ".glb", ".json", ".dxf"):
        assert _purpose([suffix], None, {}) != "text", suffix
    assert "OBJ" in _purpose([".obj"], None, {})


def test_a_strand_books_card_counts_what_the_maker_prints(tmp_path):
    """Walk of issue #29: the card of a paper model's PDF said "11 colours" (every fill of its
    pages: the light under-tints, the glue bands' grey): it says how many strand colours the
    strips have, each with its light tint, as the book's own palette has them."""
    from weavecut.papermodel.wording import colours_said

    with recording() as record:
        result = CliRunner().invoke(cli, ["-q", "strands", "square-grid:2x2", "--tile-size",
                                          "20mm", "--palette", "maritime-4", "-o",
                                          str(tmp_path / "sq.pdf")])
        assert result.exit_code == 0, result.output
    kitpage.write(tmp_path / "k.html", "kit", [kitpage.Run.of(record, "weave-cut strands")])
    facts = cards((tmp_path / "k.html").read_text(encoding="utf-8"))["sq"]["facts"]
    said = [f for f in facts if "colour" in f]
    assert said == ["4 strand colours, each with a light tint"] == [colours_said("abcd")]
