"""The Drawing: what every layout produces and every writer consumes.

Drawing -> sheets (size in mm) -> layers (a role: cut, score, engrave, paint, label, guide)
-> shapes. Coordinates are millimetres with the origin at the sheet's bottom-left corner and
y pointing up (the CAD convention); the SVG and PNG writers flip y. Shapes are batches held as
ragged arrays so that a million faces cost a few arrays, not a million objects.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import shapely
from numpy.typing import NDArray

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


Shape = Polygons | Polylines | Text


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
    for exteriors and clockwise for holes."""
    shapes = np.empty(len(geoms), dtype=object)
    shapes[:] = list(geoms)
    if hasattr(shapely, "orient_polygons") and (shapely.get_type_id(shapes) == 3).all() \
            and not shapely.is_empty(shapes).any():  # polygons, none empty
        # every ring of every polygon at once (exterior first), its closing corner dropped
        rings, owner = shapely.get_rings(shapely.orient_polygons(shapes), return_index=True)
        xy, ring = shapely.get_coordinates(rings, return_index=True)
        size = np.bincount(ring, minlength=len(rings)) - 1
        keep = np.ones(len(xy), dtype=bool)
        keep[np.cumsum(size + 1) - 1] = False
        poly = Polygons(xy[keep], np.concatenate([[0], np.cumsum(size)]).astype(np.int64),
                        style, None, None)
        counts = np.bincount(owner, minlength=len(shapes))
    else:
        shapes = [shapely.orient_polygons(g) if hasattr(shapely, "orient_polygons")
                  else shapely.geometry.polygon.orient(g) for g in shapes]
        rings, counts = [], []
        for g in shapes:
            parts = [g.exterior, *g.interiors]
            rings.extend(np.asarray(r.coords)[:-1] for r in parts)
            counts.append(len(parts))
        poly = polygons_from_rings(rings, style)
    po = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    return replace(poly, polygon_offsets=po, fills=None if fills is None else tuple(fills))


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
