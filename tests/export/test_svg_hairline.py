"""A laser hairline (stroke width 0) in an SVG is drawn thin by librsvg, the renderer of GNOME's
image viewer: librsvg 2.54 ignores ``vector-effect="non-scaling-stroke"``, so Inkscape's 1 px
hairline came out 1 mm wide there and engraved labels blotted. Rendered with rsvg-convert at
10 pixels per mm and measured in pixels, against the width the writer states."""

from __future__ import annotations

import shutil
import subprocess

import numpy as np
import pytest
from PIL import Image

from weavecut.export import svg
from weavecut.layout.drawing import Drawing, Layer, Polylines, Sheet, Style

PX = 10  # pixels per mm (254 dpi)


def drawn_rows(tmp_path, width: float) -> int:
    """Rows of dark pixels across a horizontal engraved line of stroke ``width`` mm (0: a
    hairline), 20 x 10 mm sheet, line at mid-height, read in the column at x = 10 mm."""
    line = Polylines(np.array([[2.0, 5.0], [18.0, 5.0]]), np.array([0, 2]),
                     Style("#000000", width))
    sheet = Sheet(20.0, 10.0, (Layer("engrave", "engrave", (line,)),))
    path = tmp_path / "line.svg"
    path.write_bytes(svg.render(Drawing((sheet,), "a line")))
    png = tmp_path / "line.png"
    subprocess.run(["rsvg-convert", "-d", str(25.4 * PX), "-p", str(25.4 * PX), "-b", "white",
                    "-o", str(png), str(path)], check=True)
    grey = np.asarray(Image.open(png).convert("L")).astype(int)
    assert grey.shape == (10 * PX, 20 * PX)  # the sheet at 10 px per mm
    return int((grey[:, 10 * PX] < 160).sum())


@pytest.mark.skipif(shutil.which("rsvg-convert") is None, reason="rsvg-convert not installed")
def test_a_hairline_is_drawn_a_quarter_millimetre_wide_by_librsvg(tmp_path):
    # 0.25 mm is 2.5 pixels: 2 or 3 rows dark, never the 10 of a millimetre-wide blot; and
    # as wide as a stroke given 0.25 mm (an independent width to compare with)
    rows = drawn_rows(tmp_path, 0.0)
    assert 2 <= rows <= 3
    assert rows == drawn_rows(tmp_path, 0.25)
    assert drawn_rows(tmp_path, 1.0) >= 9  # the reading sees a 1 mm line as one
