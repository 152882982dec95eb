"""Cells fitted to an outline: cut at its reflex corners into convex pieces, the small pieces
merged into a neighbour or cut anew with their neighbours (``outline_mesh`` uses both)."""

from __future__ import annotations

import math
from itertools import combinations

import numpy as np
import shapely
from shapely.ops import split

from ..errors import MeshError

GENTLE = math.sin(math.radians(15))  # reflex turns below 15 degrees are bends of the outline
MIN_SIZE = 0.6  # smaller pieces (times cell) merge into a neighbour


def convex_pieces(polygon, tolerance: float) -> list:
    """``polygon`` cut at its reflex corners until every piece is convex.

    A reflex bend under 15 degrees less than ``tolerance`` deep (a gentle S-bend) is dropped
    instead, which moves the boundary by less than the tolerance. At a real reflex corner r the
    cut runs to another corner of the cell or along one of 9 rays spread over the corner's
    angle: of the cuts that leave both pieces convex at r, the one whose smaller piece is
    largest.
    """
    if polygon.is_empty or polygon.area == 0:
        return []
    if polygon.interiors:  # a hole inside one cell: cut across the middle of the hole first
        hx0, _, hx1, _ = shapely.Polygon(polygon.interiors[0]).bounds
        _, y0, _, y1 = polygon.bounds
        x = (hx0 + hx1) / 2  # strictly inside the hole's span: the line crosses the hole
        halves = shapely.get_parts(split(polygon, shapely.LineString([(x, y0), (x, y1)])))
        return [q for p in halves for q in convex_pieces(p, tolerance)]
    ring = np.asarray(shapely.orient_polygons(polygon).exterior.coords)[:-1]
    before, after = ring - np.roll(ring, 1, axis=0), np.roll(ring, -1, axis=0) - ring
    turn = before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0]
    lengths = np.hypot(*before.T) * np.hypot(*after.T)
    reflex = np.flatnonzero(turn < -1e-6 * lengths)  # turning back by more than 1e-6 rad
    if len(reflex) == 0:
        return [polygon]
    depth = -turn[reflex] / np.hypot(*(before + after)[reflex].T)
    depth[-turn[reflex] > GENTLE * lengths[reflex]] = np.inf  # a corner, not a bend
    if depth.min() <= tolerance:
        return convex_pieces(shapely.Polygon(np.delete(ring, reflex[np.argmin(depth)], axis=0)),
                              tolerance)
    k = reflex[0]
    # cut to another corner, or along one of 9 rays spread over the reflex angle
    a0 = math.atan2(after[k, 1], after[k, 0])
    a1 = math.atan2(-before[k, 1], -before[k, 0])
    fan = a0 + np.linspace(0.1, 0.9, 9) * np.mod(a1 - a0, 2 * np.pi)
    rays = ring[k] + 4 * polygon.length * np.column_stack([np.cos(fan), np.sin(fan)])
    ends = np.vstack([np.delete(ring, [k - 1, k, (k + 1) % len(ring)], axis=0), rays])
    d = ends - ring[k]
    in_cone = ((after[k, 0] * d[:, 1] - after[k, 1] * d[:, 0] >= 0)
               & (before[k, 0] * d[:, 1] - before[k, 1] * d[:, 0] >= 0))
    best, best_area = None, 0.0
    for end in ends[in_cone]:
        parts = shapely.get_parts(split(polygon, shapely.LineString([ring[k], end])))
        smaller = shapely.area(parts).min() if len(parts) > 1 else 0.0
        if smaller > best_area:
            best, best_area = parts, smaller
    if best is None:
        raise MeshError("could not cut a cell at a reflex corner of the outline; try "
                        "another --cell")
    return [q for p in best for q in convex_pieces(p, tolerance)]


def merged_small(pieces: list, cell: float) -> list:
    """Pieces smaller than MIN_SIZE * cell (side of the square of equal area), smallest first,
    merged into the neighbour with the longest shared edge whose union stays convex, or else
    cut anew (``_recut``) together with one neighbour, or with the two it shares most with,
    where that leaves two or more pieces whose smallest is over 1.2 times the small one's
    area; failing those, together with any two or three neighbours along an edge (a sliver
    between two cuts, or between a cut and the outline, needs the pieces on both sides). A
    recut leaves as many pieces as neighbours or more (only a single neighbour, whose union
    with the small piece is convex, takes it whole), so a face never swallows two."""
    pieces = list(pieces)
    hopeless = set()  # a piece with the same neighbours as when nothing helped it
    while True:
        areas = shapely.area(pieces)
        for i in np.argsort(areas, kind="stable"):
            if areas[i] >= (MIN_SIZE * cell) ** 2:
                return pieces
            neighbours = shapely.STRtree(pieces).query(pieces[i], predicate="intersects")
            neighbours = neighbours[neighbours != i]
            key = (pieces[i].wkb, *sorted(shapely.to_wkb(np.take(pieces, neighbours))))
            if key in hopeless:
                continue
            unions = shapely.union(pieces[i], np.take(pieces, neighbours))
            shared = shapely.length(shapely.intersection(
                pieces[i].boundary, shapely.boundary(np.take(pieces, neighbours))))
            convex = ((shapely.area(shapely.convex_hull(unions)) - shapely.area(unions)
                       <= 1e-9 * shapely.area(unions)) & (shapely.get_type_id(unions) == 3))
            if (shared * convex).max(initial=0) > 0:
                k = int(np.argmax(shared * convex))
                pieces[neighbours[k]] = unions[k]
                del pieces[i]
                break
            # else cut the piece anew with one neighbour, or with the two it shares most with;
            # failing those, with any two or three of its neighbours along an edge (to within
            # rounding: a T-junction's edges are not exactly collinear)
            near = shapely.length(shapely.intersection(shapely.boundary(np.take(
                pieces, neighbours)), shapely.buffer(pieces[i].boundary, 1e-6 * cell)))
            touching = [int(j) for j in neighbours[near > 1e-3 * cell]]
            tries = ([[j] for j in neighbours[shared > 0]]
                     + [list(neighbours[np.argsort(-shared)[:2]])],
                     [list(g) for k in (2, 3) for g in combinations(touching, k)])
            for groups in tries:
                recuts = [_recut([pieces[n] for n in (i, *g)]) for g in groups]
                gains = [shapely.area(r).min() if len(r) else 0.0 for r in recuts]
                if max(gains, default=0.0) > 1.2 * areas[i]:
                    k = int(np.argmax(gains))
                    pieces = [p for n, p in enumerate(pieces) if n not in (i, *groups[k])]
                    pieces += recuts[k]
                    break
            else:
                hopeless.add(key)
                continue  # nothing helped this piece: the next smallest
            break
        else:
            return pieces


def _recut(pieces: list) -> list:
    """``pieces`` (a small one and its neighbours) joined and cut anew into convex pieces, as
    many as its neighbours or more (and two or more); else no pieces.

    No bend of the union is dropped (``convex_pieces`` with no tolerance): the pieces already
    follow the outline to the tolerance, and a bend dropped on an edge shared with a piece
    outside the group would overlap that piece. Pieces meet at T-junctions whose edges are
    collinear only to within rounding, so the union may hold cracks or spikes of no width and
    holes of no area; these are dropped."""
    together = shapely.union_all(pieces)
    if together.geom_type != "Polygon":
        return []
    small = 1e-9 * together.area
    holes = [h for h in together.interiors if shapely.Polygon(h).area > small]
    together = shapely.Polygon(_without_spikes(np.asarray(together.exterior.coords)[:-1]),
                               holes)
    if not together.is_valid:
        return []
    try:
        parts = convex_pieces(together, 0.0)
    except MeshError:  # no cut at a reflex corner: this group cannot be cut anew
        return []
    return parts if len(parts) >= max(2, len(pieces) - 1) else []


def _without_spikes(ring: np.ndarray) -> np.ndarray:
    """``ring`` without the corners where it turns back on itself (by 180 degrees to within
    1e-6 rad): the tips of spikes and cracks of no width."""
    while len(ring) > 3:
        before, after = ring - np.roll(ring, 1, axis=0), np.roll(ring, -1, axis=0) - ring
        cross = before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0]
        back = (((before * after).sum(axis=1) < 0)
                & (np.abs(cross) <= 1e-6 * np.hypot(*before.T) * np.hypot(*after.T)))
        if not back.any():
            break
        ring = ring[~back]
    return ring
