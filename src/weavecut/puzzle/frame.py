"""Split a frame that is larger than the sheet into parts joined by dovetails.

The frame is cut along k straight rays from its centre, at equal angles (k = 2, 3, ... until
every part fits the sheet), starting through a side's midpoint (the shortest cut across the
band) or else through a corner. On every ray a dovetail tab, as large as the band of frame the
ray crosses allows (its inner edge is notched by the ring's hexagons), sticks out of one part
into the next. Parts are numbered F1, F2, ... counter-clockwise, so F1 joins F2. They come from
one partition of the plane (wedges that share their ray polylines), so they tile the frame
exactly.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from numpy.typing import NDArray

from ..errors import WeaveCutError
from ..layout.nesting import offset, upright_angles
from ..numeric import affine, transform

HEADS = np.array([0.56, 0.45, 0.36, 0.28])  # dovetail head widths tried, x the band's width
NECK, DEPTH = 0.6, 0.8  # neck width and depth, x the head width
PLACES = (0.5, 0.65, 0.8)  # where across the band (from its inner edge) the tab may sit
WALL = 0.05  # frame kept around a tab, x the band's width
MAX_PARTS = 12


def fits(parts: NDArray[np.object_], sheet: tuple[float, float], margin: float
         ) -> NDArray[np.bool_]:
    """(N,) True where a part, laid flat on its minimum rectangle, fits the sheet's room."""
    angles = upright_angles(parts)
    turned = [shapely.transform(p, transform(affine(a))) for p, a in zip(parts, angles)]
    b = shapely.bounds(np.array(turned, dtype=object))
    return ((b[:, 2] - b[:, 0] <= sheet[0] - 2 * margin + 1e-9)
            & (b[:, 3] - b[:, 1] <= sheet[1] - 2 * margin + 1e-9))


def split_frame(frame: shapely.Polygon, outer: shapely.Polygon, sheet: tuple[float, float],
                margin: float, kerf: float = 0.0) -> NDArray[np.object_]:
    """The frame itself when it fits ``sheet``, else the fewest dovetailed parts that do.

    Parameters
    ----------
    frame : the frame board (outer outline with the pieces' hole)
    outer : its outer outline (the rays start at its centroid)
    sheet : (width, height) mm; ``margin`` mm stays free along its edges
    kerf : parts are checked as they will be cut, grown by kerf / 2
    """
    whole = np.array([frame], dtype=object)
    if fits(offset(whole, kerf), sheet, margin).all():
        return whole
    centre = np.asarray(outer.centroid.coords[0])
    corners = np.asarray(outer.exterior.coords)[:-1]
    mids = (corners + np.roll(corners, -1, axis=0)) / 2
    starts = [float(np.arctan2(*(p - centre)[::-1])) for p in np.concatenate([mids, corners])]
    for k in range(2, MAX_PARTS + 1):
        for start in starts:
            parts = _parts(frame, centre, start + 2 * np.pi * np.arange(k) / k)
            if parts is not None and fits(offset(parts, kerf), sheet, margin).all():
                return parts
    raise WeaveCutError(f"even in {MAX_PARTS} parts the frame does not fit a {sheet[0]:g} x "
                        f"{sheet[1]:g} mm sheet; use a larger --sheet or a smaller --size")


def _parts(frame: shapely.Polygon, centre, angles) -> NDArray[np.object_] | None:
    """The frame cut along rays at ``angles`` (ascending), or None where a dovetail does not
    fit in the band or a part falls apart."""
    reach = 4.0 * float(np.max(np.linalg.norm(np.asarray(frame.exterior.coords) - centre,
                                              axis=1)))
    rays = [_ray(frame, centre, a, reach) for a in angles]
    if any(r is None for r in rays):
        return None
    k = len(angles)
    out = []
    for j in range(k):  # a handful of parts
        a0, a1 = angles[j], angles[(j + 1) % k] + (2 * np.pi if j == k - 1 else 0.0)
        arc = np.linspace(a0, a1, 33)[1:-1]
        rim = centre + reach * np.column_stack([np.cos(arc), np.sin(arc)])
        wedge = shapely.Polygon(np.concatenate([rays[j], rim, rays[(j + 1) % k][::-1]]))
        part = shapely.intersection(frame, wedge)
        if part.geom_type != "Polygon" or not wedge.is_valid:
            return None
        out.append(shapely.normalize(part))
    return np.array(out, dtype=object)


def _ray(frame: shapely.Polygon, centre, angle: float, reach: float
         ) -> NDArray[np.float64] | None:
    """The cut line from ``centre`` outward at ``angle`` with a dovetail tab in the outermost
    band of frame it crosses: the largest that stays inside the frame, towards the next part
    where it fits, else towards the one before (None when none fits)."""
    u = np.array([np.cos(angle), np.sin(angle)])
    n = np.array([-u[1], u[0]])
    line = shapely.LineString([centre, centre + reach * u])
    inside = shapely.get_parts(shapely.intersection(line, frame))
    inside = [g for g in inside if g.geom_type == "LineString" and g.length > 0]
    if not inside:
        return None
    band = max(inside, key=lambda g: math.hypot(*(np.asarray(g.coords).mean(axis=0) - centre)))
    ends = np.linalg.norm(np.asarray(band.coords) - centre, axis=1)
    r_in, r_out = float(ends.min()), float(ends.max())
    width = r_out - r_in

    def at(r, side=0.0):
        return centre + r * u + side * n

    solid = shapely.buffer(frame, -WALL * width)
    for head in HEADS * width:  # the largest dovetail that stays inside the frame
        for where in PLACES:
            for side in (1.0, -1.0):
                mid = r_in + where * width
                neck, depth = NECK * head, DEPTH * head * side
                tab = np.array([at(mid - neck / 2), at(mid - head / 2, depth),
                                at(mid + head / 2, depth), at(mid + neck / 2)])
                if solid.contains(shapely.Polygon(tab)):
                    return np.concatenate([[centre], tab, [centre + reach * u]])
    return None
