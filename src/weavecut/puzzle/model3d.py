"""The finished puzzle in 3-D: every piece a slab of the material's thickness in its frame,
painted on the front (the top, z = thickness) and the back (z = 0) as the painting guides
say, bare wood on its cut edges, on the frame and wherever the guides leave unpainted.

Lengths in mm, z up; one part per paint and side (``front: green 3``), one for the bare wood.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..weave.woven import Model
from .colouring import Colouring
from .guides import painted
from .pieces import Puzzle

WOOD = "#d8bd8f"  # light plywood


def _flat(polygons, z: float, up: bool):
    """(vertices, triangles) of ``polygons`` triangulated (holes kept) at height ``z``,
    counter-clockwise seen from above when ``up`` else from below."""
    triangles = shapely.get_parts(shapely.constrained_delaunay_triangles(
        shapely.GeometryCollection(list(polygons))))
    coords = shapely.get_coordinates(shapely.get_exterior_ring(triangles)).reshape(-1, 4, 2)[:, :3]
    ccw = (coords[:, 1, 0] - coords[:, 0, 0]) * (coords[:, 2, 1] - coords[:, 0, 1]) - \
        (coords[:, 1, 1] - coords[:, 0, 1]) * (coords[:, 2, 0] - coords[:, 0, 0]) > 0
    coords = np.where((ccw == up)[:, None, None], coords, coords[:, ::-1])
    vertices = np.column_stack([coords.reshape(-1, 2), np.full(len(coords) * 3, z)])
    return vertices, np.arange(len(vertices)).reshape(-1, 3)


def _walls(polygons, thickness: float):
    """(vertices, triangles, normals) of the cut edges of ``polygons``, facing out."""
    # outlines counter-clockwise, holes clockwise: the material is on the left of every edge
    rings = shapely.get_rings(shapely.orient_polygons(np.asarray(polygons, dtype=object)))
    coords, ring = shapely.get_coordinates(rings, return_index=True)
    last = np.r_[ring[1:] != ring[:-1], True]
    p, q = coords[~last], coords[1:][~last[:-1]]
    d = q - p
    n = len(p)
    zero, top = np.zeros(n), np.full(n, thickness)
    corners = np.stack([np.column_stack([p, zero]), np.column_stack([q, zero]),
                        np.column_stack([q, top]), np.column_stack([p, top])], axis=1)
    normal = np.column_stack([d[:, 1], -d[:, 0], zero])
    normal /= np.sqrt((normal * normal).sum(axis=1))[:, None]
    base = 4 * np.arange(n)[:, None]
    triangles = np.concatenate([base + [0, 1, 2], base + [0, 2, 3]])
    return corners.reshape(-1, 3), triangles, np.repeat(normal, 4, axis=0)


def painted_union(polygons) -> shapely.Geometry:
    """The union of a side's painted polygons. They meet edge to edge (the pieces share their
    corners, the halves their chords: a coverage), whose union GEOS makes from the edges used
    once, twenty times faster than ``union_all``; that union is invalid where they do not (an
    overlap, a corner on one side of an edge only), and ``union_all`` makes it then."""
    union = shapely.coverage_union_all(polygons)
    return union if shapely.is_valid(union) else shapely.union_all(polygons)


def puzzle_model(puzzle: Puzzle, colouring: Colouring, thickness: float) -> Model:
    """The puzzle in its frame, pieces and frame ``thickness`` mm thick."""
    parts = []  # (name, colour, vertices, triangles, normals)
    front, back = painted(puzzle, colouring, "front"), painted(puzzle, colouring, "back")
    for side, paint, z, up in (("front", front, thickness, True), ("back", back, 0.0, False)):
        for colour in dict.fromkeys(paint.colours.tolist()):
            v, t = _flat(paint.polygons[paint.colours == colour], z, up)
            name = colouring.names.get(colour, colour)
            parts.append((f"{side}: {name}", colour, v, t, np.tile([0.0, 0.0, 1.0 if up else
                                                                     -1.0], (len(v), 1))))
    wood = []
    for paint, z, up in ((front, thickness, True), (back, 0.0, False)):
        bare = shapely.difference(shapely.Polygon(puzzle.outer.exterior),
                                  painted_union(paint.polygons))
        v, t = _flat(shapely.get_parts(bare), z, up)
        wood.append((v, t, np.tile([0.0, 0.0, 1.0 if up else -1.0], (len(v), 1))))
    wood.append(_walls(np.concatenate([puzzle.pieces, [puzzle.frame]]), thickness))
    offsets = np.cumsum([0] + [len(v) for v, _, _ in wood])
    parts.append(("bare wood", WOOD, np.concatenate([v for v, _, _ in wood]),
                  np.concatenate([t + o for (_, t, _), o in zip(wood, offsets)]),
                  np.concatenate([n for _, _, n in wood])))
    offsets = np.cumsum([0] + [len(p[2]) for p in parts])
    return Model(np.concatenate([p[2] for p in parts]), np.concatenate([p[4] for p in parts]),
                 np.concatenate([p[3] + o for p, o in zip(parts, offsets)]).astype(np.int64),
                 np.repeat(np.arange(len(parts)), [len(p[3]) for p in parts]),
                 tuple(p[1] for p in parts), tuple(p[0] for p in parts))
