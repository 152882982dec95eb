"""Tessellations of an outline's inside, one per mesh kind, for ``outline_mesh``.

Kinds (``cell`` is the side of a square of the faces' target area):

- ``quad`` and ``hex``: the Voronoi cells of a square or triangular lattice (squares and
  regular hexagons), Lloyd-relaxed 15 times (every seed moved to the centroid of its cell
  clipped to the outline): inner cells stay regular, the boundary cells grow to about full
  size instead of leaving slivers.
- ``voronoi``: a centroidal Voronoi tessellation (Du, Faber and Gunzburger, "Centroidal Voronoi
  tessellations", SIAM Review 41, 1999): random seeds, Lloyd-relaxed 40 times, clipped.
- ``tri``: a conforming Delaunay triangulation (scipy) of the relaxed seeds of ``hex`` (at the
  triangles' spacing) and points along the outline; a boundary segment missing from the
  triangulation is split at its middle until every one is an edge (the segment splitting of
  Ruppert's algorithm), and the inner points are Laplace-smoothed.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from scipy.spatial import Delaunay

from ..errors import MeshError
from ..mesh import Mesh

# lattice spacing (times cell) that gives faces of area cell**2
SPACING = {"quad": 1.0, "hex": math.sqrt(2 / math.sqrt(3)), "tri": math.sqrt(4 / math.sqrt(3))}


def _lattice(kind: str, region, spacing: float) -> np.ndarray:
    """(N, 2) lattice points (square or triangular) inside ``region``."""
    x0, y0, x1, y1 = region.bounds
    if kind == "quad":
        a, b = np.array([spacing, 0.0]), np.array([0.0, spacing])
    else:
        a, b = np.array([spacing, 0.0]), spacing * np.array([0.5, math.sqrt(3) / 2])
    # rows over the bounding box, each as wide as the box (a triangular row shifts by half)
    rows = np.arange(-1, math.ceil((y1 - y0) / b[1]) + 2)
    width = math.ceil((x1 - x0) / spacing) + 5
    i = (np.floor(-rows * b[0] / spacing).astype(np.int64)[:, None] - 2
         + np.arange(width)).reshape(-1)
    j = np.repeat(rows, width)
    # the lower left corner of the bounding box is a cell corner (a box fits whole cells)
    points = i.reshape(-1, 1) * a + j.reshape(-1, 1) * b + (a + b) / 2 + (x0, y0)
    return points[shapely.contains_xy(region, *points.T)]


def _relaxed_cells(region, kind: str, cell: float) -> tuple[np.ndarray, np.ndarray]:
    """(N, 2) relaxed seeds and their Voronoi cells clipped to ``region`` (a shapely array)."""
    if kind == "voronoi":
        rng = np.random.default_rng(0)
        x0, y0, x1, y1 = region.bounds
        n = max(3, round((x1 - x0) * (y1 - y0) / cell ** 2))
        seeds = rng.uniform((x0, y0), (x1, y1), size=(n, 2))
        seeds = seeds[shapely.contains_xy(region, *seeds.T)]
        rounds = 40
    else:
        seeds = _lattice(kind, region, SPACING[kind] * cell)
        rounds = 15
    if len(seeds) < 2:
        return seeds, np.array([region])
    for _ in range(rounds):
        cells = shapely.intersection(_voronoi_cells(seeds), region)
        keep = ~shapely.is_empty(cells)
        seeds = shapely.get_coordinates(shapely.centroid(cells[keep]))
    return seeds, shapely.intersection(_voronoi_cells(seeds), region)


def _voronoi_cells(seeds: np.ndarray) -> np.ndarray:
    """(N,) convex Voronoi cell of every seed (bounded by a far ring of extra points).

    A cell is the convex hull of the circumcentres of the Delaunay triangles around its seed,
    which stays valid where GEOS's Voronoi diagram fails on co-circular seeds (a lattice).
    """
    centre = seeds.mean(axis=0)
    reach = 10 * (np.ptp(seeds, axis=0).max() + 1.0)
    angles = np.linspace(0, 2 * np.pi, 32, endpoint=False)
    points = np.vstack([seeds, centre + reach * np.column_stack([np.cos(angles), np.sin(angles)])])
    triangles = Delaunay(points).simplices
    a, b, c = (points[triangles[:, k]] for k in range(3))
    d = 2 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    bb, cc = ((b - a) ** 2).sum(axis=1), ((c - a) ** 2).sum(axis=1)
    offsets = np.column_stack([(c[:, 1] - a[:, 1]) * bb - (b[:, 1] - a[:, 1]) * cc,
                               (b[:, 0] - a[:, 0]) * cc - (c[:, 0] - a[:, 0]) * bb])
    centres = a + offsets / d[:, None]
    owner = triangles.reshape(-1)
    order = np.argsort(owner, kind="stable")
    corners = np.repeat(np.arange(len(triangles)), 3)[order]
    hulls = shapely.multipoints(centres[corners], indices=owner[order])
    return shapely.convex_hull(hulls)[: len(seeds)]


def _triangles(region, cell: float) -> Mesh:
    """A conforming, smoothed Delaunay triangulation of ``region`` with sides near SPACING."""
    side = SPACING["tri"] * cell
    rings = [np.asarray(r.coords)[:-1] for p in shapely.get_parts(region)
             for r in (p.exterior, *p.interiors)]
    rings = [_densified(r, side) for r in rings]
    inner, _ = _relaxed_cells(region, "hex", cell * SPACING["tri"] / SPACING["hex"])
    inner = inner[shapely.distance(region.boundary, shapely.points(inner)) > 0.35 * side]
    for smoothing in (True, False):
        rings, triangles = _conforming(region, rings, inner)
        if not smoothing:
            break
        inner = _smoothed(np.concatenate([*rings, inner]), triangles, len(inner))
    points = np.concatenate([*rings, inner])
    used, faces = np.unique(triangles, return_inverse=True)
    return Mesh(points[used], np.arange(0, 3 * len(triangles) + 1, 3), faces.reshape(-1))


def _densified(ring: np.ndarray, side: float) -> np.ndarray:
    """``ring`` with every edge longer than ``side`` cut into equal parts no longer than it."""
    edges = np.roll(ring, -1, axis=0) - ring
    parts = np.maximum(1, np.ceil(np.hypot(*edges.T) / side)).astype(int)
    start = np.repeat(ring, parts, axis=0)
    step = np.repeat(edges / parts[:, None], parts, axis=0)
    k = np.arange(parts.sum()) - np.repeat(np.cumsum(parts) - parts, parts)
    return start + k[:, None] * step


def _conforming(region, rings, inner):
    """Delaunay triangles inside ``region``, splitting boundary segments until all are edges."""
    for _ in range(30):
        points = np.concatenate([*rings, inner])
        simplices = Delaunay(points).simplices
        p = points[simplices]
        area = ((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                - (p[:, 1, 1] - p[:, 0, 1]) * (p[:, 2, 0] - p[:, 0, 0]))
        # Qhull's triangulated output can hold flat triangles along a straight run of outline
        # points, whose centre rounding may put inside: no faces (real ones are about a cell,
        # and mesh_outline refuses cells under 1e-6 of the region)
        solid = np.abs(area) > 1e-9 * region.area
        keep = shapely.contains_xy(region, *p.mean(axis=1).T) & solid
        triangles, area = simplices[keep], area[keep]
        edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]],
                                        triangles[:, [2, 0]]]), axis=1)
        keys = set((edges[:, 0] * len(points) + edges[:, 1]).tolist())
        start, missing = 0, []
        for r in rings:
            a = start + np.arange(len(r))
            b = start + (np.arange(len(r)) + 1) % len(r)
            seg = np.sort(np.column_stack([a, b]), axis=1)
            missing.append(~np.isin(seg[:, 0] * len(points) + seg[:, 1], list(keys)))
            start += len(r)
        if not any(m.any() for m in missing):
            triangles[area < 0] = triangles[area < 0][:, [0, 2, 1]]
            return rings, triangles
        rings = [_with_midpoints(r, m) for r, m in zip(rings, missing)]
    raise MeshError("could not triangulate the outline so that it follows every boundary "
                    "segment; try a smaller --cell")


def _with_midpoints(ring: np.ndarray, split: np.ndarray) -> np.ndarray:
    middles = (ring + np.roll(ring, -1, axis=0)) / 2
    both = np.stack([ring, middles], axis=1).reshape(-1, 2)
    keep = np.stack([np.ones(len(ring), bool), split], axis=1).reshape(-1)
    return both[keep]


def _smoothed(points: np.ndarray, triangles: np.ndarray, n_inner: int, rounds: int = 5):
    """The last ``n_inner`` points, each moved (5 times) to the mean of its neighbours."""
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    edges = np.unique(np.sort(edges, axis=1), axis=0)
    edges = np.concatenate([edges, edges[:, ::-1]])
    n = len(points)
    count = np.bincount(edges[:, 0], minlength=n)
    moving = np.arange(n - n_inner, n)
    points = points.copy()
    for _ in range(rounds):
        mean = np.column_stack([np.bincount(edges[:, 0], weights=points[edges[:, 1], k],
                                            minlength=n) for k in (0, 1)])
        points[moving] = mean[moving] / np.maximum(count[moving], 1)[:, None]
    return points[moving]
