"""A value worked out once per test session and shared by pytest-xdist's workers: the first
test to ask makes it while the others wait on its lock, and keeps it as JSON in the session's
temporary root (``session_root``), which every worker of this session shares and no other
session sees, so nothing made by older code is ever read back."""

from __future__ import annotations

import fcntl
import hashlib
import json
from pathlib import Path
from typing import Any, Callable

import pytest


def session_root(factory: pytest.TempPathFactory) -> Path:
    """The folder the workers of this session share: the parent of a worker's base temporary
    folder (``pytest-N/popen-gw0``), or the base folder itself without xdist."""
    base = factory.getbasetemp()
    return base.parent if base.name.startswith("popen-gw") else base


def once(root: Path, key: str, make: Callable[[], Any]) -> Any:
    """``make()`` for ``key``, made by the first caller in ``root`` and read back by the
    others (a JSON value)."""
    folder = root / "once"
    folder.mkdir(exist_ok=True)
    name = hashlib.sha256(key.encode()).hexdigest()[:24]
    with open(folder / f"{name}.lock", "w", encoding="utf-8") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        path = folder / f"{name}.json"
        if path.exists():  # written whole under the lock
            return json.loads(path.read_text(encoding="utf-8"))
        value = make()
        path.write_text(json.dumps(value), encoding="utf-8")
        return value
