"""Latency of the web app in this process (Starlette's TestClient, the job queue of
``web.jobs`` or its stand-in): each preview and kit cold (an empty cache; the first request
also imports the command's modules) and cached (the same link again).

    python benchmarks/bench_web.py
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

from starlette.testclient import TestClient

from weavecut.web.server import create_app

from weavecut.web.cache import Cache
from weavecut.web.queues import open_queue

LINKS = [
    "/strands/preview.svg?input=square-grid&size=27cm",
    "/strands.zip?input=square-grid&size=27cm",
    "/strands/preview.svg?input=pentagon-flower&size=23cm",
    "/strands.zip?input=pentagon-flower&size=23cm",
    "/puzzle/preview.svg",
    "/puzzle.zip",
    "/weave/preview.svg?input=square-grid&levels=2&outline-level=1",
    "/weave.zip?input=square-grid&levels=2&outline-level=1",
]


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        queue = open_queue(None, workers=1, cpu_seconds=300, memory_mb=4096, waiting=8)
        app = create_app(queue, Cache(Path(tmp) / "results", 2**30), Path(tmp))
        with TestClient(app) as client:
            print(f"{'link':60} {'cold s':>7} {'cached s':>9} {'bytes':>9}")
            for link in LINKS:
                times = []
                for _ in range(2):
                    start = time.perf_counter()
                    response = client.get(link)
                    times.append(time.perf_counter() - start)
                    assert response.status_code == 200, response.text
                print(f"{link:60} {times[0]:7.2f} {times[1]:9.3f} {len(response.content):9,}")


if __name__ == "__main__":
    main()
