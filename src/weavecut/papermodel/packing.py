"""Dense pages: a raster polygon packer (turns in 15 degree steps, never mirrored).

Every piece, turned by each allowed angle, becomes a mask on a grid of ``cell`` mm: the cells
whose centre lies within ``gap / 2 + cell / sqrt(2)`` of the piece. Two pieces whose masks share
no cell are at least ``gap`` apart (a point nearer than ``gap / 2`` to both would put its
cell in both masks), and a piece lies inside the union of its mask's cells, so inside the page
when its mask is. Where a mask fits on a page's occupancy grid is one FFT correlation per
angle; of all the places that fit the piece goes where its top is lowest, then leftmost
(gravity packing), pieces largest first, each on the first page with room (first fit).

Congruent pieces (the k copies of a module strip) share their masks: pass the same ``kind``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from numpy.typing import NDArray
from scipy.signal import fftconvolve

ANGLE_STEP = 15.0  # degrees between the turns tried


@dataclass(frozen=True)
class Place:
    """Where a piece went: ``page`` (0-based), turned by ``angle`` degrees about the origin of its
    own frame, then moved by ``shift`` (mm, in the packing area's frame)."""

    page: int
    angle: float
    shift: tuple[float, float]

    def matrix(self) -> NDArray[np.float64]:
        """(3, 3) the affine map from the piece's frame to the packing area."""
        a = np.radians(self.angle)
        c, s = np.cos(a), np.sin(a)
        return np.array([[c, -s, self.shift[0]], [s, c, self.shift[1]], [0.0, 0.0, 1.0]])


def _turned(shape, angle: float):
    a = np.radians(angle)
    c, s = np.cos(a), np.sin(a)
    return shapely.transform(shape, lambda xy: xy @ np.array([[c, s], [-s, c]]))


def _mask(shape, angle: float, gap: float, cell: float, width: float, height: float):
    """(mask, origin) of ``shape`` turned by ``angle``: origin is where cell (0, 0) of the mask
    starts in the turned frame; None when the turned piece cannot fit the area at all."""
    turned = _turned(shape, angle)
    reach = gap / 2 + cell * np.sqrt(0.5)
    x0, y0, x1, y1 = turned.bounds
    nx = int(np.ceil((x1 - x0 + 2 * reach) / cell))
    ny = int(np.ceil((y1 - y0 + 2 * reach) / cell))
    if nx > width // cell or ny > height // cell:
        return None
    origin = np.array([x0 - reach, y0 - reach])
    xs = origin[0] + (np.arange(nx) + 0.5) * cell
    ys = origin[1] + (np.arange(ny) + 0.5) * cell
    gx, gy = np.meshgrid(xs, ys)
    grown = shapely.buffer(turned, reach, quad_segs=4)
    shapely.prepare(grown)
    mask = shapely.contains_xy(grown, gx, gy)
    return mask.astype(np.float64), origin


def pack(shapes, width: float, height: float, gap: float = 2.0, cell: float = 1.0,
         kinds=None, angle_step: float = ANGLE_STEP) -> list[Place]:
    """Pack ``shapes`` (shapely polygons, mm) onto as few ``width`` x ``height`` areas as it can.

    Parameters
    ----------
    shapes : (n,) polygons in their own frames
    width, height : the packing area (mm); the area's lower-left corner is the origin
    gap : least distance between two pieces (mm)
    cell : grid size (mm); smaller packs tighter and slower
    kinds : (n,) ints, equal for congruent pieces (their masks are computed once)
    angle_step : turns tried are the multiples of this (degrees), never a mirror

    Returns
    -------
    one Place per shape, in input order

    Raises
    ------
    ValueError if a piece fits the area at no angle
    """
    shapes = np.asarray(shapes, dtype=object)
    n = len(shapes)
    kinds = np.arange(n) if kinds is None else np.asarray(kinds)
    angles = np.arange(0.0, 360.0, angle_step)
    nx, ny = int(width // cell), int(height // cell)
    masks: dict[int, list] = {}
    areas = shapely.area(shapes)
    order = np.lexsort((np.arange(n), -areas))
    grids: list[NDArray[np.float64]] = []
    out: list[Place | None] = [None] * n
    for i in order.tolist():  # pieces, not mesh elements
        key = int(kinds[i])
        if key not in masks:
            masks[key] = [(a, *m) for a in angles.tolist()
                          if (m := _mask(shapes[i], a, gap, cell, width, height)) is not None]
            if not masks[key]:
                x0, y0, x1, y1 = shapes[i].bounds
                raise ValueError(f"a strip of {x1 - x0:.0f} x {y1 - y0:.0f} mm fits the printable "
                                 f"area of {width:.0f} x {height:.0f} mm at no angle")
        need = masks[key][0][1].sum()
        for page in range(len(grids) + 1):
            if page == len(grids):
                grids.append(np.zeros((ny, nx)))
            grid = grids[page]
            if grid.size - grid.sum() < need:
                continue
            best = _best_spot(grid, masks[key])
            if best is not None:
                (iy, ix), angle, mask, origin = best
                grid[iy:iy + mask.shape[0], ix:ix + mask.shape[1]] += mask
                shift = (ix * cell - origin[0], iy * cell - origin[1])
                out[i] = Place(page, float(angle), (float(shift[0]), float(shift[1])))
                break
    return out  # type: ignore[return-value]


def _best_spot(grid, options):
    """((iy, ix), angle, mask, origin) with the lowest top, then leftmost; None if none fits."""
    best, best_key = None, None
    for angle, mask, origin in options:  # the allowed turns
        my, mx = mask.shape
        if my > grid.shape[0] or mx > grid.shape[1]:
            continue
        hits = fftconvolve(grid, mask[::-1, ::-1], mode="valid")
        free = np.argwhere(hits < 0.5)
        if len(free) == 0:
            continue
        tops = free[:, 0] + my
        j = np.lexsort((free[:, 1], tops))[0]
        key = (int(tops[j]), int(free[j, 1]))
        if best_key is None or key < best_key:
            best, best_key = ((int(free[j, 0]), int(free[j, 1])), angle, mask, origin), key
    return best
