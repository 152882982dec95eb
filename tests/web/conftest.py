"""Fixtures of the web app's tests: a working folder that must stay empty (the app writes
only into its own folder), the app with a recording queue or with the real one."""

from __future__ import annotations

import pytest

from tests.web_app import Recording, make_client
from weavecut.web.queues import open_queue


@pytest.fixture
def cwd(tmp_path, monkeypatch):
    """The server's working folder: nothing may appear in it."""
    here = tmp_path / "cwd"
    here.mkdir()
    monkeypatch.chdir(here)
    return here


@pytest.fixture
def recording(tmp_path, cwd):
    queue = Recording()
    with make_client(tmp_path, queue) as client:
        client.queue = queue
        yield client


@pytest.fixture
def served(tmp_path, cwd):
    """The app with the real queue: jobs run."""
    queue = open_queue(None, workers=1, cpu_seconds=120, memory_mb=4096, waiting=8)
    with make_client(tmp_path, queue) as client:
        yield client
