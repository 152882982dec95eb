"""Every file weave-cut writes is read back by a program other than weave-cut: provenance in
every format (an XML parser for SVG, ezdxf and LibreCAD for DXF, pdfinfo for PDF, Pillow for
PNG), the weave's colours in its DXF, and PDFs on real printer pages."""

from __future__ import annotations

import os
import re
import shlex
from pathlib import Path
import shutil
import subprocess
import sys
from xml.etree import ElementTree

import ezdxf
import ezdxf.comments
import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

from weavecut import __version__
from weavecut.analysis import levels as lv
from weavecut.cli import cli
from weavecut.figures import gallery

GENERATOR = f"weave-cut {__version__}"
A4 = (595.276, 841.89)  # points
LETTER = (612.0, 792.0)


def run(monkeypatch, *args):
    """Run the CLI with ``sys.argv`` as a shell would set it (the command is in the files, an
    absolute path by its file's name: no file tells where the maker keeps it)."""
    args = [str(a) for a in args]
    monkeypatch.setattr(sys, "argv", ["weave-cut", *args])
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 0, result.output
    return "weave-cut " + shlex.join(Path(a).name if Path(a).is_absolute() else a for a in args)


def program(name: str) -> str:
    """The path of a Debian program the test needs (.ci/run installs it); skipped where it is
    missing, except in CI."""
    path = shutil.which(name)
    if path is None:
        if os.environ.get("CI"):
            pytest.fail(f"{name} is missing; .ci/run installs it")
        pytest.skip(f"{name} is not installed")
    return path


def pdfinfo(path) -> dict[str, str]:
    out = subprocess.run([program("pdfinfo"), "-l", "-1", str(path)], capture_output=True,
                         text=True, check=True).stdout
    return {k.strip(): v.strip() for k, _, v in (line.partition(":") for line in out.splitlines())}


def page_sizes(info: dict[str, str]) -> set[tuple[float, float]]:
    sizes = set()
    for key, value in info.items():
        if re.fullmatch(r"Page\s+\d+ size", key):
            w, h = re.match(r"([\d.]+) x ([\d.]+)", value).groups()
            sizes.add((float(w), float(h)))
    return sizes


def png_text(path) -> dict[str, str]:
    with Image.open(path) as im:
        im.verify()  # chunk CRCs
    with Image.open(path) as im:
        im.load()
        return dict(im.text)


def test_svg_names_generator_and_command(tmp_path, monkeypatch):
    out = tmp_path / "p.svg"
    command = run(monkeypatch, "subdivide", "pentagon", "-n", "2", "-o", out)
    desc = ElementTree.parse(out).getroot().find("{http://www.w3.org/2000/svg}desc").text
    assert f"generator: {GENERATOR}" in desc and f"command: {command}" in desc


def test_dxf_comments_name_generator_and_command(tmp_path, monkeypatch):
    out = tmp_path / "p.dxf"
    command = run(monkeypatch, "subdivide", "pentagon", "-n", "2", "-o", out)
    comments = [tag.value for tag in ezdxf.comments.from_file(str(out))]
    assert f"generator: {GENERATOR}" in comments and f"command: {command}" in comments
    assert not ezdxf.readfile(out).audit().has_errors


def test_pdf_names_generator_and_command(tmp_path, monkeypatch):
    out = tmp_path / "p.pdf"
    command = run(monkeypatch, "subdivide", "pentagon", "-n", "2", "-o", out)
    info = pdfinfo(out)
    assert info["Creator"] == GENERATOR and info["Subject"] == command


@pytest.mark.parametrize("args", [
    ["subdivide", "pentagon", "-n", "2"],
    ["levels", "pentagon", "-n", "4", "--size", "64"],
    ["figure", "level-image"],
], ids=["drawing", "levels", "figure"])
def test_every_png_names_generator_and_command(tmp_path, monkeypatch, args):
    small = lv.png_bytes(np.full((8, 8, 3), 200, dtype=np.uint8))
    monkeypatch.setitem(gallery.FIGURES, "level-image",
                        (gallery.FIGURES["level-image"][0], lambda: small))  # fast stand-in
    out = tmp_path / "p.png"
    command = run(monkeypatch, *args, "-o", out)
    text = png_text(out)
    assert text["generator"] == GENERATOR and text["command"] == command and text["Title"]


def test_png_text_outside_latin1_is_utf8(tmp_path, monkeypatch):
    out = tmp_path / "Wabe-ω.png"
    command = run(monkeypatch, "levels", "pentagon", "-n", "3", "--size", "32", "-o", out)
    assert png_text(out)["command"] == command


def test_librecad_reads_the_weave_dxf(tmp_path, monkeypatch):
    out = tmp_path / "w.dxf"
    run(monkeypatch, "weave", "pentagon", "-n", "3", "--outline-level", "2", "--palette",
        "puzzle", "-o", out)
    subprocess.run([program("xvfb-run"), "-a", program("librecad"), "dxf2pdf", "-a", "-t",
                    str(tmp_path), str(out)], check=True, capture_output=True, timeout=300)
    printed = tmp_path / "w.pdf"
    assert pdfinfo(printed)["Pages"] == "1"
    subprocess.run([program("pdftoppm"), "-r", "20", "-png", str(printed), str(tmp_path / "r")],
                   check=True)
    (image,) = tmp_path.glob("r*.png")
    pixels = np.asarray(Image.open(image).convert("RGB")).reshape(-1, 3).astype(int)
    coloured = np.ptp(pixels, axis=1) > 40  # neither white, grey nor black: a tile colour
    assert coloured.mean() > 0.05


def test_weave_dxf_has_a_layer_per_strand_colour(tmp_path, monkeypatch):
    dxf, svg = tmp_path / "w.dxf", tmp_path / "w.svg"
    for out in (dxf, svg):
        run(monkeypatch, "weave", "pentagon", "-n", "4", "--outline-level", "3", "-o", out)
    doc = ezdxf.readfile(dxf)
    assert not doc.audit().has_errors
    hatches = doc.modelspace().query("HATCH")
    colour = {h.dxf.layer: "#{:02x}{:02x}{:02x}".format(*doc.layers.get(h.dxf.layer).rgb)
              for h in hatches}
    ns = "{http://www.w3.org/2000/svg}"
    tiles = next(g for g in ElementTree.parse(svg).getroot().iter(f"{ns}g")
                 if g.get("id") == "paint-tiles")
    assert set(colour.values()) == {p.get("fill") for p in tiles.iter(f"{ns}path")}
    assert len(colour) == len(hatches)  # one layer per colour
    assert all(name == "tiles-" + c[1:] for name, c in colour.items())
    assert sum(len(h.paths) for h in hatches) == 5 ** 4  # every pentagon of level 4 once
    outline = doc.layers.get("outline")
    assert "tile-outlines" in doc.layers and outline.dxf.name == "outline"
    black = [e for e in doc.modelspace().query('LWPOLYLINE[layer=="outline"]')]
    assert black and all(e.rgb == (0, 0, 0) for e in black)
    grey = doc.modelspace().query('LWPOLYLINE[layer=="tile-outlines"]')
    assert all(e.rgb != (0, 0, 0) for e in grey)
    assert min(e.dxf.lineweight for e in black) > max(e.dxf.lineweight for e in grey)


@pytest.mark.parametrize("size, page, pages, points", [
    ("150mm", "a4", 1, A4),
    ("200mm", "letter", 1, LETTER),  # the 200 mm picture fits inside 5 mm printer margins
    ("40cm", "a4", 6, A4),  # (420 - 10) / (190 - 10) -> 3 columns, / (277 - 10) -> 2 rows
])
def test_weave_pdf_is_on_printer_pages(tmp_path, monkeypatch, size, page, pages, points):
    out = tmp_path / "w.pdf"
    run(monkeypatch, "weave", "square-grid", "-n", "2", "--size", size, "--page", page,
        "-o", out)
    info = pdfinfo(out)
    assert int(info["Pages"]) == pages
    assert page_sizes(info) == {points}
