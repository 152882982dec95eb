"""Pictures of outputs for the kit page: SVG previews drawn from a Drawing (hairlines made
visible), and PNG thumbnails of every page of a PDF.

A PDF's pages are rendered by poppler's ``pdftoppm`` when it is on PATH (the file as a printer
gets it), else drawn from the Drawing the PDF was made from with weave-cut's own PNG writer, so
the page needs no system program.
"""

from __future__ import annotations

import base64
import shutil
import struct
import subprocess
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np

from ..layout.drawing import Drawing, Polygons, Polylines, Sheet

THUMB_PX = 240  # longer side of a PDF page thumbnail
PREVIEW_PX = 600  # strokes of an SVG preview are at least one pixel at this width
DECIMALS = 1  # mm: preview coordinates (a tenth of a pixel at PREVIEW_PX on a 600 mm sheet)


def data_uri(data: bytes, mime: str) -> str:
    return f"data:{mime};base64,{base64.b64encode(data).decode('ascii')}"


def png_size(data: bytes) -> tuple[int, int]:
    """Width and height in pixels of a PNG stream (from its header chunk)."""
    return struct.unpack(">II", data[16:24])


def visible(drawing: Drawing) -> Drawing:
    """``drawing`` with every stroke at least a pixel wide when the whole drawing is shown
    ``PREVIEW_PX`` wide (laser hairlines are 0.01 mm), coordinates rounded to ``DECIMALS``."""
    width = sum(s.width for s in drawing.sheets)
    least = width / PREVIEW_PX

    def shape(s):
        if not isinstance(s, (Polygons, Polylines)):
            return s
        style = s.style
        if style.stroke and style.stroke_width < least:
            style = replace(style, stroke_width=least)
        return replace(s, coords=np.round(s.coords, DECIMALS), style=style)

    return replace(drawing, metadata=(), sheets=tuple(
        replace(sheet, layers=tuple(replace(layer, shapes=tuple(map(shape, layer.shapes)))
                                    for layer in sheet.layers))
        for sheet in drawing.sheets))


def svg_preview(drawing: Drawing) -> bytes:
    """An SVG of ``drawing`` to look at (not to cut): see ``visible``."""
    from .. import export

    return export.render(visible(drawing), "svg")


def pdf_thumbnails(pdf: Path, drawing: Drawing | None) -> tuple[list[bytes], str]:
    """PNG thumbnails of every page of ``pdf`` and what drew them ("pdftoppm" or "weave-cut");
    no thumbnails when neither can (no pdftoppm and no Drawing)."""
    if shutil.which("pdftoppm"):
        with tempfile.TemporaryDirectory(prefix="weavecut-thumbs-") as tmp:
            done = subprocess.run(["pdftoppm", "-png", "-scale-to", str(THUMB_PX), str(pdf),
                                   f"{tmp}/page"], capture_output=True, timeout=300)
            pages = sorted(Path(tmp).glob("page-*.png"), key=lambda p: int(p.stem[5:]))
            if done.returncode == 0 and pages:
                return [p.read_bytes() for p in pages], "pdftoppm"
    if drawing is None:
        return [], ""
    return [sheet_png(sheet) for sheet in drawing.sheets], "weave-cut"


def sheet_png(sheet: Sheet) -> bytes:
    """One sheet drawn by weave-cut's PNG writer, ``THUMB_PX`` on its longer side."""
    from ..export import png

    dpi = THUMB_PX * 25.4 / max(sheet.width, sheet.height)
    return png.render(Drawing((sheet,), ""), dpi=dpi)
