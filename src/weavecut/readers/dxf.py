"""Closed outlines of a DXF drawing's model space, in millimetres, curves flattened.

ezdxf reads the file (``ezdxf.recover``, which also repairs what CAD programs commonly get
wrong) and turns every entity into a path (``ezdxf.path.make_path``: bulges, arcs, circles,
ellipses and splines included), flattened so no chord strays beyond the tolerance. Closed
LWPOLYLINE, 2-D POLYLINE, CIRCLE, closed ELLIPSE and SPLINE are rings; open pieces (LINE, ARC,
open polylines) that meet end to end are chained into rings. Blocks (INSERT) are ignored.
``$INSUNITS`` gives the unit (unitless drawings are read as millimetres).
"""

from __future__ import annotations

from pathlib import Path

import ezdxf
import numpy as np
from ezdxf import path as dxfpath
from ezdxf import recover
from ezdxf import units as dxfunits
from scipy.spatial import cKDTree

from ..errors import MeshFileError
from .rings import Ring

ENTITIES = "LWPOLYLINE POLYLINE CIRCLE ELLIPSE SPLINE LINE ARC"


def read_rings(path: Path, flatten: float, layer: str | None = None) -> tuple[list[Ring], int]:
    """Closed rings of the DXF at ``path`` and the number of open pieces left over (always 0:
    an open end that no other piece continues is an error naming the entity).

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
    scale = 1.0 if units == 0 else dxfunits.conversion_factor(units, dxfunits.InsertUnits.MM)
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
    """Rings made of open pieces whose ends meet (within ``tolerance``), two at every joint."""
    if not pieces:
        return []
    ends = np.array([[p.points[0], p.points[-1]] for p in pieces]).reshape(-1, 2)
    pairs = cKDTree(ends).query_pairs(tolerance, output_type="ndarray")
    partner = np.full(len(ends), -1)
    degree = np.bincount(pairs.ravel(), minlength=len(ends))
    if (degree != 1).any():
        k = int(np.flatnonzero(degree != 1)[0])
        what = "meets no other piece" if degree[k] == 0 else f"meets {degree[k]} other pieces"
        x, y = ends[k]
        raise MeshFileError(f"{pieces[k // 2].label} ends at ({x:.3f}, {y:.3f}) mm where it "
                            f"{what}; outlines must be closed loops")
    partner[pairs[:, 0]], partner[pairs[:, 1]] = pairs[:, 1], pairs[:, 0]
    rings, done = [], np.zeros(len(pieces), dtype=bool)
    for start in range(len(pieces)):  # walk each loop once, piece to piece
        if done[start]:
            continue
        chain, piece, forward = [], start, True  # leave the start piece by its last point
        while not done[piece]:
            done[piece] = True
            pts = pieces[piece].points
            chain.append((pts if forward else pts[::-1])[:-1])
            end = partner[2 * piece + 1 if forward else 2 * piece]
            piece, forward = end // 2, end % 2 == 0
        label = (pieces[start].label if len(chain) == 1
                 else f"loop of {len(chain)} pieces from {pieces[start].label}")
        rings.append(Ring(label, np.concatenate(chain)))
    return rings
