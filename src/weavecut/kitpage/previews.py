"""Pictures of outputs for the kit page: SVG previews drawn from a Drawing (hairlines made
visible), PNG thumbnails of every page of a PDF, and PNG pictures of cut files as the cut
comes out: a print-and-cut file's cut lines drawn over the printed page, a card sheet's lines
on the card's colour.

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

from ..layout.contrast import text_colour_on
from ..layout.drawing import Drawing, Layer, Polygons, Polylines, Sheet, Style

THUMB_PX = 240  # longer side of a PDF page thumbnail
CUT_PX = 400  # longer side of a cut file's picture
CUT_OVER = "#e4002b"  # the cut lines drawn over a printed page
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


def sheet_png(sheet: Sheet, px: int = THUMB_PX) -> bytes:
    """One sheet drawn by weave-cut's PNG writer, ``px`` on its longer side."""
    from ..export import png

    dpi = px * 25.4 / max(sheet.width, sheet.height)
    return png.render(Drawing((sheet,), ""), dpi=dpi)


def _restyled(layer: Layer, stroke: str, width: float) -> Layer:
    """``layer`` with every line and outline stroked ``stroke``, ``width`` mm, unfilled."""
    style = Style(stroke, width, None)
    return replace(layer, shapes=tuple(replace(s, style=style, **({"fills": None} if isinstance(
        s, Polygons) else {})) for s in layer.shapes if isinstance(s, (Polygons, Polylines))))


def _line(sheet: Sheet) -> float:
    """mm of one pixel of ``sheet`` drawn ``CUT_PX`` on its longer side."""
    return max(sheet.width, sheet.height) / CUT_PX


def overlay_png(page: Sheet, cut: Sheet) -> bytes:
    """The printed ``page`` with the cut layers of ``cut`` (a print-and-cut file of it) drawn
    over it in red, two pixels wide: where the knife will run on the print."""
    over = [_restyled(layer, CUT_OVER, 2 * _line(page)) for layer in cut.layers
            if layer.role == "cut"]
    return sheet_png(replace(page, layers=(*page.layers, *over)), CUT_PX)


def card_png(sheet: Sheet, colour: str) -> bytes:
    """A laser sheet as it comes out of card of ``colour``: its engraved lines one pixel and
    its cuts two pixels wide, in black or white (whichever reads on the card)."""
    ink, px = text_colour_on(colour), _line(sheet)
    card = Polygons(np.array([[0, 0], [sheet.width, 0], [sheet.width, sheet.height],
                              [0, sheet.height]], dtype=float), np.array([0, 4]),
                    Style(None, 0.0, colour))
    lines = [_restyled(layer, ink, px * (2 if layer.role == "cut" else 1))
             for layer in sheet.layers if layer.visible and layer.role in ("cut", "engrave",
                                                                          "score")]
    return sheet_png(replace(sheet, layers=(Layer("card", "paint", (card,)), *lines)), CUT_PX)
