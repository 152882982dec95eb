"""The kit page in a real browser: headless Chromium (Debian's package, driven over the
DevTools protocol by tests/browser.py) opens the page of a small build with every kind of
output at 1280 and 390 px: every image loads, nothing is logged as an error, every link
reaches a file, nothing is wider than a phone, and the page prints."""

from __future__ import annotations

from pathlib import Path
from urllib.parse import unquote, urlparse

import pytest
from click.testing import CliRunner

from weavecut.cli import cli

from .test_readback import program

RECIPE = """[recipe]
name = "every kind"
[[job]]
command = "puzzle"
levels = 2
size = "20cm"
numbers = true
output = "puzzle"
[[job]]
command = "strands"
input = "square-grid"
output = "strands.pdf"
[[job]]
command = "weave"
input = "pentagon"
levels = 2
output = "weave.png"
[[job]]
command = "subdivide"
input = "pentagon"
levels = 2
output = "pentagon.dxf"
"""


@pytest.fixture(scope="module")
def browser():
    with chromium() as browser:
        yield browser


def chromium(webgl: bool = False):
    """Debian's headless Chromium (skipped without it or websocket-client)."""
    pytest.importorskip("websocket", reason="websocket-client is a test dependency")
    from .browser import Chromium

    return Chromium(program("chromium"), webgl=webgl)


def kit_page(tmp_path_factory, recipe: str) -> Path:
    """The kit page of ``recipe`` built into a new folder."""
    root = tmp_path_factory.mktemp("kit")
    (root / "r.toml").write_text(recipe)
    result = CliRunner().invoke(cli, ["build", str(root / "r.toml"), "-o", str(root / "out")])
    assert result.exit_code == 0, result.output
    return root / "out" / "index.html"


@pytest.fixture(scope="module")
def page(tmp_path_factory) -> Path:
    return kit_page(tmp_path_factory, RECIPE)


@pytest.mark.slow
@pytest.mark.parametrize("width", [1280, 390])
def test_the_page_in_chromium(browser, page, width):
    visit = browser.visit(page, width)
    (page.parent / f"screenshot-{width}.png").write_bytes(visit.screenshot)
    assert visit.errors == []
    assert len(visit.images) >= 10  # guides, cut sheets, PDF pages, the PNG, the DXF preview
    assert [i for i in visit.images if not i["loaded"]] == []
    files = [Path(unquote(urlparse(href).path)) for href in visit.links]
    assert files and all(f.is_file() and f.is_relative_to(page.parent) for f in files)
    assert visit.scroll_width <= visit.inner_width == width  # no sideways scrolling


def test_a_broken_picture_is_seen(browser, page, tmp_path):
    """Plant the bug: a picture whose file is missing fails the checks above."""
    broken = tmp_path / "broken.html"
    broken.write_text(page.read_text(encoding="utf-8").replace('src="weave.png"', 'src="gone.png"'))
    visit = browser.visit(broken, 1280)
    assert [i for i in visit.images if not i["loaded"]]
    assert any("ERR_FILE_NOT_FOUND" in e for e in visit.errors)


def test_the_page_prints(browser, page):
    browser.visit(page, 1280)
    pdf = browser.print_pdf()
    assert pdf.startswith(b"%PDF-") and pdf.count(b"/Type /Page\n") + pdf.count(b"/Type/Page")


def test_links_named_with_a_space_hash_or_percent_open_in_chromium(browser, tmp_path):
    """The kit page of files (in a folder) named with a space, ``#`` and ``%``: Chromium loads
    every picture and every link's URL names a file that exists."""
    from .test_kitpage import ODD_FILES, odd_kit

    page = odd_kit(tmp_path)
    visit = browser.visit(page, 1280)
    assert visit.errors == []
    assert visit.images and [i for i in visit.images if not i["loaded"]] == []
    files = {Path(unquote(urlparse(href).path)) for href in visit.links}
    assert files == {page.parent / name for name in ODD_FILES}
