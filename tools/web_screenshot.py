"""Redraw the README's screenshot of the web app (``docs/web-app.png``): start
``weave-cut serve`` on a free port, open the pentagon flower's page in headless Chromium
(tests/browser.py) at 1280 px, wait for the kit, and keep the top of the page at 960 px wide.

    python tools/web_screenshot.py
"""

from __future__ import annotations

import io
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from PIL import Image

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from tests.browser import Chromium  # noqa: E402

PAGE = "strands?input=pentagon-flower&size=23cm&palette=maritime-12"
READY = "document.getElementById('status').textContent.includes('ready to download')"


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
        server = subprocess.Popen([sys.executable, "-m", "weavecut", "serve", "--port", "0",
                                   "--cache", tmp], stdout=subprocess.PIPE, text=True, env=env)
        try:
            url = re.search(r"http://[^ ]+/", server.stdout.readline()).group(0)
            with Chromium("chromium", timeout=300) as browser:
                browser.goto(url + PAGE, 1280)
                browser.wait_until(READY, 300)
                shot = Image.open(io.BytesIO(browser.screenshot(1280))).convert("RGB")
        finally:
            server.terminate()
            server.wait()
    shot = shot.crop((0, 0, 1280, 1240)).resize((960, 930), Image.LANCZOS)
    shot.quantize(colors=256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE).save(
        ROOT / "docs" / "web-app.png", optimize=True)


if __name__ == "__main__":
    main()
