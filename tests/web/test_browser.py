"""The web app end to end in Debian's Chromium (tests/browser.py over the DevTools protocol),
against ``weave-cut serve`` started as a user starts it: open the start page, choose the paper
model, change its size, wait for the preview to change, download the ZIP and compare its files
with the CLI's for the same options; upload a drawing and make a puzzle of it; reach the
fields from the keyboard; nothing wider than a phone."""

from __future__ import annotations

import io
import json
import os
import re
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import pytest

from tests.test_readback import program
from tests.web_app import cli_files

pytestmark = pytest.mark.slow  # Chromium driving the web app through whole kits

ROOT = Path(__file__).resolve().parents[2]
READY = "document.getElementById('status').textContent.includes('ready to download')"


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    folder = tmp_path_factory.mktemp("serve")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen([sys.executable, "-m", "weavecut", "serve", "--port", "0",
                             "--cache", str(folder / "cache")], cwd=folder, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = proc.stdout.readline()
    found = re.search(r"http://[^ ]+/", line)
    assert found, line + proc.stderr.read()
    yield found.group(0)
    proc.terminate()
    proc.wait(timeout=20)
    proc.stdout.close()
    proc.stderr.close()


@pytest.fixture(scope="module")
def browser():
    pytest.importorskip("websocket", reason="websocket-client is a test dependency")
    from tests.browser import Chromium

    with Chromium(program("chromium"), timeout=240) as chromium:
        yield chromium


def test_make_the_paper_model_and_download_it(browser, server, tmp_path):
    browser.goto(server, 1280)
    assert browser.evaluate("[...document.images].every(i => i.complete && i.naturalWidth)")
    browser.click('a[href^="/strands?input=square-grid"]')
    # the whole page parsed: a loaded machine once answered on the form with the rest unread
    browser.wait_until("location.pathname === '/strands' && document.readyState === 'complete'")
    browser.wait_until(READY, 240)
    before = browser.evaluate("document.getElementById('preview').src")
    assert browser.evaluate("document.getElementById('preview').naturalWidth") > 0
    browser.type_into("#f-size", "25cm")
    browser.wait_until("document.getElementById('preview').src !== " + json.dumps(before)
                       + " && document.getElementById('preview').dataset.query"
                       ".includes('size=25cm')", 120)
    assert "size=25cm" in browser.evaluate("location.search")  # the link carries it
    browser.wait_until(READY, 240)
    shown = browser.evaluate("document.getElementById('cmdline').textContent")
    assert "--size 25cm" in shown
    downloads = tmp_path / "downloads"
    downloads.mkdir()
    browser.downloads_into(downloads)
    browser.click("#download")
    end = time.monotonic() + 120
    while not (downloads / "weave-cut-strands.zip").is_file() or any(
            downloads.glob("*.crdownload")):
        assert time.monotonic() < end, sorted(downloads.iterdir())
        time.sleep(0.2)
    kit = zipfile.ZipFile(io.BytesIO((downloads / "weave-cut-strands.zip").read_bytes()))
    files = {n: kit.read(n) for n in kit.namelist()}
    cli = tmp_path / "cli"
    cli.mkdir()
    assert files == cli_files(files["index.html"].decode(), cli)
    assert browser.errors() == []


def test_a_puzzle_of_an_uploaded_drawing(browser, server):
    browser.goto(server + "puzzle?cell=39mm&levels=2&size=30cm", 1280)
    browser.wait_until(READY, 240)
    browser.set_files("#f-upload", [ROOT / "templates" / "recipes" / "heart.svg"])
    browser.wait_until("document.getElementById('f-input').value.startsWith('upload:')", 60)
    browser.wait_until("document.getElementById('preview').dataset.query.includes('upload')"
                       " && " + READY, 240)
    assert browser.evaluate("document.getElementById('cmdline').textContent").startswith(
        "weave-cut puzzle upload-")
    figures = browser.evaluate("document.getElementById('figures').textContent")
    assert "Pieces" in figures
    assert browser.errors() == []


def test_the_fields_are_reached_from_the_keyboard(browser, server):
    browser.goto(server + "strands?input=square-grid", 1280)
    seen = []
    for _ in range(40):
        browser.press("Tab", "Tab", 9)
        seen.append(browser.evaluate("document.activeElement.id || "
                                     "document.activeElement.textContent.slice(0, 20)"))
        if seen[-1] == "f-size":
            break
    assert seen[-1] == "f-size", seen
    assert "f-input" in seen and "f-upload" in seen


@pytest.mark.parametrize("path", ["", "strands?input=square-grid", "puzzle", "figure"])
def test_nothing_is_wider_than_a_phone(browser, server, path):
    browser.goto(server + path, 390)
    assert browser.evaluate("document.documentElement.scrollWidth <= window.innerWidth")


def test_the_laser_card_and_its_files_per_sheet_from_the_keyboard_on_a_phone(browser, server):
    browser.goto(server + "strands?input=square-grid&size=27cm&palette=maritime-4", 390)
    browser.wait_until("!!document.getElementById('f-laser-card')", 60)
    visible = ("(k => !document.querySelector(`[data-key=${k}]`).hidden)")
    assert browser.evaluate(visible + "('format')") and not browser.evaluate(
        visible + "('formats')")
    browser.evaluate("document.getElementById('f-laser-card').focus(), 0")
    browser.press(" ", "Space", 32)  # the check box, from the keyboard
    browser.wait_until(visible + "('formats') && !" + visible + "('format')", 10)
    # the boxes start as the command writes without --formats: SVG and DXF
    ticked = "[...document.querySelectorAll('input[name=formats]:checked')].map(c => c.value)"
    assert browser.evaluate(ticked + ".join()") == "svg,dxf"
    for box in ("svg", "dxf", "lbrn2"):  # untick both, tick LightBurn
        browser.evaluate(f"document.querySelector('input[name=formats][value={box}]').focus(), 0")
        browser.press(" ", "Space", 32)
    browser.wait_until("location.search.includes('formats=lbrn2')", 10)
    assert "format=" not in browser.evaluate("location.search").replace("formats=", "")
    browser.wait_until("document.getElementById('cmdline').textContent"
                       ".includes('--laser-card --formats lbrn2')", 60)
    # the command line wraps on a phone: nothing to scroll sideways
    assert browser.evaluate("(p => p.scrollWidth <= p.clientWidth)"
                            "(document.getElementById('cmdline').parentElement)")
    assert browser.errors() == []


def test_an_upload_that_is_no_drawing_says_so_and_the_message_stays(browser, server, tmp_path):
    picture = tmp_path / "heart.png"
    picture.write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(200))  # what a person may try first
    browser.goto(server + "puzzle", 390)
    browser.wait_until("!!document.getElementById('f-upload')", 60)
    browser.set_files("#f-upload", [picture])
    browser.wait_until("!document.getElementById('e-input').hidden", 60)
    time.sleep(1.5)  # past the form's debounce: nothing redraws over the message
    assert "not a drawing" in browser.evaluate("document.getElementById('e-input').textContent")
    assert not browser.evaluate("document.getElementById('e-input').hidden")
    assert "not accepted" in browser.evaluate("document.getElementById('status').textContent")


def test_a_kit_without_figures_says_so_once_made(browser, server):
    browser.goto(server + "subdivide?input=pentagon&levels=2", 1280)
    before = "getComputedStyle(document.getElementById('figures'), '::before').content"
    browser.wait_until(READY, 120)
    assert "prints no figures" in browser.evaluate(before)


@pytest.mark.parametrize("path", ["weave?input=square-grid&levels=2",
                                  "subdivide?input=pentagon&levels=2",
                                  "figure?name=square-grid-weaving"])
def test_a_kit_without_a_model_is_not_asked_for_one(browser, server, path):
    """A kit without a woven 3-D model (weave, subdivide, figure): the page does not fetch
    model.glb, whose 404 Chromium logs as a console error (it once failed the next test, which
    read it). The page's fetches are recorded as they start, and the model's would start in
    the task that says the kit is ready: no wait for it to happen. Planted: the model fetched
    for every kit, as before."""
    script = browser.call("Page.addScriptToEvaluateOnNewDocument", source=(
        "window.asked = []; const f = window.fetch;"
        " window.fetch = (url, o) => (window.asked.push(String(url)), f(url, o));"))
    try:
        browser.goto(server + path, 1280)
        browser.wait_until(READY, 240)
        asked = browser.evaluate("window.asked")
    finally:
        browser.call("Page.removeScriptToEvaluateOnNewDocument", identifier=script["identifier"])
    assert any("/summary.json?" in url for url in asked), asked  # the kit was made
    assert not [url for url in asked if "model.glb" in url]
    assert browser.errors() == []


def test_choosing_a_ball_hides_what_a_ball_refuses_and_sends_none_of_it(browser, server):
    """The fields the command refuses for a surface in space (its KIT_REFUSES) disappear when
    the input becomes the dodecahedron, with the fields that need the hidden laser card; the
    query then carries none of them; back on a flat input they return as they were."""
    browser.goto(server + "strands?input=square-grid&laser-card=on&palette=maritime-4", 1280)
    browser.wait_until("!!document.getElementById('f-laser-card')", 60)
    visible = "(k => !document.querySelector(`.field[data-key=${k}]`).hidden)"
    gone = ("cutter", "laser-card", "layout", "turn", "material", "laser", "formats")
    assert all(browser.evaluate(f"{visible}('{k}')") for k in gone if k != "cutter")
    assert not browser.evaluate(f"{visible}('project')")
    browser.evaluate("(s => { s.value = 'dodecahedron'; s.dispatchEvent(new Event('change', "
                     "{bubbles: true})); })(document.getElementById('f-input')), 0")
    browser.wait_until(" && ".join(f"!{visible}('{k}')" for k in gone)
                       + f" && {visible}('project') && {visible}('format')", 10)
    page_help = "document.getElementById('h-page').textContent"
    assert "Laser-cut card" not in browser.evaluate(page_help)  # no help names a gone field
    browser.wait_until("location.search.includes('input=dodecahedron')", 10)
    assert "laser-card" not in browser.evaluate("location.search")
    browser.evaluate("(s => { s.value = 'square-grid'; s.dispatchEvent(new Event('change', "
                     "{bubbles: true})); })(document.getElementById('f-input')), 0")
    browser.wait_until(f"{visible}('laser-card') && {visible}('material') && !{visible}('format')"
                       f" && !{visible}('project')", 10)
    browser.wait_until("location.search.includes('laser-card=on')", 10)
    assert "Laser-cut card" in browser.evaluate(page_help)
    assert browser.errors() == []


def test_an_uploaded_ball_is_a_ball(browser, server, tmp_path):
    """A closed surface in space uploaded as OBJ makes a ball, as ``strands FILE`` does: the
    fields a ball refuses go, the projection comes, and no help names what went."""
    from weavecut import inputs, mesh_io

    mesh_io.write_mesh(inputs.get("dodecahedron"), tmp_path / "ball.obj")
    browser.goto(server + "strands?input=square-grid&laser-card=on", 1280)
    browser.wait_until("!!document.getElementById('f-upload')", 60)
    browser.set_files("#f-upload", [tmp_path / "ball.obj"])
    browser.wait_until("document.getElementById('f-input').value.startsWith('upload:')", 60)
    visible = "(k => !document.querySelector(`.field[data-key=${k}]`).hidden)"
    browser.wait_until(" && ".join(f"!{visible}('{k}')" for k in ("cutter", "laser-card",
                                                                  "layout", "turn", "material"))
                       + f" && {visible}('project')", 10)
    assert "Laser-cut card" not in browser.evaluate(
        "document.getElementById('h-page').textContent")
    browser.wait_until(READY, 240)  # the ball's kit, made
    assert browser.errors() == []


def test_the_puzzles_numbers_start_ticked_and_unticking_sends_off(browser, server):
    """The form ticks the puzzle's Numbers at first (``forms.TICKED``), though ``puzzle``
    engraves none without ``--numbers``: the command line shown has it; unticked from the
    keyboard, the query says numbers=off and the command line loses it; ticked again, the
    query drops it (the form's default) and the command line has it back."""
    browser.goto(server + "puzzle", 1280)
    browser.wait_until("!!document.getElementById('f-numbers')", 60)
    assert browser.evaluate("document.getElementById('f-numbers').checked")
    line = "document.getElementById('cmdline').textContent"
    browser.wait_until(f"{line}.includes('--numbers')", 60)
    browser.evaluate("document.getElementById('f-numbers').focus(), 0")
    browser.press(" ", "Space", 32)
    browser.wait_until("location.search.includes('numbers=off')", 10)
    browser.wait_until(f"!{line}.includes('--numbers')", 60)
    browser.press(" ", "Space", 32)
    browser.wait_until("!location.search.includes('numbers')", 10)
    browser.wait_until(f"{line}.includes('--numbers')", 60)
    assert browser.errors() == []


def test_a_mistyped_input_in_a_shared_link_keeps_its_refusal_and_makes_nothing(browser, server):
    """A link with an input the command does not know (``squre-grid``) opens with the
    refusal next to the input, and the script sends that input again: no other item of the
    list is drawn or made in its place until the maker chooses one."""
    browser.goto(server + "strands?input=squre-grid&size=15cm", 1280)
    browser.wait_until("!!document.getElementById('f-input')", 60)
    error = "document.getElementById('e-input')"
    browser.wait_until("document.getElementById('status').textContent.includes('Fix the marked')",
                       60)
    time.sleep(1.5)  # past the form's debounce: nothing redraws over the message
    assert not browser.evaluate(f"{error}.hidden")
    assert "square-grid" in browser.evaluate(f"{error}.textContent")  # its "did you mean"
    assert browser.evaluate("document.getElementById('f-input').value") == "squre-grid"
    assert not browser.evaluate("document.getElementById('preview').getAttribute('src')")
    assert browser.evaluate("document.getElementById('download').getAttribute('aria-disabled')"
                            ) == "true"
    assert "input=squre-grid" in browser.evaluate("location.search")
    browser.evaluate("(s => { s.value = 'square-grid'; s.dispatchEvent(new Event('change', "
                     "{bubbles: true})); })(document.getElementById('f-input')), 0")
    browser.wait_until(READY, 240)  # a known input chosen: the kit is made
    assert browser.evaluate(f"{error}.hidden")
    assert [e for e in browser.errors() if "status of 400" not in e] == []  # the refusals
