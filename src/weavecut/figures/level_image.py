"""The level image figure (the paper's colorLevels, a raster figure): pixels coloured by level.

``level_image_png`` is the PNG builder of ``figures.subdivision.FIGURES["level-image"]``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .. import inputs
from ..analysis import levels as lv

LEVEL_ZOOM = (0.29, 0.09, 0.39, 0.19)


def _frame(rgb: NDArray[np.uint8], box, colour=(224, 48, 42), width: int = 2) -> None:
    r0, c0, r1, c1 = box
    rgb[r0:r0 + width, c0:c1] = colour
    rgb[r1 - width:r1, c0:c1] = colour
    rgb[r0:r1, c0:c0 + width] = colour
    rgb[r0:r1, c1 - width:c1] = colour


def level_image_png(size: int = 1200, zoom_size: int = 560, levels: int = 9,
                    zoom_levels: int = 12, zoom=LEVEL_ZOOM) -> bytes:
    """Figure colorLevels: the pentagon to level 9 (left, the zoom box framed in red); right,
    the box as the left image has it (enlarged pixels), and recomputed to level 12."""
    mesh = inputs.get("pentagon")
    big, grid = lv.level_image(mesh, levels, size)
    deep, _ = lv.level_image(mesh, zoom_levels, zoom_size, zoom)
    left = lv.colour(big)
    x0, _, _, y1 = grid.window
    c0 = int(round((zoom[0] - x0) / grid.pixel))
    c1 = int(round((zoom[2] - x0) / grid.pixel))
    r0 = int(round((y1 - zoom[3]) / grid.pixel))
    r1 = int(round((y1 - zoom[1]) / grid.pixel))
    crop = left[r0:r1, c0:c1]
    rows = np.minimum(np.arange(zoom_size) * crop.shape[0] // zoom_size, crop.shape[0] - 1)
    cols = np.minimum(np.arange(zoom_size) * crop.shape[1] // zoom_size, crop.shape[1] - 1)
    near = crop[rows][:, cols]
    _frame(left, (r0 - 2, c0 - 2, r1 + 2, c1 + 2))
    gap = 16
    height = max(left.shape[0], 2 * zoom_size + gap)
    canvas = np.full((height, left.shape[1] + gap + zoom_size, 3), 255, dtype=np.uint8)
    canvas[:left.shape[0], :left.shape[1]] = left
    for k, rgb in enumerate((near, lv.colour(deep))):
        rgb = rgb.copy()
        _frame(rgb, (0, 0, rgb.shape[0], rgb.shape[1]))
        top = k * (zoom_size + gap)
        canvas[top:top + rgb.shape[0], left.shape[1] + gap:left.shape[1] + gap + rgb.shape[1]] \
            = rgb
    legend = _legend(max(zoom_levels, levels) + 1, width=canvas.shape[1])
    return lv.png_bytes(np.concatenate([canvas, legend], axis=0))


def _legend(n: int, width: int, height: int = 28) -> NDArray[np.uint8]:
    """A strip of the level colours 0..n-1 (no text: the README explains the scale)."""
    out = np.full((height, width, 3), 255, dtype=np.uint8)
    cell = min(40, width // max(n, 1))
    colours = lv.colour(np.arange(n, dtype=np.uint8)[None, :])[0]
    for k in range(n):  # a loop over levels
        out[6:height - 6, k * cell + 2:(k + 1) * cell - 2] = colours[k]
    return out
