"""20 kits asked for at once from ``weave-cut serve`` on the 2-core machine, as a class of makers
would: every answer is a ZIP (200) or "busy, retry" (503 with Retry-After), never a 500; the
server's memory stays bounded, no job process is left behind, and it answers afterwards. Once
with the defaults (two workers: every kit is made), once with one worker and room for two
waiting kits (most are turned away with 503)."""

from __future__ import annotations

import io
import os
import re
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
import zipfile
from pathlib import Path

import pytest

KITS = 20
TIMEOUT = 600  # s for one request: all of them queue behind two workers on a busy machine


def rss_mb(pid: int) -> float:
    """Resident memory of one process, from /proc."""
    status = Path(f"/proc/{pid}/status").read_text()
    return int(re.search(r"VmRSS:\s+(\d+) kB", status)[1]) / 1024


def descendants(pid: int) -> set[int]:
    """Every process below ``pid`` (children, grandchildren), from /proc."""
    parent = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            parent[int(entry.name)] = int(fields[1])
    found, frontier = set(), {pid}
    while frontier:
        frontier = {p for p, pp in parent.items() if pp in frontier} - found
        found |= frontier
    return found


def get(url: str) -> tuple[int, object, bytes]:
    """Status, headers (names in any case) and body of a GET."""
    try:
        with urllib.request.urlopen(url, timeout=TIMEOUT) as response:
            return response.status, response.headers, response.read()
    except urllib.error.HTTPError as error:
        return error.code, error.headers, error.read()


@pytest.fixture(params=[(2, None), (1, 2)], ids=["defaults", "one-worker-two-waiting"])
def server(request, tmp_path_factory):
    if not sys.platform.startswith("linux"):
        pytest.skip("reads /proc")
    folder = tmp_path_factory.mktemp("serve")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    workers, waiting = request.param
    limit = ["--waiting", str(waiting)] if waiting is not None else []
    proc = subprocess.Popen([sys.executable, "-m", "weavecut", "serve", "--port", "0",
                             "--workers", str(workers), *limit, "--cache",
                             str(folder / "cache")], cwd=folder, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    found = re.search(r"http://[^ ]+/", proc.stdout.readline())
    assert found, "weave-cut serve printed no address"
    yield proc, found.group(0), waiting
    proc.terminate()
    proc.wait(timeout=30)
    proc.stdout.close()


@pytest.mark.slow
def test_twenty_kits_at_once(server):
    proc, url, waiting = server
    # warm: the first kit starts the worker processes; its memory is the baseline
    status, _, _ = get(f"{url}puzzle.zip?input=pentagon&levels=2&size=19cm")
    assert status == 200
    before, children = rss_mb(proc.pid), len(descendants(proc.pid))
    links = [f"{url}puzzle.zip?input=pentagon&levels=2&size={20 + k}cm" if k % 2 else
             f"{url}strands.zip?input=square-grid&size={20 + k}cm" for k in range(KITS)]
    answers: list = [None] * KITS

    def ask(k: int) -> None:
        answers[k] = get(links[k])

    threads = [threading.Thread(target=ask, args=(k,)) for k in range(KITS)]
    start = time.monotonic()
    for t in threads:
        t.start()
    for t in threads:
        t.join(TIMEOUT + 30)
    elapsed = time.monotonic() - start
    assert all(a is not None for a in answers), "a request never came back"
    statuses = [a[0] for a in answers]
    assert set(statuses) <= {200, 503}, statuses
    for status, headers, body in answers:
        if status == 200:
            with zipfile.ZipFile(io.BytesIO(body)) as kit:
                assert kit.testzip() is None and "index.html" in kit.namelist()
        else:
            assert int(headers["Retry-After"]) > 0
    if waiting is None:
        assert statuses == [200] * KITS  # room for all: every kit is made
    else:  # one running, ``waiting`` waiting: the rest are turned away at once
        assert 1 + waiting <= statuses.count(200) < KITS and 503 in statuses, statuses
    # bounded: the server holds no kit in memory for long, and no job process is left over
    time.sleep(1)
    after = rss_mb(proc.pid)
    assert after < before + 150, (before, after)
    assert len(descendants(proc.pid)) <= children, "job processes left behind"
    status, _, page = get(url)
    assert status == 200 and b"weave-cut" in page
    print(f"\n{KITS} kits at once: {statuses.count(200)} x 200, {statuses.count(503)} x 503 "
          f"in {elapsed:.1f} s; server {before:.0f} -> {after:.0f} MB")
