"""The web app under Starlette's TestClient, for ``tests/web/``: the real job queue
(``web.jobs``, or its stand-in until that branch is merged) or a recording one that runs
nothing."""

from __future__ import annotations

try:
    from weavecut.web.jobs import Cache, JobResult, open_queue
except ImportError:  # until the job queue's branch is merged
    from weavecut.web.standin import Cache, JobResult, open_queue


class Recording:
    """A queue that records every job and answers a tiny preview, running nothing."""

    def __init__(self) -> None:
        self.specs = []

    async def run(self, spec):
        self.specs.append(spec)
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
