"""Closed outlines of a DXF drawing's model space, in millimetres, curves flattened.

ezdxf reads the file (``ezdxf.recover``, which also repairs what CAD programs commonly get
wrong) and turns every entity into a path (``ezdxf.path.make_path``: bulges, arcs, circles,
ellipses and splines included), flattened so no chord strays beyond the tolerance. Closed
LWPOLYLINE, 2-D POLYLINE, CIRCLE, closed ELLIPSE and SPLINE are rings; open pieces (LINE, ARC,
open polylines) are returned apart: ``rings.enclosed_faces`` finds the faces they enclose.
Blocks (INSERT) are ignored. ``$INSUNITS`` gives the unit (unitless drawings are read as mm).
"""

from __future__ import annotations

from pathlib import Path

import ezdxf
import numpy as np
from ezdxf import path as dxfpath
from ezdxf import recover
from ezdxf import units as dxfunits

from ..errors import MeshFileError
from .rings import Ring

ENTITIES = "LWPOLYLINE POLYLINE CIRCLE ELLIPSE SPLINE LINE ARC"


def read_rings(path: Path, flatten: float,
               layer: str | None = None) -> tuple[list[Ring], list[Ring]]:
    """Closed rings and open pieces (lines, arcs, open polylines) of the DXF at ``path``.

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
    return rings, pieces


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
