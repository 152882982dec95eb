"""The woven 3-D model on a command's page of ``weave-cut serve`` in Debian's Chromium with
WebGL in software (tests/browser.py): once the square grid's kit is made the page shows its
model in the kit page's viewer, drawn and filling a fair part of the canvas, with no error, and
the page asks nothing of any host but the app's own."""

from __future__ import annotations

from urllib.parse import urlparse

import numpy as np
import pytest
from PIL import Image

from tests.test_kitpage_browser import chromium
from tests.test_kitpage_viewer import canvas_shot, model_box
from tests.web.test_browser import server  # noqa: F401  (the fixture: the app as users start it)

pytestmark = pytest.mark.slow  # Chromium drawing a kit's 3D model

SHOWN = ("(() => { const f = document.querySelector('#model figure.model3d');"
         " return f && f.dataset.state !== 'loading' ? f.dataset.state : null; })()")


@pytest.fixture(scope="module")
def browser():
    with chromium(webgl=True) as browser:
        browser.call("Network.enable")
        yield browser


def test_the_square_grids_model_appears_and_nothing_comes_from_another_host(
        browser, server, tmp_path):  # noqa: F811
    browser.goto(server + "strands?input=square-grid&size=27cm", 1280)
    assert browser.wait_until(SHOWN, 240) == "ready"
    assert not browser.evaluate("document.getElementById('model').hidden")
    assert browser.errors() == []
    pixels = canvas_shot(browser, 0)
    Image.fromarray(pixels).save(tmp_path / "model.png")
    share, width, height = model_box(pixels)
    assert share > 0.1 and max(width, height) > 0.6, (share, width, height)
    assert len(np.unique(pixels.reshape(-1, 3) // 32, axis=0)) > 12  # the palette's strands
    asked = [e["params"]["request"]["url"] for e in browser.events
             if e.get("method") == "Network.requestWillBeSent"]
    assert any("/strands/model.glb?" in u for u in asked)
    own = urlparse(server).netloc
    for url in asked:
        assert url.startswith(("data:", "blob:")) or urlparse(url).netloc == own, url
