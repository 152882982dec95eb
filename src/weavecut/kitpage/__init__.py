"""The kit page: an HTML page showing every file a build (or one command) wrote, with a
picture of each, what it is for, its size, and the command that made it.

``weave-cut build`` writes ``DIR/index.html``; ``strands``, ``puzzle`` and ``weave`` take
``--html PAGE``; ``python -m weavecut.kitpage OUT PAGE...`` writes a page linking pages
(``make run``'s ``build/index.html``).
"""

from __future__ import annotations

import os
from pathlib import Path

from ..fileio import write_atomic
from .document import Run, index, page

__all__ = ["Run", "index", "page", "write", "write_index"]


def write(path: str | os.PathLike, title: str, runs: list[Run]) -> None:
    """Write the kit page of ``runs`` to ``path`` atomically."""
    path = Path(path)
    write_atomic(path, page(title, runs, path.parent).encode("utf-8"))


def write_index(path: str | os.PathLike, title: str, pages: list[Path]) -> None:
    """Write a page linking the kit ``pages`` to ``path`` atomically."""
    path = Path(path)
    write_atomic(path, index(title, [Path(p) for p in pages], path.parent).encode("utf-8"))
