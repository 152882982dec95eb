"""Writers: every format renders a Drawing to bytes; ``write`` picks one by suffix."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..errors import ExportError
from ..fileio import write_atomic
from ..layout.drawing import Drawing
from ..text import clean_drawing
from . import dxf, pdf, png, svg

RENDERERS: dict[str, Callable[[Drawing], bytes]] = {m.SUFFIX: m.render for m in (svg, dxf, pdf, png)}


def formats() -> list[str]:
    return sorted(RENDERERS)


def render(drawing: Drawing, file_format: str) -> bytes:
    fmt = file_format.lower().lstrip(".")
    if fmt not in RENDERERS:
        raise ExportError(f"unknown output format {fmt!r}; choose one of {formats()}")
    return RENDERERS[fmt](clean_drawing(drawing))


def write(drawing: Drawing, path: str | Path, file_format: str | None = None) -> None:
    """Render ``drawing`` in the format of ``path``'s suffix and write it atomically."""
    fmt = file_format or Path(path).suffix
    write_atomic(path, render(drawing, fmt))
