"""Writers: every format renders a Drawing to bytes; ``write`` picks one by suffix.

A writer module is imported when its format is first used, so a command that writes SVG never
loads ezdxf, reportlab or Pillow.
"""

from __future__ import annotations

import importlib
from pathlib import Path

from ..errors import ExportError
from ..fileio import note, write_atomic
from ..text import clean_drawing

FORMATS = ("dxf", "pdf", "png", "svg")  # each the SUFFIX of the module of that name


def formats() -> list[str]:
    return list(FORMATS)


def render(drawing, file_format: str) -> bytes:
    fmt = file_format.lower().lstrip(".")
    if fmt not in FORMATS:
        raise ExportError(f"unknown output format {fmt!r}; choose one of {formats()}")
    return importlib.import_module(f".{fmt}", __name__).render(clean_drawing(drawing))


def write(drawing, path: str | Path, file_format: str | None = None) -> None:
    """Render ``drawing`` in the format of ``path``'s suffix and write it atomically."""
    fmt = file_format or Path(path).suffix
    write_atomic(path, render(drawing, fmt))
    note(path, drawing)
