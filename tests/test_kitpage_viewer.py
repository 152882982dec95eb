"""The kit page's 3-D viewer in a real browser: Debian's Chromium with WebGL in software
(SwiftShader), driven over the DevTools protocol (tests/browser.py), opens from file:// the page
of a build with a woven ball, a flat paper model and a puzzle; every model is drawn, fills a
fair part of its viewer, turns when dragged and comes back with the reset button, and the page
asks for nothing beyond its own folder (no other host, no file outside it)."""

from __future__ import annotations

import base64
import io
from pathlib import Path
from urllib.parse import unquote, urlparse

import numpy as np
import pytest
from PIL import Image

from .test_kitpage_browser import chromium, kit_page

pytestmark = pytest.mark.slow  # Chromium drawing every kit page's model viewer

RECIPE = """[recipe]
name = "models"
[[job]]
command = "strands"
input = "dodecahedron"
levels = 1
project = "sphere"
size = "12cm"
output = "ball.pdf"
[[job]]
command = "strands"
input = "square-grid"
output = "square.pdf"
[[job]]
command = "puzzle"
levels = 2
size = "20cm"
output = "puzzle"
"""
READY = """(() => { const f = [...document.querySelectorAll('figure.model3d')];
  return f.length && f.every(x => x.dataset.state !== 'loading')
    ? f.map(x => x.dataset.state) : null; })()"""


@pytest.fixture(scope="module")
def browser():
    with chromium(webgl=True) as browser:
        browser.call("Network.enable")
        yield browser


@pytest.fixture(scope="module")
def page(tmp_path_factory) -> Path:
    return kit_page(tmp_path_factory, RECIPE)


def open_page(browser, page: Path) -> list[str]:
    browser.goto(page.resolve().as_uri(), 1280)
    return browser.wait_until(READY, 60)


def canvas_shot(browser, k: int) -> np.ndarray:
    """(H, W, 3) the k-th viewer's canvas as the screen shows it."""
    x, y, w, h = browser.evaluate(
        f"(() => {{ const e = document.querySelectorAll('figure.model3d canvas')[{k}];"
        " e.scrollIntoView({block: 'center'}); const r = e.getBoundingClientRect();"
        " return [r.x + scrollX, r.y + scrollY, r.width, r.height]; })()")
    data = browser.call("Page.captureScreenshot", format="png",
                        clip={"x": x, "y": y, "width": w, "height": h, "scale": 1})["data"]
    return np.asarray(Image.open(io.BytesIO(base64.b64decode(data))).convert("RGB"))


def model_box(pixels: np.ndarray) -> tuple[float, float, float]:
    """Share of the canvas the model's pixels (not the white background) cover, and of its
    width and height their bounding box spans."""
    inked = (pixels < 235).any(axis=2)
    inked[:2], inked[-2:], inked[:, :2], inked[:, -2:] = False, False, False, False  # border
    rows, cols = np.flatnonzero(inked.any(axis=1)), np.flatnonzero(inked.any(axis=0))
    if not len(rows):
        return 0.0, 0.0, 0.0
    return (float(inked.mean()), (cols[-1] - cols[0] + 1) / inked.shape[1],
            (rows[-1] - rows[0] + 1) / inked.shape[0])


def test_every_model_is_drawn_and_fills_its_viewer(browser, page):
    states = open_page(browser, page)
    assert states == ["ready"] * 3  # the ball, the square grid, the puzzle
    assert browser.errors() == []
    for k in range(3):
        pixels = canvas_shot(browser, k)
        Image.fromarray(pixels).save(page.parent / f"viewer-{k}.png")
        share, width, height = model_box(pixels)
        assert share > 0.1 and max(width, height) > 0.6, (k, share, width, height)
        # colours, not a grey silhouette: the palette's strands show
        assert len(np.unique(pixels.reshape(-1, 3) // 32, axis=0)) > 12


def test_a_drag_turns_the_model_and_reset_brings_it_back(browser, page):
    open_page(browser, page)
    before = canvas_shot(browser, 0)
    x, y = browser._centre("figure.model3d canvas")
    for kind, dx in (("mousePressed", 0), ("mouseMoved", 60), ("mouseMoved", 140),
                     ("mouseReleased", 140)):
        browser.call("Input.dispatchMouseEvent", type=kind, x=x + dx, y=y, button="left",
                     buttons=1 if kind != "mouseReleased" else 0, clickCount=1)
    turned = canvas_shot(browser, 0)
    assert np.abs(turned.astype(int) - before).mean() > 2
    browser.click("figure.model3d button")
    back = canvas_shot(browser, 0)
    assert np.abs(back.astype(int) - before).mean() < 0.5


def test_the_page_asks_for_nothing_beyond_its_own_files(browser, page):
    open_page(browser, page)
    asked = [e["params"]["request"]["url"] for e in browser.events
             if e.get("method") == "Network.requestWillBeSent"]
    assert asked
    for url in asked:
        if url.startswith("data:"):
            continue
        parsed = urlparse(url)
        assert parsed.scheme == "file", url
        assert Path(unquote(parsed.path)).resolve().is_relative_to(page.parent.resolve()), url


def test_a_request_to_another_host_or_a_broken_model_is_seen(browser, page, tmp_path):
    """Plant the bugs: a script from another host, and a model whose bytes are not glTF."""
    text = page.read_text(encoding="utf-8")
    bad = tmp_path / "bad.html"
    bad.write_text(text.replace("<script>", '<script src="https://cdn.invalid/three.js">'
                                "</script><script>", 1).replace(
        '<script type="model/gltf-binary">', '<script type="model/gltf-binary">AAAA', 1))
    states = open_page(browser, bad)
    assert states[0] == "error" and states[1:] == ["ready", "ready"]
    asked = [e["params"]["request"]["url"] for e in browser.events
             if e.get("method") == "Network.requestWillBeSent"]
    assert any(urlparse(u).hostname == "cdn.invalid" for u in asked)


def test_the_viewer_scripts_are_inlined_once(page):
    text = page.read_text(encoding="utf-8")
    assert text.count("WeaveCutThree=") == 1
    assert text.split("<script>", 1)[0].count('<figure class="model3d"') == 3
    assert 'src="http' not in text and "<script src=" not in text  # nothing fetched
