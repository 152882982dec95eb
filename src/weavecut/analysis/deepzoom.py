"""A DeepZoom tile pyramid of a level image, its tiles rendered independently and in parallel.

Layout (Microsoft's DZI, read by OpenSeadragon and most deep-zoom viewers): ``levels.dzi``
(XML: size, tile size, overlap 0, PNG) and ``levels_files/L/C_R.png``, pyramid level L from
0 (1 x 1 pixel) to ceil(log2(max(W, H))) (the full image), column C and row R of
``tile_size`` pixels (tiles on the right and bottom edges are smaller).

The full-resolution tiles are the expensive part: each is :func:`levels.tile_image` of its
pixel rectangle, which refines only the faces near it, so every tile is one task in a
process pool (or on another machine) and equals its part of the single-image render. Each
lower level is the 2 x 2 minimum of the one above: the first refinement level with a vertex
in any of four pixels is the first with a vertex in their union, which is exactly the level
image at half the resolution.
"""

from __future__ import annotations

import math
import os
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from .. import budget
from ..fileio import make_folder, note, write_atomic
from ..mesh import Mesh
from . import levels as lv

NAME = "levels"
_WORKER: dict = {}
# the disk estimate: twice the densest pyramid measured (0.45 bytes per pixel, a level-12
# zoom; whole-input pyramids take 0.07 to 0.2), each file at least one disk block
PNG_BYTES_PER_PIXEL = 1.0


def pyramid_sizes(width: int, height: int) -> list[tuple[int, int]]:
    """(width, height) of pyramid levels 0 .. ceil(log2(max(width, height)))."""
    top = math.ceil(math.log2(max(width, height, 1)))
    return [(math.ceil(width / 2 ** (top - lev)), math.ceil(height / 2 ** (top - lev)))
            for lev in range(top + 1)]


def tile_rects(width: int, height: int, size: int) -> list[tuple[int, int, int, int]]:
    """Pixel rectangles (column, row, w, h) of the tiles of a width x height level, row by row."""
    return [(c, r, min(size, width - c), min(size, height - r))
            for r in range(0, height, size) for c in range(0, width, size)]


def png_bound(width: int, height: int) -> int:
    """The most bytes an RGB PNG of width x height pixels takes: the raw rows, deflate's
    worst-case growth (zlib's ``deflateBound``) and the chunks around them."""
    raw = height * (3 * width + 1)
    return raw + (raw >> 11) + 1024


def pyramid_files(width: int, height: int, tile_size: int) -> int:
    """Files of the pyramid: the tiles of every level and the descriptor."""
    return 1 + sum(math.ceil(w / tile_size) * math.ceil(h / tile_size)
                   for w, h in pyramid_sizes(width, height))


def check_budget(grid: lv.Grid, tile_size: int, folder) -> None:
    """Refuse, before any tile is made, a pyramid of more than ``budget.MAX_FILES`` files,
    with a tile that may exceed the file-size limit, or larger than the free disk space."""
    sizes = pyramid_sizes(grid.width, grid.height)
    files = pyramid_files(grid.width, grid.height, tile_size)
    what = f"a {grid.width:,} x {grid.height:,} px pyramid in {tile_size}-pixel tiles"
    budget.check_count(files, budget.MAX_FILES, "files", what,
                       "use a larger --tile-size or a smaller --size")
    tile = min(tile_size, grid.width), min(tile_size, grid.height)
    budget.check_file_size(png_bound(*tile), f"a {tile[0]} x {tile[1]} px tile",
                           "use a smaller --tile-size", most=True)
    pixels = sum(w * h for w, h in sizes)
    budget.check_disk(int(PNG_BYTES_PER_PIXEL * pixels) + files * budget.FILE_BLOCK, folder,
                      f"{what} ({files:,} files)")


def halve(image: NDArray[np.uint8]) -> NDArray[np.uint8]:
    """The level image at half resolution: the minimum of every 2 x 2 block (UNSET beyond
    an odd edge)."""
    h, w = image.shape
    padded = np.full((h + h % 2, w + w % 2), lv.UNSET, dtype=np.uint8)
    padded[:h, :w] = image
    return padded.reshape(padded.shape[0] // 2, 2, padded.shape[1] // 2, 2).min(axis=(1, 3))


def dzi(width: int, height: int, tile_size: int) -> bytes:
    """The ``.dzi`` descriptor."""
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n'
            f'<Image xmlns="http://schemas.microsoft.com/deepzoom/2008" Format="png" '
            f'Overlap="0" TileSize="{tile_size}">\n'
            f'  <Size Width="{width}" Height="{height}"/>\n</Image>\n').encode()


def _tile_path(folder: Path, level: int, rect, tile_size: int) -> Path:
    return folder / f"{NAME}_files" / str(level) / f"{rect[0] // tile_size}_{rect[1] // tile_size}.png"


def _start(mesh: Mesh, levels: int, grid: lv.Grid, options: dict) -> None:
    _WORKER.update(mesh=mesh, levels=levels, grid=grid, options=options)


def _render(rect, path: Path) -> NDArray[np.uint8]:
    w = _WORKER
    image = lv.tile_image(w["mesh"], w["levels"], w["grid"], rect, **w["options"])
    write_atomic(path, lv.png_bytes(lv.colour(image)))
    return image


def _write(path: Path, image: NDArray[np.uint8]) -> None:
    write_atomic(path, lv.png_bytes(lv.colour(image)))


def write_pyramid(mesh: Mesh, levels: int, grid: lv.Grid, folder, *, tile_size: int = 256,
                  jobs: int | None = None, **options) -> dict:
    """Write the DeepZoom pyramid of the level image on ``grid`` into ``folder``.

    ``jobs`` processes render the full-resolution tiles (one task per tile; default: one per
    core; 1 renders in this process). Refused first if over budget (:func:`check_budget`).
    The descriptor is written last, so a viewer never sees
    a pyramid whose tiles are missing. Returns counts and seconds.
    """
    if tile_size < 1:
        raise ValueError(f"tile size must be at least 1 pixel, got {tile_size}")
    check_budget(grid, tile_size, folder)
    folder = Path(folder)
    start = time.perf_counter()
    sizes = pyramid_sizes(grid.width, grid.height)
    for lev in range(len(sizes)):  # through make_folder: locks the folder before any tile
        make_folder(folder / f"{NAME}_files" / str(lev))
    top = len(sizes) - 1
    rects = tile_rects(grid.width, grid.height, tile_size)
    paths = [_tile_path(folder, top, rect, tile_size) for rect in rects]
    image = np.empty((grid.height, grid.width), dtype=np.uint8)
    jobs = jobs or os.cpu_count() or 1
    with _pool(jobs, mesh, levels, grid, options) as pool:
        for (c, r, w, h), tile in zip(rects, pool.map(_render, rects, paths)):
            image[r:r + h, c:c + w] = tile
        rendered = time.perf_counter()
        lower = []
        for lev in range(top - 1, -1, -1):
            image = halve(image)
            for c, r, w, h in tile_rects(image.shape[1], image.shape[0], tile_size):
                lower.append((_tile_path(folder, lev, (c, r), tile_size),
                              image[r:r + h, c:c + w].copy()))
        if lower:
            list(pool.map(_write, *zip(*lower)))
    for path in [*paths, *(p for p, _ in lower)]:  # written by workers: noted here
        note(path)
    write_atomic(folder / f"{NAME}.dzi", dzi(grid.width, grid.height, tile_size))
    done = time.perf_counter()
    return {"width": grid.width, "height": grid.height, "pyramid_levels": len(sizes),
            "full_resolution_tiles": len(rects), "tiles": len(rects) + len(lower),
            "jobs": jobs, "render_seconds": rendered - start, "seconds": done - start}


class _InProcess:
    """The pool interface, run here (jobs = 1: no processes, easy to debug and profile)."""

    def __init__(self, *initargs) -> None:
        _start(*initargs)

    def map(self, fn, *iterables):
        return map(fn, *iterables)

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        _WORKER.clear()


def _pool(jobs: int, *initargs):
    if jobs == 1:
        return _InProcess(*initargs)
    return ProcessPoolExecutor(jobs, initializer=_start, initargs=initargs)
