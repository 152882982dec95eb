"""The web app under Starlette's TestClient, for ``tests/web/``: the real job queue
(``web.jobs``, or its stand-in until that branch is merged) or a recording one that runs
nothing."""

from __future__ import annotations

import html
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

from weavecut.web.cache import Cache
from weavecut.web.jobs import JobResult
from weavecut.web.uploads import read_job


class Recording:
    """A queue that records every job and answers a tiny preview, running nothing but the
    reading of uploads (``read_job``, in this process)."""

    def __init__(self) -> None:
        self.specs = []

    async def run(self, spec):
        self.specs.append(spec)
        if spec.kind == "read":
            return read_job(spec)
        body = b"<svg xmlns='http://www.w3.org/2000/svg'/>"
        return JobResult(True, body, "image/svg+xml", {"strands": 1})

    async def close(self) -> None:
        pass


def make_client(tmp_path, queue):
    from starlette.testclient import TestClient

    from weavecut.web.server import create_app

    folder = tmp_path / "app"
    app = create_app(queue, Cache(folder / "results", 2**28), folder)
    return TestClient(app, raise_server_exceptions=False)


def written(root, app_folder) -> list[str]:
    """Files under ``root`` outside ``app_folder``."""
    return sorted(str(p.relative_to(root)) for p in root.rglob("*")
                  if p.is_file() and not p.is_relative_to(app_folder))


def cli_files(page: str, folder: Path) -> dict[str, bytes]:
    """The files the CLI writes, run in the empty ``folder`` with the command line that the
    kit page ``page`` shows (its files record that command line: the CLI itself, as the job
    ran it, with its own sys.argv)."""
    found = re.search(r"weave-cut ((?:-\S+ )*(?:strands|puzzle|weave|subdivide|figure) [^<]*)",
                      page)
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(os.path.abspath(p) for p in sys.path)}
    subprocess.run([sys.executable, "-m", "weavecut", *shlex.split(html.unescape(
        found.group(1)))], cwd=folder, env=env, check=True, capture_output=True)
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}
