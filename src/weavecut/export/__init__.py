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
# laser programs' projects: written by the laser commands with the laser's settings (a
# layout.lasersetup.LaserJob), never offered as a picture format
PROJECTS = ("lbrn2",)


def formats() -> list[str]:
    return list(FORMATS)


def render(drawing, file_format: str, job=None) -> bytes:
    """``drawing`` in ``file_format``; a laser project (``PROJECTS``) with ``job``'s settings."""
    fmt = file_format.lower().lstrip(".")
    if fmt not in FORMATS + PROJECTS:
        raise ExportError(f"unknown output format {fmt!r}; choose one of {formats()}")
    module = importlib.import_module(f".{fmt}", __name__)
    if fmt in PROJECTS:
        return module.render(clean_drawing(drawing), job)
    return module.render(clean_drawing(drawing))


def write(drawing, path: str | Path, file_format: str | None = None, job=None) -> None:
    """Render ``drawing`` in the format of ``path``'s suffix and write it atomically; ``job``
    (a ``LaserJob``) is what a laser project holds besides the drawing."""
    fmt = file_format or Path(path).suffix
    write_atomic(path, render(drawing, fmt, job))
    note(path, drawing)
