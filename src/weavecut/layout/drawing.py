"""The Drawing: what every layout produces and every writer consumes.

Drawing -> sheets (size in mm) -> layers (a role: cut, score, engrave, paint, label, guide)
-> shapes (polygons, polylines, text, and pictures of line work too fine for vectors).
Coordinates are millimetres with the origin at the sheet's bottom-left corner and
y pointing up (the CAD convention); the SVG and PNG writers flip y. Shapes are batches held as
ragged arrays so that a million faces cost a few arrays, not a million objects.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import shapely
from numpy.typing import NDArray

from ..numeric import offsets_of

ROLES = ("cut", "score", "engrave", "paint", "label", "guide")


@dataclass(frozen=True)
class Style:
    """Stroke and fill. ``stroke_width`` 0 means a hairline (what lasers cut on; drawn one
    device pixel wide: a non-scaling stroke in SVG, a 0-width line in PDF)."""

    stroke: str | None = "#000000"
    stroke_width: float = 0.2
    fill: str | None = None
    opacity: float = 1.0


@dataclass(frozen=True, eq=False)
class Polygons:
    """Closed rings (no repeated last point), grouped into polygons (exterior, then holes).

    Parameters
    ----------
    coords : (N, 2) float64, mm
    ring_offsets : (R + 1,) int64, ring r is ``coords[ring_offsets[r]:ring_offsets[r + 1]]``
    polygon_offsets : (P + 1,) int64 into rings; None means every ring is a polygon
    fills : per-polygon fill colours overriding ``style.fill``, or None
    """

    coords: NDArray[np.float64]
    ring_offsets: NDArray[np.int64]
    style: Style = Style()
    polygon_offsets: NDArray[np.int64] | None = None
    fills: tuple[str, ...] | None = None

    @property
    def n_polygons(self) -> int:
        po = self.polygon_offsets
        return len(self.ring_offsets) - 1 if po is None else len(po) - 1

    def polygon_rings(self) -> NDArray[np.int64]:
        """(P + 1,) offsets of every polygon's rings."""
        if self.polygon_offsets is None:
            return np.arange(len(self.ring_offsets), dtype=np.int64)
        return self.polygon_offsets

    def rings(self) -> list[NDArray[np.float64]]:
        """Every ring as an (n, 2) array."""
        o = self.ring_offsets.tolist()
        return [self.coords[a:b] for a, b in zip(o[:-1], o[1:])]

    def to_shapely(self) -> NDArray[np.object_]:
        """(P,) shapely polygons."""
        ring_id = np.repeat(np.arange(len(self.ring_offsets) - 1), np.diff(self.ring_offsets))
        rings = shapely.linearrings(self.coords, indices=ring_id)
        po = self.polygon_rings()
        poly_id = np.repeat(np.arange(len(po) - 1), np.diff(po))
        return shapely.polygons(rings, indices=poly_id)

    def transformed(self, scale: float, offset) -> Polygons:
        return replace(self, coords=self.coords * scale + np.asarray(offset, dtype=float))


@dataclass(frozen=True, eq=False)
class Polylines:
    """Open polylines: ``coords`` (N, 2) mm split by ``offsets`` (L + 1,)."""

    coords: NDArray[np.float64]
    offsets: NDArray[np.int64]
    style: Style = Style()

    def lines(self) -> list[NDArray[np.float64]]:
        o = self.offsets.tolist()
        return [self.coords[a:b] for a, b in zip(o[:-1], o[1:])]


@dataclass(frozen=True)
class Text:
    """A line of text; ``size`` is the cap height in mm, ``angle`` in degrees counter-clockwise."""

    x: float
    y: float
    text: str
    size: float = 3.0
    anchor: str = "start"  # start, middle, end
    angle: float = 0.0
    fill: str = "#000000"


@dataclass(frozen=True, eq=False)
class Raster:
    """A greyscale picture stretched over the box from (``x``, ``y``) (its bottom-left corner,
    mm) to (``x + width``, ``y + height``): line work too fine to draw as vectors
    (``layout.raster``). Opaque: white where there is no ink.

    Parameters
    ----------
    pixels : (H, W) uint8, row 0 at the top (as image files hold them); 0 black, 255 white
    vector : the Polygons and Polylines it is a picture of, which a writer without a good
        picture element (DXF) draws instead; empty for a cropped picture (a tiled page)
    """

    x: float
    y: float
    width: float
    height: float
    pixels: NDArray[np.uint8]
    vector: tuple[Polygons | Polylines, ...] = ()

    def __post_init__(self) -> None:
        pixels = np.array(self.pixels, dtype=np.uint8)  # a private copy, read-only
        if pixels.ndim != 2 or not pixels.size:
            raise ValueError(f"a picture needs (H, W) pixels, got shape {pixels.shape}")
        if not (np.isfinite([self.x, self.y, self.width, self.height]).all()
                and self.width > 0 and self.height > 0):
            raise ValueError(f"a picture needs a finite box of positive size, got "
                             f"{self.width} x {self.height} mm at ({self.x}, {self.y})")
        pixels.flags.writeable = False
        object.__setattr__(self, "pixels", pixels)

    @property
    def coords(self) -> NDArray[np.float64]:
        """(4, 2) the box's corners, counter-clockwise from the bottom left (what bounds are
        taken from)."""
        x0, y0, x1, y1 = self.x, self.y, self.x + self.width, self.y + self.height
        return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)

    def moved(self, dx: float, dy: float) -> Raster:
        return replace(self, x=self.x + dx, y=self.y + dy, vector=tuple(
            replace(s, coords=s.coords + (dx, dy)) for s in self.vector))

    def cropped(self, x0: float, y0: float, x1: float, y1: float) -> Raster | None:
        """The whole pixels that reach into the box (x0, y0, x1, y1), or None for none; the
        crop stands for no vector."""
        h, w = self.pixels.shape
        px, py = self.width / w, self.height / h
        c0 = max(0, int(np.floor((x0 - self.x) / px)))
        c1 = min(w, int(np.ceil((x1 - self.x) / px)))
        r0 = max(0, int(np.floor((self.y + self.height - y1) / py)))  # rows from the top
        r1 = min(h, int(np.ceil((self.y + self.height - y0) / py)))
        if c1 <= c0 or r1 <= r0:
            return None
        return Raster(self.x + c0 * px, self.y + self.height - r1 * py, (c1 - c0) * px,
                      (r1 - r0) * py, self.pixels[r0:r1, c0:c1])


Shape = Polygons | Polylines | Text | Raster


def vectors(shapes):
    """``shapes`` with every picture (Raster) replaced by the shapes it is a picture of (for
    writers with no good picture element: DXF, a laser project)."""
    for shape in shapes:
        yield from shape.vector if isinstance(shape, Raster) else (shape,)


@dataclass(frozen=True)
class Layer:
    """Named shapes with a role; a hidden layer is kept in the file but not shown."""

    name: str
    role: str
    shapes: tuple[Shape, ...] = ()
    visible: bool = True

    def __post_init__(self) -> None:
        if self.role not in ROLES:
            raise ValueError(f"layer role must be one of {ROLES}, got {self.role!r}")


@dataclass(frozen=True)
class Sheet:
    width: float
    height: float
    layers: tuple[Layer, ...] = ()
    name: str = ""


@dataclass(frozen=True)
class Drawing:
    """Sheets plus metadata (title, and the command that made it)."""

    sheets: tuple[Sheet, ...]
    title: str = "weave-cut"
    metadata: tuple[tuple[str, str], ...] = field(default=())

    def with_metadata(self, **items: str) -> Drawing:
        return replace(self, metadata=self.metadata + tuple(items.items()))


def polygons_from_rings(rings, style: Style = Style(), fills=None) -> Polygons:
    """Polygons from a list of (n, 2) arrays, one polygon per ring."""
    rings = [np.asarray(r, dtype=float).reshape(-1, 2) for r in rings]
    coords = np.concatenate(rings) if rings else np.zeros((0, 2))
    offsets = np.concatenate([[0], np.cumsum([len(r) for r in rings])]).astype(np.int64)
    return Polygons(coords, offsets, style, None, None if fills is None else tuple(fills))


def polylines_from_lines(lines, style: Style = Style()) -> Polylines:
    """Polylines from a list of (n, 2) arrays."""
    lines = [np.asarray(line, dtype=float).reshape(-1, 2) for line in lines]
    coords = np.concatenate(lines) if lines else np.zeros((0, 2))
    offsets = np.concatenate([[0], np.cumsum([len(line) for line in lines])]).astype(np.int64)
    return Polylines(coords, offsets, style)


def polygons_from_shapely(geoms, style: Style = Style(), fills=None) -> Polygons:
    """Polygons from shapely Polygons (holes kept); rings are written counter-clockwise
    for exteriors and clockwise for holes (an empty polygon: one ring without points)."""
    geoms = list(geoms)
    polys = np.empty(len(geoms), dtype=object)
    polys[:] = geoms
    polys = shapely.orient_polygons(polys)
    po = offsets_of(shapely.get_num_interior_rings(polys) + 1)
    rings, owner = shapely.get_rings(polys, return_index=True)  # none for an empty polygon
    first = np.searchsorted(owner, owner)  # the polygon's first ring among ``rings``
    slot = po[owner] + np.arange(len(owner)) - first
    n = shapely.get_num_coordinates(rings)
    counts = np.zeros(po[-1], dtype=np.int64)
    counts[slot] = np.maximum(n - 1, 0)  # the closing point is left out
    keep = np.ones(n.sum(), dtype=bool)
    keep[(np.cumsum(n) - 1)[n > 0]] = False
    coords = shapely.get_coordinates(rings)[keep] if len(rings) else np.zeros((0, 2))
    return Polygons(coords, offsets_of(counts), style, po,
                    None if fills is None else tuple(fills))


def mesh_polygons(mesh, transform, style: Style = Style(), fills=None,
                  faces: NDArray[np.int64] | None = None) -> Polygons:
    """The faces of a mesh (all, or the ``faces`` selected) as polygons through ``transform``."""
    sizes = mesh.face_sizes
    if faces is None:
        idx, offsets = mesh.face_indices, mesh.face_offsets
    else:
        faces = np.asarray(faces, dtype=np.int64)
        starts = mesh.face_offsets[faces]
        sel_sizes = sizes[faces]
        offsets = np.concatenate([[0], np.cumsum(sel_sizes)]).astype(np.int64)
        within = np.arange(offsets[-1]) - np.repeat(offsets[:-1], sel_sizes)
        idx = mesh.face_indices[np.repeat(starts, sel_sizes) + within]
    coords = transform(np.take(mesh.vertices, idx, axis=0))
    return Polygons(coords, np.asarray(offsets, dtype=np.int64), style, None,
                    None if fills is None else tuple(fills))


@dataclass(frozen=True)
class Fit:
    """Uniform scale and offset that place model coordinates on a sheet (mm)."""

    scale: float
    offset: tuple[float, float]

    def __call__(self, xy: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(xy, dtype=float) * self.scale + np.asarray(self.offset)

    @classmethod
    def into(cls, bounds, width: float, height: float, margin: float) -> Fit:
        """Fit ``bounds`` (x0, y0, x1, y1) centred into a width x height sheet with a margin."""
        x0, y0, x1, y1 = bounds
        scale = min((width - 2 * margin) / max(x1 - x0, 1e-12),
                    (height - 2 * margin) / max(y1 - y0, 1e-12))
        ox = (width - (x1 - x0) * scale) / 2 - x0 * scale
        oy = (height - (y1 - y0) * scale) / 2 - y0 * scale
        return cls(float(scale), (float(ox), float(oy)))


def mesh_bounds(mesh) -> tuple[float, float, float, float]:
    v = mesh.vertices
    return (float(v[:, 0].min()), float(v[:, 1].min()), float(v[:, 0].max()), float(v[:, 1].max()))
