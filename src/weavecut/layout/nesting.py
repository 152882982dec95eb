"""Kerf compensation and nesting of separately cut parts onto sheets.

Kerf: a part is cut along its outline offset outward by kerf/2 (a hole inward by kerf/2), with
mitred corners, so that after the beam removes kerf/2 on either side of the cut line the part
has its design size. ``kerf = 0`` leaves compensation to the laser software.

Nesting: every part is turned to its minimum-area bounding rectangle and laid flat (long side
along x), then the rectangles, inflated by the spacing, are placed tallest first with a skyline
bottom-left packer (each goes where its bottom is lowest, then leftmost) on the first sheet where
it fits, opening a new sheet when none does. Rectangles, not outlines: simple, predictable and
about 60-75 % dense for these near-round pieces; the frame, the largest part, goes first.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from numpy.typing import NDArray

from ..errors import WeaveCutError
from ..numeric import affine, snap


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

    def apply(self, parts: NDArray[np.object_]) -> NDArray[np.object_]:
        """The parts moved to their places on their sheets."""
        return moved(parts, self.angle, self.shift)


def moved(parts: NDArray[np.object_], angles: NDArray[np.float64], shifts: NDArray[np.float64]
          ) -> NDArray[np.object_]:
    """Every part turned by its angle (degrees, about the origin), then shifted: one affine
    matrix per part, applied to all points at once as ``transform`` applies one."""
    m = np.array([affine(a, t) for a, t in zip(angles, shifts)]).reshape(-1, 3, 3)
    m = m[np.repeat(np.arange(len(parts)), shapely.get_num_coordinates(parts))]

    def move(xy: NDArray) -> NDArray[np.float64]:
        x, y = xy[:, 0], xy[:, 1]
        return np.stack([m[:, 0, 0] * x + m[:, 0, 1] * y + m[:, 0, 2],
                         m[:, 1, 0] * x + m[:, 1, 1] * y + m[:, 1, 2]], axis=-1)

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
         names: list[str] | None = None) -> Placement:
    """Place ``parts`` on as few ``sheet`` (width, height) mm sheets as the packer finds.

    Parameters
    ----------
    parts : (N,) shapely polygons (already kerf-offset)
    spacing : mm between the bounding rectangles of two parts (>= kerf)
    margin : mm kept free along the sheet edges
    rotate : (N,) False for parts to keep unturned (default: all may turn)
    names : what to call each part in an error (default: "part 1", "part 2", ...)
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
    pos = np.zeros((n, 2))
    for k in order.tolist():  # parts, a packing loop (no array form)
        for s, sky in enumerate(skylines):
            spot = _skyline_fit(sky, w[k], h[k], room_w, room_h)
            if spot is not None:
                break
        else:
            skylines.append([[0.0, 0.0, room_w]])  # segments: x, y, width
            s, spot = len(skylines) - 1, (0, 0.0, 0.0)
        i, x, y = spot
        _skyline_add(skylines[s], i, x, y, w[k], h[k])
        sheet_of[k], pos[k] = s, (x, y)
    shift = pos + margin - b[:, :2]
    return Placement(sheet_of, angle, shift, len(skylines))


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
