"""A Raster's pixels as a greyscale PNG, written here byte by byte so that the bytes are the
same wherever the same zlib runs: no filter, zlib at a fixed level, no time or software chunk.
The PDF writer embeds the same zlib stream (``deflated``) as an image XObject with PNG
predictors, so a picture costs the same in both formats."""

from __future__ import annotations

import struct
import zlib

import numpy as np
from numpy.typing import NDArray

LEVEL = 9  # zlib's compression level: fixed, so the stream does not follow a library default
# PNG's filter of every row: none. A texture of fine lines is noise to the predicting filters:
# Paeth's stream of the level-8 panel is a third larger (1.64 MB against 1.23 MB), Sub's and
# Up's are too
FILTER = 0


def deflated(pixels: NDArray[np.uint8]) -> bytes:
    """The zlib stream of ``pixels`` (H, W) as PNG rows: a filter byte, then the row."""
    pixels = np.asarray(pixels, dtype=np.uint8)
    rows = np.empty((pixels.shape[0], pixels.shape[1] + 1), dtype=np.uint8)
    rows[:, 0] = FILTER
    rows[:, 1:] = pixels
    return zlib.compress(rows.tobytes(), LEVEL)


def png(pixels: NDArray[np.uint8], dpi: float) -> bytes:
    """``pixels`` (H, W) uint8 as an 8-bit greyscale PNG stating ``dpi``."""
    h, w = np.shape(pixels)
    per_metre = round(dpi / 0.0254)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
            + chunk(b"pHYs", struct.pack(">IIB", per_metre, per_metre, 1))
            + chunk(b"IDAT", deflated(pixels)) + chunk(b"IEND", b""))


def dpi(raster) -> float:
    """Pixels per inch of ``raster`` across (its pixels over its width)."""
    return raster.pixels.shape[1] / raster.width * 25.4


def chunk(kind: bytes, body: bytes) -> bytes:
    """A PNG chunk: its length, ``kind``, ``body`` and their CRC."""
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
