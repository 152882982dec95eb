"""PNG writer (Pillow): sheets rasterised at ``DPI``, supersampled for smooth edges; several
sheets are stacked top to bottom; a picture (Raster) is pasted over its box. Hidden layers are
left out. The title and the metadata (generator, command) are text chunks, which ``with_text``
also adds to raster figures. Pillow installs from wheels with no system libraries, so PNG
output works everywhere weave-cut does."""

from __future__ import annotations

import io
import math
from collections.abc import Iterable
from functools import lru_cache

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from .. import budget
from ..errors import ExportError
from ..layout.drawing import Drawing, Polylines, Raster, Text
from ..layout.labels import CAP_RATIO, text_width
from .picture import chunk

SUFFIX = "png"
DPI = 150
SUPERSAMPLE = 2
MAX_PIXELS = 12_000 * 12_000
# the memory guard's model, per output pixel (fitted to peak RSS: 27 bytes per pixel for one
# sheet of 36 and of 129 million pixels): while a sheet is drawn, its supersampled picture
# (12), a mask for a fill with holes (4) and the resampling's half-way picture (6); every
# page kept (3); the stacked picture and the PNG stream (3 each)
SHEET_BYTES_PER_PIXEL = 22
PAGE_BYTES_PER_PIXEL = 3
STACK_BYTES_PER_PIXEL = 6


def render(drawing: Drawing, dpi: float = DPI) -> bytes:
    check_size(drawing, dpi)
    pages = [_sheet(sheet, dpi) for sheet in drawing.sheets]
    width = max(p.width for p in pages)
    height = sum(p.height for p in pages) + 10 * (len(pages) - 1)
    out = Image.new("RGB", (width, height), "white")
    y = 0
    for page in pages:
        out.paste(page, (0, y))
        y += page.height + 10
    buf = io.BytesIO()
    out.save(buf, "PNG", dpi=(dpi, dpi), optimize=False)
    return with_text(buf.getvalue(), [("Title", drawing.title), *drawing.metadata])


def _pixels(sheet, dpi: float) -> tuple[int, int]:
    """(width, height) of ``sheet`` in supersampled pixels."""
    px = dpi / 25.4 * SUPERSAMPLE
    return round(sheet.width * px), round(sheet.height * px)


def check_size(drawing: Drawing, dpi: float = DPI) -> None:
    """Refuse, before drawing anything, a sheet or the sheets stacked over ``MAX_PIXELS``,
    or a picture that would not fit in memory."""
    sizes = [_pixels(sheet, dpi) for sheet in drawing.sheets]
    for sheet, (w, h) in zip(drawing.sheets, sizes):
        if w * h > MAX_PIXELS * SUPERSAMPLE**2:
            raise ExportError(f"a {sheet.width:.0f} x {sheet.height:.0f} mm sheet at {dpi:g} "
                              f"dpi is too large for PNG ({w // SUPERSAMPLE} x "
                              f"{h // SUPERSAMPLE} px)")
    out = [max(1, w // SUPERSAMPLE) * max(1, h // SUPERSAMPLE) for w, h in sizes]
    width = max(max(1, w // SUPERSAMPLE) for w, _ in sizes)
    height = sum(max(1, h // SUPERSAMPLE) for _, h in sizes) + 10 * (len(sizes) - 1)
    if width * height > MAX_PIXELS:
        raise ExportError(f"{len(sizes)} sheets at {dpi:g} dpi stacked are too large for PNG "
                          f"({width} x {height} px)")
    budget.check_memory(budget.BASE_BYTES + SHEET_BYTES_PER_PIXEL * max(out)
                        + PAGE_BYTES_PER_PIXEL * sum(out)
                        + STACK_BYTES_PER_PIXEL * width * height,
                        f"a {width} x {height} px PNG")


def with_text(data: bytes, items: Iterable[tuple[str, str]]) -> bytes:
    """The PNG ``data`` with a text chunk per (keyword, text) after its header chunk: tEXt
    when the text is Latin-1, else iTXt (UTF-8). The pixels are not decoded again."""
    if data[12:16] != b"IHDR":
        raise ExportError("not a PNG stream")
    end = 8 + 4 + 4 + 13 + 4  # signature, then IHDR: length, type, 13 bytes, CRC
    return data[:end] + b"".join(_text_chunk(k, v) for k, v in items) + data[end:]


def _text_chunk(keyword: str, text: str) -> bytes:
    try:
        kind, body = b"tEXt", keyword.encode("latin-1") + b"\0" + text.encode("latin-1")
    except UnicodeEncodeError:  # keyword, no compression, no language, no translated keyword
        kind, body = b"iTXt", keyword.encode("latin-1") + b"\0\0\0\0\0" + text.encode("utf-8")
    return chunk(kind, body)


def _sheet(sheet, dpi: float) -> Image.Image:
    px = dpi / 25.4 * SUPERSAMPLE
    w, h = _pixels(sheet, dpi)
    img = Image.new("RGB", (w, h), "white")
    draw = ImageDraw.Draw(img)

    def to_px(xy):
        xy = np.asarray(xy, dtype=float)
        return [(x * px, (sheet.height - y) * px) for x, y in xy.tolist()]

    for layer in sheet.layers:
        if not layer.visible:
            continue
        for shape in layer.shapes:
            if isinstance(shape, Raster):
                _picture(img, shape, px, sheet.height)
                continue
            if isinstance(shape, Text):
                font = _font(shape.text, shape.size, px)
                anchor = {"start": "ls", "middle": "ms", "end": "rs"}[shape.anchor]
                (x, y), = to_px([(shape.x, shape.y)])
                if shape.angle:
                    _rotated_text(img, (x, y), shape.text, font, shape.fill, shape.angle, anchor)
                else:
                    draw.text((x, y), shape.text, fill=shape.fill, font=font, anchor=anchor)
                continue
            if not shape.style.stroke and isinstance(shape, Polylines):
                continue  # nothing to draw (older Pillow drew a 0-wide line 1 px wide)
            width = max(1, round(shape.style.stroke_width * px)) if shape.style.stroke else 0
            if isinstance(shape, Polylines):
                for line in shape.lines():
                    draw.line(to_px(line), fill=shape.style.stroke, width=width, joint="curve")
                continue
            fills = shape.fills or (shape.style.fill,) * shape.n_polygons
            po = shape.polygon_rings().tolist()
            rings = shape.rings()
            for i, fill in enumerate(fills):
                own = rings[po[i]:po[i + 1]]
                if fill and len(own) == 1:
                    draw.polygon(to_px(own[0]), fill=fill)
                elif fill:
                    mask = Image.new("L", img.size, 0)
                    md = ImageDraw.Draw(mask)
                    md.polygon(to_px(own[0]), fill=255)
                    for hole in own[1:]:
                        md.polygon(to_px(hole), fill=0)
                    img.paste(fill, mask=mask)
                if shape.style.stroke:
                    for ring in own:
                        # closed through the second point again: Pillow joins only the
                        # inner points of a line, and the first corner is one of them too
                        pts = to_px(ring)
                        draw.line(pts + pts[:2], fill=shape.style.stroke, width=width,
                                  joint="curve")
    return img.resize((max(1, w // SUPERSAMPLE), max(1, h // SUPERSAMPLE)), Image.LANCZOS)


def _picture(img: Image.Image, raster: Raster, px: float, height: float) -> None:
    """``raster`` over its box (whole pixels of ``img``, ``px`` a mm), averaged down or
    repeated up to the box's size (Pillow's box filter)."""
    left, right = round(raster.x * px), round((raster.x + raster.width) * px)
    top, bottom = (round((height - raster.y - raster.height) * px),
                   round((height - raster.y) * px))
    pic = Image.fromarray(np.ascontiguousarray(raster.pixels), "L")
    img.paste(pic.resize((max(1, right - left), max(1, bottom - top)), Image.BOX).convert("RGB"),
              (left, top))


def _font(text: str, size: float, px: float) -> ImageFont.FreeTypeFont:
    """The SVG writer's DejaVu Sans where the system has it (else Pillow's own font, which
    lacks signs like the superscript two), at cap height ``size`` mm, made smaller where it
    would run wider than the width the layout reserved for ``text``."""
    em = size / CAP_RATIO * px
    font = _face(max(1, int(em)))
    natural = font.getlength(text)
    room = text_width(text, size) * px
    return font if natural <= room else _face(max(1, int(em * room / natural)))


@lru_cache(maxsize=None)
def _face(size: int) -> ImageFont.FreeTypeFont:
    """The font at ``size`` px, loaded once (a sheet has hundreds of texts in a few sizes)."""
    try:
        return ImageFont.truetype("DejaVuSans.ttf", size)
    except OSError:
        return ImageFont.load_default(size=size)


def _rotated_text(img, xy, text, font, fill, angle, anchor) -> None:
    """``text`` turned ``angle`` degrees counter-clockwise about its anchor point ``xy``, as
    SVG and PDF turn it: drawn on a square tile with the anchor at the centre, large enough
    for the text turned any way, and the tile turned about its centre."""
    box = font.getbbox(text, anchor=anchor)  # relative to the anchor point
    r = math.ceil(math.hypot(max(-box[0], box[2]), max(-box[1], box[3]))) + 2
    tile = Image.new("RGBA", (2 * r, 2 * r), (0, 0, 0, 0))
    ImageDraw.Draw(tile).text((r, r), text, font=font, fill=fill, anchor=anchor)
    tile = tile.rotate(angle, center=(r, r))
    img.paste(tile, (round(xy[0]) - r, round(xy[1]) - r), tile)
