"""The README's images show what the code draws now: each records the digest of its Drawing
(``make docs`` writes it), and the test draws the Drawing again, without rasterising, and
compares. A changed drawing fails here until ``make docs`` is run."""

from __future__ import annotations

import importlib.util
import re
import sys
from pathlib import Path

import pytest
from PIL import Image

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("make_docs", ROOT / "docs" / "make_docs.py")
make_docs = sys.modules["make_docs"] = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(make_docs)


# screenshots: not a Drawing, each redrawn by its own script
SCREENSHOTS = {"docs/web-app.png": "tools/web_screenshot.py"}


def test_every_readme_image_is_made_by_make_docs():
    shown = set(re.findall(r"!\[[^\]]*\]\(([^)]+\.png)\)", (ROOT / "README.md").read_text()))
    assert shown == set(make_docs.IMAGES) | set(SCREENSHOTS)
    for path, script in SCREENSHOTS.items():
        assert (ROOT / path).is_file() and (ROOT / script).is_file()


@pytest.mark.parametrize("path", sorted(make_docs.IMAGES))
def test_readme_image_is_up_to_date(path):
    with Image.open(ROOT / path) as im:
        recorded = im.text.get("drawing-sha256")
    now = make_docs.digest(make_docs.drawing(make_docs.IMAGES[path]))
    assert recorded == now, f"{path} is older than the code that draws it: run `make docs`"


def test_digest_sees_a_moved_line_and_ignores_metadata():
    image = make_docs.IMAGES["docs/pentagon-level4.png"]
    d = make_docs.drawing(image)
    assert make_docs.digest(d.with_metadata(command="elsewhere")) == make_docs.digest(d)
    sheet = d.sheets[0]
    shape = sheet.layers[-1].shapes[0]
    moved = shape.__class__(shape.coords + [0.001, 0.0], shape.offsets, shape.style)
    layers = (*sheet.layers[:-1], sheet.layers[-1].__class__(
        sheet.layers[-1].name, sheet.layers[-1].role, (moved,)))
    other = d.__class__((sheet.__class__(sheet.width, sheet.height, layers),), d.title)
    assert make_docs.digest(other) != make_docs.digest(d)
