"""Every SVG the figures recipe writes opens in rsvg (librsvg: GNOME's image viewers, Inkscape's
import of many files) with every panel drawn, and is a size a viewer opens at once (issue #29:
``edge-renders.svg`` was 29.9 MB, and a viewer drew its level-8 panel empty).

librsvg refuses a whole file when one attribute (a path's ``d``) passes libxml2's 10 MB limit
(``XML parse error ... Couldn't find end of Start Tag path``, checked with rsvg-convert 2.54.7),
and viewers that run it with time or memory limits give up on files of tens of megabytes."""

from __future__ import annotations

import io
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from tests.test_readback import program
from weavecut.export import png, svg
from weavecut.figures import gallery
from weavecut.layout.drawing import Drawing, Text

pytestmark = pytest.mark.slow  # every figure drawn, then opened in rsvg

RECIPE = Path(__file__).parents[2] / "templates" / "recipes" / "figures.toml"
# edge-renders: issue #29 is open (its level-8 panel: 1.5 million points in strokes 0.015 mm
# wide, which cairo's sampled coverage drops below about a tenth of a pixel, so rsvg draws the
# panel empty at a viewer's fit-to-window size; Chromium's analytic coverage draws it grey)
OPEN = pytest.mark.xfail(strict=True, reason="issue #29: edge-renders level 8 is 24 MB of "
                         "sub-pixel strokes")
SVG_FIGURES = [pytest.param(job["input"], marks=OPEN) if job["input"] == "edge-renders"
               else job["input"] for job in tomllib.loads(RECIPE.read_text())["job"]
               if job["output"].endswith(".svg")]
DPI = 40  # coarse: what is checked is where the ink is, panel by panel
# A page of figures in a paper is a few megabytes at most; 5 MB is four times the largest
# figure but edge-renders (non-pentagonal, 1.2 MB), and a sixth of what issue #29 found.
MAX_BYTES = 5_000_000


def _layers(drawing: Drawing) -> dict[str, tuple[float, float, float, float]]:
    """Per layer ("d-edges": panel d's edges), the bounds in mm of what it draws; captions
    left out."""
    boxes: dict[str, list] = {}
    for layer in drawing.sheets[0].layers:
        if layer.role == "label" or not layer.visible:
            continue
        for shape in layer.shapes:
            if not isinstance(shape, Text) and len(shape.coords):
                boxes.setdefault(layer.name, []).append(
                    (*shape.coords.min(axis=0), *shape.coords.max(axis=0)))
    return {k: (min(b[0] for b in v), min(b[1] for b in v), max(b[2] for b in v),
                max(b[3] for b in v)) for k, v in boxes.items()}


def _ink(img: np.ndarray, box, height: float) -> float:
    """The share of not-white pixels of ``img`` (drawn at DPI) inside ``box`` (mm)."""
    px = DPI / 25.4
    x0, y0, x1, y1 = box
    rows = slice(int((height - y1) * px), int(np.ceil((height - y0) * px)) + 1)
    cols = slice(int(x0 * px), int(np.ceil(x1 * px)) + 1)
    return float((img[rows, cols].min(axis=2) < 245).mean())


@pytest.mark.parametrize("name", SVG_FIGURES)
def test_each_figure_svg_is_a_size_a_viewer_opens(name):
    data = svg.render(gallery.FIGURES[name][1]())
    assert len(data) < MAX_BYTES, f"{name}.svg is {len(data):,} bytes"


@pytest.mark.parametrize("name", SVG_FIGURES)
def test_each_figure_svg_opens_in_rsvg_with_every_panel_drawn(name, tmp_path):
    drawing = gallery.FIGURES[name][1]()
    (tmp_path / "f.svg").write_bytes(svg.render(drawing))
    done = subprocess.run([program("rsvg-convert"), "-d", f"{DPI}", "-p", f"{DPI}", "-b", "white",
                           "-o", str(tmp_path / "f.png"), str(tmp_path / "f.svg")],
                          capture_output=True, text=True)
    assert done.returncode == 0 and not done.stderr, done.stderr
    ours = np.asarray(Image.open(io.BytesIO(png.render(drawing, dpi=DPI)))
                      .convert("RGB"))
    theirs = np.asarray(Image.open(tmp_path / "f.png").convert("RGB"))
    height = drawing.sheets[0].height
    for layer, box in _layers(drawing).items():
        # weave-cut's own rasteriser (Pillow) is the reference: rsvg draws at least a tenth
        # as much ink where the layer is (a line Pillow draws 1 px wide, rsvg draws as wide
        # as it is: a 0.015 mm line is a light grey at DPI); an empty panel draws none
        assert _ink(theirs, box, height) >= _ink(ours, box, height) / 10, (name, layer)
