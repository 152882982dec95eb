"""The level image (paper Figure colorLevels): every pixel coloured by the first refinement step
in which it contains a vertex, and the windowed refinement that makes deep zooms affordable.

Windowed refinement refines only the faces that can influence the window, and is *exact*
there: every vertex of level t inside the window has the same coordinates, bit for bit, as in
the full refinement. Why that holds, and how it is checked:

- The children of a face f before smoothing depend only on f's vertices. Smoothing moves a
  child vertex to the mean centre of its child faces, and those lie in the parent faces around
  the parent element it came from (an old vertex's faces, the two faces of an edge, or f).
  So a child vertex is exact when its whole star was refined from exact vertices.
- Every vertex carries three flags: ``exact`` (its position equals the full one), ``complete``
  (all faces around it in the full mesh are present) and ``outer`` (1 yes, 0 no, -1 unknown:
  smoothing keeps outer vertices still). The flags are propagated through each step with array
  operations, conservatively: anything that cannot be decided is marked inexact.
- After each step, child faces farther than a halo from the window are dropped. The halo is
  ``HALO`` times the largest face of the level: smoothing moves a vertex by less than one face
  per step, and faces shrink by about 1/sqrt(5) per step, so what a dropped face could still
  influence stays within a few of its own diameters; each level also loses one ring of exact
  faces at the cut, which the halo covers as well.
- The submesh keeps the full mesh's relative order of vertices, faces and corners, and the snub
  step's sums depend only on that order and on the local structure, so the step on the patch
  adds the same numbers in the same order: the results are equal, not just close. (The step
  sees the patch's cut as boundary and keeps vertices on it still; they are the vertices whose
  star is incomplete, already marked inexact.) :func:`refine_window` raises if any kept vertex inside the window is not
  exact, or any vertex inside it is missing part of its star.
"""

from __future__ import annotations

import io
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import WeaveCutError
from ..fileio import write_atomic
from ..mesh import Mesh, Topology, outer_vertices
from ..mesh_geometry import signed_areas
from ..subdivision import snub
from ..subdivision.hierarchy import BASE_BYTES, require, sizes

UNSET = 255
HALO = 3.0
# levels 0-9 darken-to-bright (the "inferno" ramp), 10-12 turning green, later levels darker green
LEVEL_COLOURS = np.array([
    (0, 0, 4), (22, 11, 57), (66, 10, 104), (106, 23, 110), (147, 38, 103),
    (188, 55, 84), (221, 81, 58), (243, 120, 25), (252, 165, 10), (252, 255, 164),
    (200, 240, 120), (120, 210, 80), (40, 170, 60),
], dtype=np.uint8)
DEEPER = (20, 120, 40)
BACKGROUND = (255, 255, 255)
# the memory guard's model (fitted to measured peak RSS, benchmarks/bench_memory.py)
IMAGE_BYTES_PER_PIXEL = 8      # the level image, its colours, the PNG encoder's copies
STREAM_BYTES_PER_CORNER = 44   # full refinement: the last level, its parent, the painting
WINDOW_BYTES_PER_CORNER = 70   # a windowed step per child corner: the step, the flags, the
                               # faces' boxes, the renumbered patch
SIZE_FACTOR = 6.0              # largest face box side / sqrt(mean face area) (5.8 at level 10)


@dataclass(frozen=True)
class Grid:
    """A pixel grid over ``window`` (x0, y0, x1, y1): square pixels, row 0 at the top."""

    window: tuple[float, float, float, float]
    width: int
    height: int
    pixel: float

    @classmethod
    def fit(cls, window, size: int) -> Grid:
        """``size`` pixels along the window's longer side."""
        x0, y0, x1, y1 = (float(v) for v in window)
        if not (x1 > x0 and y1 > y0):
            raise ValueError(f"window needs x0 < x1 and y0 < y1, got {window}")
        if size < 1:
            raise ValueError(f"size must be at least 1 pixel, got {size}")
        pixel = max(x1 - x0, y1 - y0) / size
        width = max(1, int(round((x1 - x0) / pixel)))
        height = max(1, int(round((y1 - y0) / pixel)))
        return cls((x0, y0, x1, y1), width, height, pixel)

    def inside(self, points: NDArray[np.float64]) -> NDArray[np.bool_]:
        """(n,) True for points in the closed window."""
        x0, y0, x1, y1 = self.window
        return ((points[:, 0] >= x0) & (points[:, 0] <= x1)
                & (points[:, 1] >= y0) & (points[:, 1] <= y1))

    def pixels(self, points: NDArray[np.float64]) -> NDArray[np.int64]:
        """Flat pixel index of every point (points must be inside the window)."""
        col, row = self.cells(points)
        return row * self.width + col

    def cells(self, points: NDArray[np.float64]) -> tuple[NDArray[np.int64], NDArray]:
        """(column, row) of every point (points must be inside the window)."""
        x0, _, _, y1 = self.window
        ix = np.clip(np.floor((points[:, 0] - x0) / self.pixel), 0, self.width - 1)
        iy = np.clip(np.floor((y1 - points[:, 1]) / self.pixel), 0, self.height - 1)
        return ix.astype(np.int64), iy.astype(np.int64)

    def region(self, rect) -> tuple[float, float, float, float]:
        """The mesh-unit window of the pixel rectangle ``(column, row, width, height)``, one
        pixel larger on every side (what lands in the rectangle is decided by :meth:`cells`,
        on this whole grid, so a tile's pixels are those of the whole image)."""
        c, r, w, h = rect
        x0, _, _, y1 = self.window
        return (x0 + (c - 1) * self.pixel, y1 - (r + h + 1) * self.pixel,
                x0 + (c + w + 1) * self.pixel, y1 - (r - 1) * self.pixel)


def default_window(mesh: Mesh) -> tuple[float, float, float, float]:
    """The input's bounds, grown by the most the boundary fractal can bulge out of an edge."""
    v = mesh.vertices
    e = mesh.topology.edges
    longest = float(np.hypot(*(v[e[:, 1]] - v[e[:, 0]]).T).max())
    pad = 0.2 * longest  # the L-system curve stays within 0.17 of its chord
    return (float(v[:, 0].min() - pad), float(v[:, 1].min() - pad),
            float(v[:, 0].max() + pad), float(v[:, 1].max() + pad))


# -- windowed refinement ------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class Patch:
    """A refined patch: a submesh and the per-vertex flags described in the module docstring."""

    mesh: Mesh
    exact: NDArray[np.bool_]
    complete: NDArray[np.bool_]
    outer: NDArray[np.int8]


def _face_boxes(mesh: Mesh) -> NDArray[np.float64]:
    """(F, 4) x0, y0, x1, y1 of every (pentagon) face."""
    p = np.take(mesh.vertices, mesh.dense_faces(), axis=0)
    return np.concatenate([p.min(axis=1), p.max(axis=1)], axis=1)


def _step(patch: Patch, window, halo: float, smooth: bool, centre: str,
          chirality: str) -> Patch:
    """One snub step of a patch, then the faces outside the window plus halo dropped."""
    mesh = patch.mesh
    topo = mesh.topology
    n_v, n_e = mesh.n_vertices, topo.n_edges
    # The step on the patch treats the patch's cut as boundary and does not move vertices on
    # it; those vertices lack part of their star, so they are marked inexact below.
    child = snub.step(mesh, smooth=smooth, centre=centre, chirality=chirality).mesh
    faces = child.dense_faces()
    n_c = child.n_vertices

    # flags of the child's vertices: old | z0 z1 per edge | centres
    ends = topo.edges
    uses = np.bincount(topo.half_edge_edge, minlength=n_e)
    at_complete = patch.complete[ends[:, 0]] | patch.complete[ends[:, 1]]
    known_boundary = (uses == 1) & at_complete
    edge_known = (uses == 2) | known_boundary
    ux = np.empty(n_c, dtype=bool)
    sc = np.empty(n_c, dtype=bool)
    co = np.empty(n_c, dtype=np.int8)
    ux[:n_v], sc[:n_v], co[:n_v] = patch.exact, patch.complete, patch.outer
    z = slice(n_v, n_v + 2 * n_e)
    ux[z] = np.repeat(patch.exact[ends[:, 0]] & patch.exact[ends[:, 1]], 2)
    sc[z] = np.repeat(edge_known, 2)
    co[z] = np.repeat(np.where(edge_known, known_boundary.astype(np.int8), -1), 2)
    exact_corners = patch.exact[mesh.face_indices]
    ux[n_v + 2 * n_e:] = np.bincount(mesh.half_edge_face, weights=~exact_corners,
                                     minlength=mesh.n_faces) == 0
    sc[n_v + 2 * n_e:] = True
    co[n_v + 2 * n_e:] = 0

    vertices = child.vertices
    if smooth:  # a moved vertex is exact when all its faces were built from exact vertices
        face_ok = ux[faces].all(axis=1)
        star_ok = np.bincount(faces[~face_ok].ravel(), minlength=n_c) == 0
        exact = np.where(co == 1, ux, (co == 0) & sc & star_ok)
    else:
        exact = ux

    # drop the child faces that cannot influence the window
    corners = np.take(vertices, faces, axis=0)
    boxes = np.concatenate([corners.min(axis=1), corners.max(axis=1)], axis=1)
    del corners
    size = float((boxes[:, 2:] - boxes[:, :2]).max()) if len(boxes) else 0.0
    margin = halo * size
    x0, y0, x1, y1 = window
    keep = ((boxes[:, 0] <= x1 + margin) & (boxes[:, 2] >= x0 - margin)
            & (boxes[:, 1] <= y1 + margin) & (boxes[:, 3] >= y0 - margin))
    complete = sc & (np.bincount(faces[~keep].ravel(), minlength=n_c) == 0)
    kept = faces[keep]
    used = np.zeros(n_c, dtype=bool)
    used[kept.ravel()] = True
    new_id = np.cumsum(used) - 1          # order-preserving renumbering
    flat = new_id[kept.ravel()].astype(np.int32)
    offsets = np.arange(0, len(flat) + 1, 5, dtype=np.int64)
    sub = Mesh.trusted(np.ascontiguousarray(vertices[used]), offsets, flat,
                       _sub_topology(child.topology, keep, new_id))
    sub.__dict__["face_degree"] = 5
    return Patch(sub, exact[used], complete[used], co[used])


def _sub_topology(topo: Topology, keep: NDArray[np.bool_], new_id: NDArray) -> Topology:
    """The topology of the kept faces (pentagons) of a child, read off the child's: the edges
    they use, renumbered in order (no sort; a cut-out patch may pinch at a vertex, which is
    fine here)."""
    he = topo.half_edge_edge.reshape(-1, 5)[keep].ravel()
    used = np.zeros(topo.n_edges, dtype=bool)
    used[he] = True
    edge_id = (np.cumsum(used) - 1).astype(np.int32)
    edges = new_id[topo.edges[used]].astype(np.int32)
    return Topology(edges, edge_id[he], topo.half_edge_side.reshape(-1, 5)[keep].ravel())


def refine_window(mesh: Mesh, levels: int, window, *, smooth: bool = True,
                  centre: str = "vertex", chirality: str = "left", halo: float = HALO):
    """Yield, for levels 0..``levels``, the (n, 2) vertices of the refinement inside ``window``.

    Only faces near the window are refined; the vertices yielded are exactly (bit for bit)
    those of the full refinement that lie in the closed window. Raises WeaveCutError if the
    exactness check fails (a halo too small for the input).
    """
    window = tuple(float(v) for v in window)
    grid = Grid.fit(window, 1)
    if mesh.face_degree is None:  # a ragged input cannot be cut without changing its sums
        keep_all_first = True
    else:
        keep_all_first = False
    outer = outer_vertices(mesh).astype(np.int8)
    patch = Patch(mesh, np.ones(mesh.n_vertices, bool), np.ones(mesh.n_vertices, bool), outer)
    yield mesh.vertices[grid.inside(mesh.vertices)]
    for t in range(1, levels + 1):
        if patch.mesh.n_faces == 0:  # the window is clear of the mesh: nothing more to refine
            yield np.zeros((0, 2))
            continue
        patch = _step(patch, window, np.inf if (t == 1 and keep_all_first) else halo, smooth,
                      centre, chirality)
        inside = grid.inside(patch.mesh.vertices)
        if not (patch.exact[inside].all() and patch.complete[inside].all()):
            bad = int((~(patch.exact & patch.complete) & inside).sum())
            raise WeaveCutError(f"windowed refinement is not exact at level {t} "
                                f"({bad} vertices in the window); use a larger halo")
        yield patch.mesh.vertices[inside]


def refine_full(mesh: Mesh, levels: int, *, smooth: bool = True, centre: str = "vertex",
                chirality: str = "left"):
    """Yield the (V, 2) vertices of levels 0..``levels`` of the full refinement."""
    yield mesh.vertices
    for _ in range(levels):
        mesh = snub.step(mesh, smooth=smooth, centre=centre, chirality=chirality).mesh
        yield mesh.vertices


def window_faces(mesh: Mesh, levels: int, window, halo: float = HALO) -> list[int]:
    """Estimated faces of the patch :func:`refine_window` keeps at levels 0..``levels``.

    Every input face f of k corners has k * 5**(t - 1) descendants at level t; the patch keeps
    the share of them that lies in the window grown by the halo and one face, estimated as
    the area of f's bounding box inside the grown window over f's area (at most 1), with a
    face size of SIZE_FACTOR * sqrt(area / count). Cheap, made before any refinement.
    """
    x0, y0, x1, y1 = window
    corners = np.take(mesh.vertices, mesh.face_indices, axis=0)
    starts = mesh.face_offsets[:-1]
    lo, hi = np.minimum.reduceat(corners, starts), np.maximum.reduceat(corners, starts)
    area = np.maximum(np.abs(signed_areas(mesh)), 1e-300)
    out = [mesh.n_faces]
    for t in range(1, levels + 1):
        count = mesh.face_sizes * 5.0 ** (t - 1)
        grow = (halo + 1) * SIZE_FACTOR * np.sqrt(area / count)
        w = np.minimum(hi[:, 0], x1 + grow) - np.maximum(lo[:, 0], x0 - grow)
        h = np.minimum(hi[:, 1], y1 + grow) - np.maximum(lo[:, 1], y0 - grow)
        share = np.minimum(np.clip(w, 0, None) * np.clip(h, 0, None) / area, 1.0)
        out.append(int(np.ceil((count * share).sum())))
    return out


def memory_need(mesh: Mesh, levels: int, grid: Grid, windowed: bool) -> tuple[list, list]:
    """(bytes, faces) estimated for stopping at each level 0..``levels``: the peak of the
    whole refinement (a stream: only the last level and its parent are alive) or of the
    windowed one (the largest step of the patch), plus the image on ``grid``."""
    fixed = BASE_BYTES + IMAGE_BYTES_PER_PIXEL * grid.width * grid.height
    if not windowed:
        table = sizes(mesh, levels, snub.counts)
        return ([fixed + STREAM_BYTES_PER_CORNER * h for *_, h in table],
                [f for _, _, f, _ in table])
    faces = window_faces(mesh, levels, grid.window)
    corners = [mesh.n_corners] + [5 * f for f in faces[1:]]
    need, peak = [], 0
    for t in range(levels + 1):
        if t:
            peak = max(peak, WINDOW_BYTES_PER_CORNER * 5 * corners[t - 1])
        need.append(fixed + peak)
    return need, faces


def check_memory(mesh: Mesh, levels: int, grid: Grid, windowed: bool,
                 available: int | None = None) -> None:
    """Refuse, before any refinement, a level image that would not fit in memory."""
    need, faces = memory_need(mesh, levels, grid, windowed)
    require(need, faces, available, " of the window" if windowed else "")


def check_tiles_memory(mesh: Mesh, levels: int, grid: Grid, tile_size: int, jobs: int,
                       available: int | None = None) -> None:
    """Refuse a tile pyramid that would not fit: the assembled full-resolution level image
    (and its halves) in this process, plus ``jobs`` windowed tiles rendering at once (a tile
    at the centre of the image stands for all)."""
    cx, cy = (grid.window[0] + grid.window[2]) / 2, (grid.window[1] + grid.window[3]) / 2
    half = tile_size * grid.pixel / 2
    tile = Grid.fit((cx - half, cy - half, cx + half, cy + half), tile_size)
    need, faces = memory_need(mesh, levels, tile, windowed=True)
    image = 2 * grid.width * grid.height
    require([image + jobs * n for n in need], faces, available, " of a tile")


# -- the image ----------------------------------------------------------------------------

def level_image(mesh: Mesh, levels: int, size: int, window=None, *, smooth: bool = True,
                centre: str = "vertex", chirality: str = "left") -> tuple[NDArray, Grid]:
    """(H, W) uint8: the first level whose vertices fall in each pixel (UNSET = 255: none).

    Without ``window`` the whole mesh is refined over :func:`default_window`; with one, only
    the faces near it (:func:`refine_window`).
    """
    _check_levels(levels)
    grid = Grid.fit(default_window(mesh) if window is None else window, size)
    options = {"smooth": smooth, "centre": centre, "chirality": chirality}
    if window is None:
        stream = refine_full(mesh, levels, **options)
    else:
        stream = refine_window(mesh, levels, grid.window, **options)
    return paint(grid, (0, 0, grid.width, grid.height), stream), grid


def tile_image(mesh: Mesh, levels: int, grid: Grid, rect, **options) -> NDArray[np.uint8]:
    """(h, w) uint8: the pixel rectangle ``rect = (column, row, w, h)`` of the level image on
    ``grid``, equal to that part of the whole image, refining only the faces near the tile
    (so tiles render independently, in any order or process)."""
    _check_levels(levels)
    return paint(grid, rect, refine_window(mesh, levels, grid.region(rect), **options))


def paint(grid: Grid, rect, stream) -> NDArray[np.uint8]:
    """(h, w) uint8 of the pixel rectangle ``rect`` of ``grid`` from a stream of per-level
    points: every pixel gets the first level with a point in it."""
    c0, r0, w, h = rect
    image = np.full(w * h, UNSET, dtype=np.uint8)
    for t, points in enumerate(stream):
        col, row = grid.cells(points[grid.inside(points)])
        col -= c0
        row -= r0
        mine = (col >= 0) & (col < w) & (row >= 0) & (row < h)
        pix = row[mine] * w + col[mine]
        pix = pix[image[pix] == UNSET]
        image[pix] = t
    return image.reshape(h, w)


def _check_levels(levels: int) -> None:
    if not 0 <= levels < UNSET:
        raise ValueError(f"levels must be 0..{UNSET - 1}, got {levels}")


def colour(image: NDArray[np.uint8]) -> NDArray[np.uint8]:
    """(H, W, 3) RGB of a level image: levels 0-9 brighter, 10-12 green, unset white."""
    table = np.empty((256, 3), dtype=np.uint8)
    table[:] = DEEPER
    table[:len(LEVEL_COLOURS)] = LEVEL_COLOURS
    table[UNSET] = BACKGROUND
    return table[image]


def png_bytes(rgb: NDArray[np.uint8]) -> bytes:
    """PNG of an (H, W, 3) uint8 image (no timestamps: same pixels, same bytes)."""
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(rgb), "RGB").save(buf, format="PNG")
    return buf.getvalue()


def write_png(path, rgb: NDArray[np.uint8]) -> None:
    write_atomic(path, png_bytes(rgb))
