"""Kerf compensation and nesting of separately cut parts onto sheets.

Kerf: a part is cut along its outline offset outward by kerf/2 (a hole inward by kerf/2), with
mitred corners, so that after the beam removes kerf/2 on either side of the cut line the part
has its design size. ``kerf = 0`` leaves compensation to the laser software.

Nesting: every part is turned to its minimum-area bounding rectangle and laid flat (long side
along x), then the rectangles, inflated by the spacing, are placed tallest first with a skyline
bottom-left packer (each goes where its bottom is lowest, then leftmost) on the first sheet where
it fits, opening a new sheet when none does. Rectangles, not outlines: simple, predictable and
about 60-75 % dense for these near-round pieces; the frame, the largest part, goes first.

A large part (the puzzle's frame or a part of it) has the room its rectangle leaves free filled
as soon as it is placed (its holes, and the bays between its outline and its rectangle): the
parts not yet placed go there, in the same order, each at the lowest (then leftmost) free spot
on a ``HOLE_GRID`` mm grid, their rectangles kept ``spacing`` from the part and from each
other; only the parts no room takes go on to the skyline. So a sheet is used before the next
is started. A part in a hole must be cut before the hole's outline (its slug may shift once
it is free): ``Placement.room_of`` says which part's room holds each part.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from numpy.typing import NDArray

from ..errors import WeaveCutError
from ..numeric import cos_sin, snap

HOLE_GRID = 1.0  # mm: the grid parts are placed on inside a hole


def offset(parts: NDArray[np.object_], kerf: float) -> NDArray[np.object_]:
    """Every part grown by ``kerf / 2`` (holes shrunk), mitred corners."""
    if kerf <= 0:
        return parts
    return shapely.buffer(parts, kerf / 2.0, join_style="mitre", mitre_limit=8.0)


@dataclass(frozen=True)
class Placement:
    """Where a part went: sheet index, rotation (degrees, about the origin) then translation."""

    sheet: NDArray[np.int64]
    angle: NDArray[np.float64]
    shift: NDArray[np.float64]  # (N, 2)
    n_sheets: int
    room_of: NDArray[np.int64] | None = None  # (N,) the part whose room holds it, or -1

    def apply(self, parts: NDArray[np.object_]) -> NDArray[np.object_]:
        """The parts moved to their places on their sheets."""
        return moved(parts, self.angle, self.shift)


def moved(parts: NDArray[np.object_], angles: NDArray[np.float64], shifts: NDArray[np.float64]
          ) -> NDArray[np.object_]:
    """Every part turned by its angle (degrees, about the origin), then shifted: each part's
    ``affine`` matrix, all made at once and applied to all points at once as ``transform``
    applies one."""
    per = shapely.get_num_coordinates(parts)
    c, s = (np.repeat(v, per) for v in cos_sin(angles))
    tx, ty = (np.repeat(v, per) for v in np.asarray(shifts, dtype=float).reshape(-1, 2).T)

    def move(xy: NDArray) -> NDArray[np.float64]:
        x, y = xy[:, 0], xy[:, 1]
        return np.stack([c * x + -s * y + tx, s * x + c * y + ty], axis=-1)

    return shapely.transform(np.asarray(parts, dtype=object), move)


def upright_angles(parts: NDArray[np.object_]) -> NDArray[np.float64]:
    """(N,) rotation (degrees) that lays every part's minimum rectangle flat, long side on x."""
    rects = shapely.minimum_rotated_rectangle(parts)
    coords = shapely.get_coordinates(shapely.get_exterior_ring(rects)).reshape(len(parts), -1, 2)
    e1 = coords[:, 1] - coords[:, 0]
    e2 = coords[:, 2] - coords[:, 1]
    long = np.where((np.hypot(*e1.T) >= np.hypot(*e2.T))[:, None], e1, e2)
    angle = -np.degrees(np.arctan2(long[:, 1], long[:, 0]))
    return (angle + 90.0) % 180.0 - 90.0  # smallest turn that lays it flat


def nest(parts: NDArray[np.object_], sheet: tuple[float, float], spacing: float,
         margin: float = 5.0, rotate: NDArray[np.bool_] | None = None,
         names: list[str] | None = None, rooms: NDArray[np.bool_] | None = None) -> Placement:
    """Place ``parts`` on as few ``sheet`` (width, height) mm sheets as the packer finds.

    Parameters
    ----------
    parts : (N,) shapely polygons (already kerf-offset)
    spacing : mm between the bounding rectangles of two parts (>= kerf)
    margin : mm kept free along the sheet edges
    rotate : (N,) False for parts to keep unturned (default: all may turn)
    names : what to call each part in an error (default: "part 1", "part 2", ...)
    rooms : (N,) True for the parts whose free room (holes, bays) takes other parts (default:
        the parts with holes)
    """
    n = len(parts)
    angle = upright_angles(parts)
    if rotate is not None:
        angle = np.where(rotate, angle, 0.0)
    turned = moved(parts, angle, np.zeros((n, 2)))
    b = shapely.bounds(turned)
    w, h = b[:, 2] - b[:, 0] + spacing, b[:, 3] - b[:, 1] + spacing
    room_w, room_h = sheet[0] - 2 * margin + spacing, sheet[1] - 2 * margin + spacing
    too_big = (w > room_w + 1e-9) | (h > room_h + 1e-9)
    if too_big.any():
        k = int(np.flatnonzero(too_big)[0])
        name = names[k] if names is not None else f"part {k + 1}"
        raise WeaveCutError(
            f"{name} is {w[k] - spacing:.1f} x {h[k] - spacing:.1f} mm and does not fit a "
            f"{sheet[0]:g} x {sheet[1]:g} mm sheet with {margin:g} mm margins; use a larger "
            "--sheet or a smaller --size")
    order = np.lexsort((np.arange(n), -snap(w), -snap(h)))  # tallest first, then widest
    skylines: list[list[list[float]]] = []
    sheet_of = np.zeros(n, dtype=np.int64)
    shift = np.zeros((n, 2))
    room_of = np.full(n, -1, dtype=np.int64)
    if rooms is None:
        rooms = shapely.get_num_interior_rings(parts) > 0
    done = np.zeros(n, dtype=bool)
    for k in order.tolist():  # parts, a packing loop (no array form)
        if done[k]:
            continue
        for s, sky in enumerate(skylines):
            spot = _skyline_fit(sky, w[k], h[k], room_w, room_h)
            if spot is not None:
                break
        else:
            skylines.append([[0.0, 0.0, room_w]])  # segments: x, y, width
            s, spot = len(skylines) - 1, (0, 0.0, 0.0)
        i, x, y = spot
        _skyline_add(skylines[s], i, x, y, w[k], h[k])
        sheet_of[k], shift[k], done[k] = s, np.array([x, y]) + margin - b[k, :2], True
        if rooms[k]:  # a frame: fill the room it leaves now
            waiting = [j for j in order.tolist() if not done[j] and not rooms[j]]
            here = moved(turned[k:k + 1], np.zeros(1), shift[k:k + 1])[0]
            for j, corner in fill_room(here, b[waiting], spacing, waiting).items():
                sheet_of[j], shift[j], room_of[j], done[j] = s, corner - b[j, :2], k, True
    return Placement(sheet_of, angle, shift, len(skylines), room_of)


def room(part: shapely.Polygon) -> shapely.Geometry:
    """The room ``part`` leaves free in its bounding rectangle: its holes and its bays."""
    return shapely.difference(shapely.box(*part.bounds), part)


def fill_room(part: shapely.Polygon, bounds: NDArray[np.float64], spacing: float,
              ids: list[int], grid: float = HOLE_GRID) -> dict[int, NDArray[np.float64]]:
    """Where the parts with ``bounds`` (m, 4) go in the :func:`room` of ``part``, in the
    order given: {id: the lower-left corner of its bounding box}. Each goes to the lowest,
    then leftmost, spot of a ``grid`` mm grid where its box grown by ``spacing / 2`` on every
    side lies inside the room shrunk by ``spacing / 2`` and overlaps no box placed before; a
    part with no such spot stays out.

    The room is read as the grid cells wholly inside it (a cell's centre inside the room
    shrunk by a further half diagonal), the boxes as whole cells: integers decide, not float
    noise."""
    out: dict[int, NDArray[np.float64]] = {}
    inside = shapely.buffer(room(part), -(spacing / 2 + grid * 0.7072), join_style="mitre")
    if inside.is_empty or not len(ids):
        return out
    micro = snap((bounds[:, 2:] - bounds[:, :2] + spacing) / grid, 1e-6)
    size = -(-micro // 1_000_000)  # (m, 2) whole cells across and up
    x0, y0 = np.floor(np.asarray(part.bounds[:2]) / grid) * grid
    nx, ny = np.ceil((np.asarray(part.bounds[2:]) - (x0, y0)) / grid).astype(int)
    spots = _place(cells_inside(inside, x0 + (np.arange(nx) + 0.5) * grid,
                                y0 + (np.arange(ny) + 0.5) * grid), size.tolist())
    for a, spot in zip(ids, spots):
        if spot is not None:
            j, i = spot
            out[a] = np.array([x0 + i * grid, y0 + j * grid]) + spacing / 2
    return out


NEAR_EDGE = 1e-6  # mm: a cell centre this near an edge is looked up by shapely


def cells_inside(area: shapely.Geometry, xs: NDArray[np.float64], ys: NDArray[np.float64]
                 ) -> NDArray[np.bool_]:
    """(len(ys), len(xs)) which of the grid's points (x, y) lie inside ``area`` (a polygon
    or multipolygon), as ``shapely.contains_xy`` finds them: row by row, a point is inside
    where an odd number of the area's edges cross its row to its left. A point within
    ``NEAR_EDGE`` of a crossing, and every point of a row that passes within it of a corner,
    is left to ``contains_xy`` (the crossings are computed in floating point)."""
    rings = shapely.get_rings(shapely.get_parts(area))
    xy, ring = shapely.get_coordinates(rings, return_index=True)
    one = ring[:-1] == ring[1:]  # consecutive corners of one ring: an edge
    (px, py), (qx, qy) = xy[:-1][one].T, xy[1:][one].T
    low, high = np.minimum(py, qy), np.maximum(py, qy)
    # the rows each edge crosses: low <= y < high (a horizontal edge crosses none)
    first = np.searchsorted(ys, low, side="left")
    stop = np.searchsorted(ys, high, side="left")
    n = np.maximum(stop - first, 0)
    edge = np.repeat(np.arange(len(px)), n)
    row = np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n) + first[edge]
    y = ys[row]
    x = px[edge] + (y - py[edge]) * (qx[edge] - px[edge]) / (qy[edge] - py[edge])
    order = np.lexsort((x, row))
    row, x = row[order], x[order]
    starts = np.searchsorted(row, np.arange(len(ys) + 1))
    out = np.zeros((len(ys), len(xs)), dtype=bool)
    doubt = np.zeros((len(ys), len(xs)), dtype=bool)
    near_corner = np.zeros(len(ys), dtype=bool)
    if len(xy):
        at = np.searchsorted(ys, xy[:, 1])
        for k in (at - 1, at):
            ok = (k >= 0) & (k < len(ys))
            ok[ok] = np.abs(ys[k[ok]] - xy[ok, 1]) <= NEAR_EDGE
            near_corner[k[ok]] = True
    for r in range(len(ys)):  # rows: a few crossings each
        cross = x[starts[r]:starts[r + 1]]
        left = np.searchsorted(cross, xs)
        out[r] = left % 2 == 1
        if len(cross):
            gap = np.minimum(np.abs(xs - cross[np.maximum(left - 1, 0)]),
                             np.abs(xs - cross[np.minimum(left, len(cross) - 1)]))
            doubt[r] = gap <= NEAR_EDGE
    doubt[near_corner] = True
    if doubt.any():
        j, i = np.nonzero(doubt)
        out[j, i] = shapely.contains_xy(area, xs[i], ys[j])
    return out


def _place(inside: NDArray[np.bool_], sizes: list[list[int]]) -> list[tuple[int, int] | None]:
    """(row, column) of every window of ``sizes`` ((wx, wy) cells, 1 or more), in order, at
    the lowest, then leftmost, spot where all its cells are ``inside`` and none is taken by a
    window placed before; None where it has none."""
    free = _free_above(inside)
    # sizes with no spot (larger ones have none either), and (wx, wy, row) of the spots found;
    # each keeps only the entries no other one makes redundant (a smaller failed size; a
    # smaller size found no lower), so thousands of parts look through a few, not thousands
    failed: list[tuple[int, int]] = []
    found: list[tuple[int, int, int]] = []
    out: list[tuple[int, int] | None] = []
    for wx, wy in sizes:
        spot = None
        hopeless = any(wx >= fx and wy >= fy for fx, fy in failed)
        if not hopeless:
            # a window at least as large as one found before lies no lower than it did then
            low = max((row for fx, fy, row in found if wx >= fx and wy >= fy), default=0)
            spot = _lowest_free(free, wx, wy, low)
        out.append(spot)
        if spot is None:
            if not hopeless:
                failed = [(fx, fy) for fx, fy in failed if fx < wx or fy < wy] + [(wx, wy)]
            continue
        j, i = spot  # its cells are taken: the free runs below it now end at it
        free[j:j + wy, i:i + wx] = 0
        free[:j, i:i + wx] = np.minimum(free[:j, i:i + wx], np.arange(j, 0, -1)[:, None])
        if j > low or not any(wx >= fx and wy >= fy for fx, fy, _ in found):
            found = [(fx, fy, row) for fx, fy, row in found
                     if fx < wx or fy < wy or row > j] + [(wx, wy, j)]
    return out


def _free_above(inside: NDArray[np.bool_]) -> NDArray[np.int32]:
    """(rows, columns): how many cells from each up are inside (0 for a cell outside)."""
    out = np.zeros(inside.shape, dtype=np.int32)
    run = np.zeros(inside.shape[1], dtype=np.int32)
    for r in range(inside.shape[0] - 1, -1, -1):  # rows, top down: each needs the one above
        run = (run + 1) * inside[r]
        out[r] = run
    return out


ROWS = 32  # rows of windows looked at in one go


def _lowest_free(free: NDArray[np.int32], wx: int, wy: int, low: int = 0
                 ) -> tuple[int, int] | None:
    """(row, column) of the lowest, then leftmost, ``wy`` x ``wx`` window of cells that are
    all free, from row ``low`` on, or None; ``free`` (:func:`_free_above`) counts the free
    cells from each cell up, so a window is free where ``wx`` neighbours in a row all count
    ``wy`` or more. A few rows at a time: a window found low costs little."""
    ny, nx = free.shape
    if wx > nx or wy > ny:
        return None
    for top in range(low, ny - wy + 1, ROWS):
        run = free[top:min(top + ROWS, ny - wy + 1)] >= wy  # columns tall enough ...
        span = 1
        while span < wx:  # ... and then ``wx`` of them side by side (doubling the run)
            step = min(span, wx - span)
            run = run[:, :-step] & run[:, step:]
            span += step
        hit = np.flatnonzero(run)
        if len(hit):
            j, i = divmod(int(hit[0]), run.shape[1])
            return top + j, i
    return None


def _skyline_fit(sky, w, h, room_w, room_h):
    """Lowest (then leftmost) spot for a w x h rectangle on the skyline, or None."""
    best = None
    for i in range(len(sky)):
        x = sky[i][0]
        if x + w > room_w + 1e-9:
            break
        y, width, j = 0.0, 0.0, i
        while width < w - 1e-9 and j < len(sky):
            y = max(y, sky[j][1])
            width += sky[j][2]
            j += 1
        if y + h <= room_h + 1e-9 and (best is None or (y, x) < (best[2], best[1])):
            best = (i, x, y)
    return best


def _skyline_add(sky, i, x, y, w, h):
    """Raise the skyline over [x, x + w) to y + h."""
    new = [x, y + h, w]
    end = x + w
    j = i
    while j < len(sky) and sky[j][0] < end - 1e-9:
        seg_end = sky[j][0] + sky[j][2]
        if seg_end > end + 1e-9:  # keep the part of this segment beyond the new one
            sky[j] = [end, sky[j][1], seg_end - end]
            break
        j += 1
    del sky[i:j]
    sky.insert(i, new)
    # merge neighbours at equal height
    k = 0
    while k < len(sky) - 1:
        if abs(sky[k][1] - sky[k + 1][1]) < 1e-9:
            sky[k][2] += sky[k + 1][2]
            del sky[k + 1]
        else:
            k += 1
