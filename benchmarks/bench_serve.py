"""Latency of ``weave-cut serve`` as a browser meets it: HTTP requests to a running server
(its embedded job queue, worker processes with the default limits), timed with
``time.perf_counter`` around each request; every run starts a server with an empty cache,
warms it with one unrelated preview (the job processes' warm parent starts on first use),
then asks for each product's preview (first, then cached) and kit (first, then cached).
Prints the median of the runs.

    python benchmarks/bench_serve.py [RUNS]
"""

from __future__ import annotations

import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HEART = ROOT / "templates" / "recipes" / "heart.svg"
PRODUCTS = {  # what a new user makes, with the form's defaults
    "square-grid paper model": "strands?input=square-grid&size=27cm",
    "heart puzzle (upload)": "puzzle?input=upload:{heart}",
    "woven ball": "strands?input=dodecahedron&levels=1&project=sphere&size=12cm",
}


def timed(url: str, data: bytes | None = None) -> tuple[float, bytes]:
    start = time.perf_counter()
    with urllib.request.urlopen(urllib.request.Request(url, data=data), timeout=600) as r:
        body = r.read()
    return time.perf_counter() - start, body


def one_run() -> dict[str, float]:
    found = {}
    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
        server = subprocess.Popen([sys.executable, "-m", "weavecut", "serve", "--port", "0",
                                   "--cache", tmp], stdout=subprocess.PIPE, text=True, env=env,
                                  stderr=subprocess.DEVNULL)
        try:
            base = re.search(r"http://[^ ]+/", server.stdout.readline()).group(0)
            timed(base + "subdivide/preview.svg?input=pentagon&levels=1")  # warm the workers
            found["upload heart.svg"], body = timed(base + "upload", HEART.read_bytes())
            heart = json.loads(body)["id"]
            for name, page in PRODUCTS.items():
                command, _, query = page.format(heart=heart).partition("?")
                for kind, path in (("preview", f"{command}/preview.svg?{query}"),
                                   ("kit", f"{command}.zip?{query}")):
                    found[f"{name}: {kind}, first"] = timed(base + path)[0]
                    found[f"{name}: {kind}, cached"] = timed(base + path)[0]
        finally:
            server.terminate()
            server.wait()
    return found


def main() -> None:
    runs = [one_run() for _ in range(int(sys.argv[1]) if len(sys.argv) > 1 else 3)]
    print(f"{'request':48} {'median s':>9}   runs")
    for key in runs[0]:
        times = [r[key] for r in runs]
        print(f"{key:48} {statistics.median(times):9.3f}   "
              + " ".join(f"{t:.3f}" for t in times))


if __name__ == "__main__":
    main()
