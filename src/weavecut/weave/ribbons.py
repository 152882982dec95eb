"""A woven model in space: every strand of a weave on a surface as a ribbon of triangles.

A strand's centre line runs through the centres of the tiles it visits and, between two
visits, the midpoint of their centres (where it crosses from one tile to the next). At a
visit the line is lifted along the tile's normal by ``lift`` where the strand is on top and
lowered by ``lift`` where it passes under, so the two strands of every octagon pass each other
``2 lift`` apart; at the midpoints it is on the surface. The ribbon is ``width`` wide, across
the centre line in the surface's tangent plane. Loops close; open strands (a surface with
boundary) end at their last visit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..surface import vector_areas
from .model import Weave


@dataclass(frozen=True)
class Ribbons:
    """Triangles of all strands' ribbons.

    Parameters
    ----------
    vertices : (N, 3) float64
    triangles : (M, 3) int64, counter-clockwise seen from outside the surface
    strand : (M,) int64, strand of every triangle
    """

    vertices: NDArray[np.float64]
    triangles: NDArray[np.int64]
    strand: NDArray[np.int64]


def _unit(v: NDArray[np.float64]) -> NDArray[np.float64]:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def tile_normals(weave: Weave) -> NDArray[np.float64]:
    """(T, 3) unit normal of every tile (its faces' vector areas added)."""
    areas = vector_areas(weave.mesh)[weave.tile_faces]
    return _unit(np.add.reduceat(areas, weave.tile_offsets[:-1], axis=0))


def mean_step(weave: Weave) -> float:
    """Mean distance between the centres of consecutive tiles along the strands."""
    lengths, visits = weave.strand_lengths(), len(weave.strand_visits)
    return float(lengths.sum() / max(visits - int((~weave.strand_closed).sum()), 1))


def ribbons(weave: Weave, width: float, lift: float) -> Ribbons:
    """The ribbons of every strand of ``weave`` (a weave on a surface in space)."""
    if weave.mesh.dim != 3:
        raise ValueError("ribbons need a weave on a surface in space")
    centres, normals = weave.tile_centres, tile_normals(weave)
    visits, over = weave.strand_visits, weave.visit_over
    n = len(visits)
    start = np.repeat(weave.strand_offsets[:-1], np.diff(weave.strand_offsets))
    end = np.repeat(weave.strand_offsets[1:], np.diff(weave.strand_offsets))
    closed = weave.strand_closed[weave.visit_strand]
    nxt = np.where(np.arange(n) + 1 < end, np.arange(n) + 1, start)  # the next visit (a loop)
    # centre line: visit k at 2k, the crossing to the next visit at 2k + 1
    point = np.empty((2 * n, 3))
    normal = np.empty((2 * n, 3))
    normal[0::2] = normals[visits]
    point[0::2] = centres[visits] + np.where(over, lift, -lift)[:, None] * normal[0::2]
    point[1::2] = 0.5 * (centres[visits] + centres[visits[nxt]])
    normal[1::2] = _unit(normals[visits] + normals[visits[nxt]])
    # the point before and after every centre-line point, along its own strand
    index = np.arange(2 * n)
    first, stop = 2 * np.repeat(start, 2), 2 * np.repeat(end, 2)
    last_kept = np.where(np.repeat(closed, 2), stop - 1, stop - 2)  # open: no crossing after
    after = np.where(index + 1 <= last_kept, index + 1, np.where(np.repeat(closed, 2), first,
                                                                 index))
    before = np.where(index > first, index - 1, np.where(np.repeat(closed, 2), last_kept, index))
    side = _unit(np.cross(normal, point[after] - point[before])) * (width / 2)
    vertices = np.stack([point + side, point - side], axis=1).reshape(-1, 3)  # left, right
    keep = index <= last_kept
    a, b = index[keep], after[keep]
    ring = a != b
    a, b = a[ring], b[ring]
    left_a, right_a, left_b, right_b = 2 * a, 2 * a + 1, 2 * b, 2 * b + 1
    triangles = np.concatenate([np.column_stack([right_a, right_b, left_b]),
                                np.column_stack([right_a, left_b, left_a])])
    strand = np.tile(weave.visit_strand[a // 2].astype(np.int64), 2)
    return Ribbons(vertices, triangles.astype(np.int64), strand)
