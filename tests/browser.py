"""A headless Chromium driven through the Chrome DevTools protocol (websocket-client): open a
local page or address at a given width, screenshot it, and report what a reader would meet —
images that did not load, console errors, links, a page wider than the screen; type into a
field, click, press a key, wait for a condition in the page and save downloads (the web app's
end-to-end test).

Uses the system's ``chromium`` (Debian's package; ``.ci/run`` installs it); nothing is
downloaded.
"""

from __future__ import annotations

import base64
import itertools
import json
import re
import subprocess
import tempfile
import threading
import time
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

import websocket

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--hide-scrollbars", "--remote-debugging-port=0"]
# WebGL in software (SwiftShader, inside Chromium): no GPU needed, the same on every machine
WEBGL = ["--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]

REPORT = """JSON.stringify({
  images: [...document.images].map(i => ({alt: i.alt, loaded: i.complete && i.naturalWidth > 0,
                                          src: i.src.slice(0, 80)})),
  links: [...document.links].map(a => a.href),
  scrollWidth: document.documentElement.scrollWidth, innerWidth: window.innerWidth,
  height: document.documentElement.scrollHeight})"""


@dataclass
class Visit:
    """What one page showed at one width."""

    images: list[dict]
    links: list[str]
    scroll_width: int
    inner_width: int
    screenshot: bytes
    errors: list[str] = field(default_factory=list)


class Chromium:
    """One headless browser with one tab; use as a context manager."""

    def __init__(self, program: str, timeout: float = 60.0, webgl: bool = False) -> None:
        self.profile = tempfile.TemporaryDirectory(prefix="weavecut-chromium-",
                                                   ignore_cleanup_errors=True)
        flags = [f for f in FLAGS if f != "--disable-gpu"] + WEBGL if webgl else FLAGS
        self.proc = subprocess.Popen([program, *flags, f"--user-data-dir={self.profile.name}",
                                      "about:blank"], stdout=subprocess.DEVNULL,
                                     stderr=subprocess.PIPE, text=True)
        self.timeout = timeout
        port = self._port()
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=10) as r:
            tab = next(t for t in json.load(r) if t["type"] == "page")
        self.ws = websocket.create_connection(tab["webSocketDebuggerUrl"], timeout=timeout,
                                              suppress_origin=True)
        self.ids = itertools.count(1)
        self.events: list[dict] = []
        for domain in ("Page", "Runtime", "Log"):
            self.call(f"{domain}.enable")

    def _port(self) -> int:
        """The DevTools port chromium reports on stderr (the rest of stderr is drained, so a
        chatty browser never blocks on a full pipe)."""
        for line in self.proc.stderr:
            found = re.search(r"DevTools listening on ws://[^:]+:(\d+)/", line)
            if found:
                threading.Thread(target=self.proc.stderr.read, daemon=True).start()
                return int(found.group(1))
        raise RuntimeError("chromium ended before it listened for DevTools")

    def call(self, method: str, **params) -> dict:
        """Send a command and wait for its answer (events that arrive meanwhile are kept)."""
        n = next(self.ids)
        self.ws.send(json.dumps({"id": n, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == n:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg["result"]
            self.events.append(msg)

    def wait_for(self, event: str) -> None:
        end = time.monotonic() + self.timeout
        while not any(e.get("method") == event for e in self.events):
            if time.monotonic() > end:
                raise TimeoutError(f"no {event} within {self.timeout} s")
            self.events.append(json.loads(self.ws.recv()))

    def visit(self, page: Path, width: int, height: int = 900) -> Visit:
        """Open ``page`` ``width`` CSS pixels wide; a full-height screenshot and a report."""
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=height,
                  deviceScaleFactor=1, mobile=width < 600)
        self.events.clear()
        self.call("Page.navigate", url=page.resolve().as_uri())
        self.wait_for("Page.loadEventFired")
        report = json.loads(self.call("Runtime.evaluate", expression=REPORT,
                                      returnByValue=True)["result"]["value"])
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=report["height"],
                  deviceScaleFactor=1, mobile=width < 600)
        shot = base64.b64decode(self.call("Page.captureScreenshot", format="png")["data"])
        return Visit(report["images"], report["links"], report["scrollWidth"],
                     report["innerWidth"], shot, self.errors())

    def goto(self, url: str, width: int, height: int = 900) -> None:
        """Open ``url`` (any address, not only a file) ``width`` CSS pixels wide and wait for
        its load event."""
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=height,
                  deviceScaleFactor=1, mobile=width < 600)
        self.events.clear()
        self.call("Page.navigate", url=url)
        self.wait_for("Page.loadEventFired")

    def evaluate(self, expression: str):
        """The value of a JavaScript expression in the open page (promises awaited)."""
        answer = self.call("Runtime.evaluate", expression=expression, returnByValue=True,
                           awaitPromise=True)
        if "exceptionDetails" in answer:
            raise RuntimeError(f"{expression}: {answer['exceptionDetails']['text']}")
        return answer["result"].get("value")

    def wait_until(self, expression: str, timeout: float | None = None):
        """Poll ``expression`` until it is truthy; its value (TimeoutError after ``timeout``)."""
        end = time.monotonic() + (self.timeout if timeout is None else timeout)
        while True:
            value = self.evaluate(expression)
            if value:
                return value
            if time.monotonic() > end:
                raise TimeoutError(f"{expression} still false after {timeout} s")
            time.sleep(0.1)

    def _centre(self, selector: str) -> tuple[float, float]:
        box = self.evaluate(f"(() => {{ const e = document.querySelector({json.dumps(selector)});"
                            " e.scrollIntoView({block: 'center'});"
                            " const r = e.getBoundingClientRect();"
                            " return [r.x + r.width / 2, r.y + r.height / 2]; })()")
        return box[0], box[1]

    def click(self, selector: str) -> None:
        """Click the middle of the element ``selector`` with the mouse, as a person would."""
        x, y = self._centre(selector)
        for kind in ("mousePressed", "mouseReleased"):
            self.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left",
                      clickCount=1)

    def type_into(self, selector: str, text: str) -> None:
        """Focus the field ``selector``, select what it holds and type ``text`` over it (input
        events as from a keyboard)."""
        self.click(selector)
        self.evaluate(f"document.querySelector({json.dumps(selector)}).select()")
        self.call("Input.insertText", text=text)

    def press(self, key: str, code: str, key_code: int) -> None:
        """Press and release one key (e.g. "Tab", "Tab", 9) in the focused element."""
        for kind in ("rawKeyDown", "keyUp"):
            self.call("Input.dispatchKeyEvent", type=kind, key=key, code=code,
                      windowsVirtualKeyCode=key_code)

    def set_files(self, selector: str, paths: list[Path]) -> None:
        """Choose ``paths`` in the file input ``selector`` (as a person's file dialog would)."""
        root = self.call("DOM.getDocument")["root"]["nodeId"]
        node = self.call("DOM.querySelector", nodeId=root, selector=selector)["nodeId"]
        self.call("DOM.setFileInputFiles", nodeId=node, files=[str(p) for p in paths])

    def downloads_into(self, folder: Path) -> None:
        """Save downloads into ``folder`` (under their own names)."""
        self.call("Browser.setDownloadBehavior", behavior="allow", downloadPath=str(folder),
                  eventsEnabled=True)

    def screenshot(self, width: int) -> bytes:
        """The whole open page, ``width`` CSS pixels wide, as PNG."""
        height = self.evaluate("document.documentElement.scrollHeight")
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=height,
                  deviceScaleFactor=1, mobile=width < 600)
        return base64.b64decode(self.call("Page.captureScreenshot", format="png")["data"])

    def errors(self) -> list[str]:
        """Console errors, uncaught exceptions and failed loads since the last navigation."""
        out = []
        for e in self.events:
            p = e.get("params", {})
            if e.get("method") == "Runtime.consoleAPICalled" and p["type"] == "error":
                out.append(" ".join(str(a.get("value")) for a in p["args"]))
            elif e.get("method") == "Runtime.exceptionThrown":
                out.append(p["exceptionDetails"]["text"])
            elif e.get("method") == "Log.entryAdded" and p["entry"]["level"] == "error":
                out.append(p["entry"]["text"])
        return out

    def print_pdf(self) -> bytes:
        """The open page printed to PDF on A4 (its print style sheet)."""
        data = self.call("Page.printToPDF", paperWidth=8.27, paperHeight=11.69)["data"]
        return base64.b64decode(data)

    def __enter__(self) -> Chromium:
        return self

    def __exit__(self, *exc) -> None:
        try:
            self.ws.close()
        finally:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
            self.proc.stderr.close()
            self.profile.cleanup()
