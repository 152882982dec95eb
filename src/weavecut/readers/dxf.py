"""Closed outlines of a DXF drawing's model space, in millimetres, curves flattened.

ezdxf reads the file (``ezdxf.recover``, which also repairs what CAD programs commonly get
wrong) and turns every entity into a path (``ezdxf.path.make_path``: bulges, arcs, circles,
ellipses and splines included), flattened so no chord strays beyond the tolerance. Closed
LWPOLYLINE, 2-D POLYLINE, CIRCLE, closed ELLIPSE and SPLINE are rings; open pieces (LINE, ARC,
open polylines) give the faces they enclose (loops, or a grid drawn with every edge once).
Blocks (INSERT) are ignored. ``$INSUNITS`` gives the unit (unitless drawings are read as mm).
"""

from __future__ import annotations

from pathlib import Path

import ezdxf
import numpy as np
import shapely
from ezdxf import path as dxfpath
from ezdxf import recover
from ezdxf import units as dxfunits

from ..errors import MeshFileError
from .rings import Ring, close_groups

ENTITIES = "LWPOLYLINE POLYLINE CIRCLE ELLIPSE SPLINE LINE ARC"


def read_rings(path: Path, flatten: float, layer: str | None = None) -> tuple[list[Ring], int]:
    """Closed rings of the DXF at ``path``, and 0 (an open end that encloses nothing is an
    error naming the entity, so no open piece is skipped).

    Parameters
    ----------
    path : the DXF file
    flatten : largest distance, in mm, between a curve and its flattened polyline
    layer : keep only entities on this layer
    """
    try:
        doc, auditor = recover.readfile(str(path))
    except (OSError, ezdxf.DXFStructureError) as exc:
        raise MeshFileError(f"{path}: not a readable DXF ({exc})"[:200]) from None
    units = doc.header.get("$INSUNITS", 0)
    scale = 1.0 if units == 0 else dxfunits.conversion_factor(units, dxfunits.MM)
    entities = doc.modelspace().query(ENTITIES)
    if layer is not None:
        layers = sorted({e.dxf.layer for e in doc.modelspace()})
        entities = [e for e in entities if e.dxf.layer == layer]
        if not entities:
            raise MeshFileError(f"{path}: no outlines on layer {layer!r}; layers: "
                                f"{', '.join(layers) or 'none'}")
    rings, pieces = [], []
    for entity in entities:
        name = f"{entity.dxftype()} #{entity.dxf.handle} (layer {entity.dxf.layer!r})"
        if entity.dxftype() == "POLYLINE" and not entity.is_2d_polyline:
            continue  # 3-D polylines and polyface meshes are no planar outlines
        p = dxfpath.make_path(entity)
        points = np.array([(v.x, v.y) for v in p.flattening(flatten / scale)]) * scale
        if len(points) < 2:
            continue
        closes = np.hypot(*(points[-1] - points[0])) <= flatten
        if _is_closed(entity) or (closes and len(points) > 3):
            rings.append(Ring(name, points[:-1] if closes else points))
        else:
            pieces.append(Ring(name, points))
    return rings + _chained(pieces, flatten), 0


def _is_closed(entity) -> bool:
    kind = entity.dxftype()
    if kind == "LWPOLYLINE":
        return entity.closed
    if kind == "POLYLINE":
        return entity.is_closed
    if kind == "SPLINE":
        return entity.closed
    if kind == "ELLIPSE":
        return bool(np.isclose(abs(entity.dxf.end_param - entity.dxf.start_param), 2 * np.pi))
    return kind == "CIRCLE"


def _chained(pieces: list[Ring], tolerance: float) -> list[Ring]:
    """The faces that open pieces (lines, arcs) enclose, as a CAD user draws a mesh: every
    region bounded by pieces is a ring, whether they form separate loops or a shared grid.

    Ends closer than ``tolerance`` are joined first; a piece with an end that joins nothing is
    an error naming it.
    """
    if not pieces:
        return []
    ends = np.array([[p.points[0], p.points[-1]] for p in pieces]).reshape(-1, 2)
    label = close_groups(ends, tolerance)
    moved = ends[np.unique(label, return_index=True)[1][label]]  # ends that meet coincide
    lines = [np.vstack([moved[2 * k], p.points[1:-1], moved[2 * k + 1]])
             for k, p in enumerate(pieces)]
    faces, _, dangles, invalid = shapely.polygonize_full(
        shapely.get_parts(shapely.union_all(shapely.linestrings(lines))))
    loose = shapely.get_parts(shapely.union(dangles, invalid))
    if len(loose):
        x, y = shapely.get_coordinates(loose[0])[0]
        k = int(np.argmin(shapely.distance(shapely.linestrings(lines), loose[0])))
        raise MeshFileError(f"{pieces[k].label} near ({x:.3f}, {y:.3f}) mm has an open end; "
                            "lines and arcs must enclose faces")
    return [Ring(f"face {k + 1} enclosed by lines and arcs", np.asarray(f.exterior.coords)[:-1])
            for k, f in enumerate(shapely.get_parts(faces))]
