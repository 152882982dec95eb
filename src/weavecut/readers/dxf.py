"""Closed outlines of a DXF drawing's model space, in millimetres, curves flattened.

ezdxf reads the file (``ezdxf.recover``, which also repairs what CAD programs commonly get
wrong) and turns every entity into a path (``ezdxf.path.make_path``: bulges, arcs, circles,
ellipses and splines included), flattened so no chord strays beyond the tolerance. Closed
LWPOLYLINE, 2-D POLYLINE, CIRCLE, closed ELLIPSE and SPLINE are rings; open pieces (LINE, ARC,
open polylines) are returned apart: ``rings.enclosed_faces`` finds the faces they enclose.
Blocks (INSERT) are ignored. ``$INSUNITS`` gives the unit (unitless drawings are read as mm).

The budgets (``budgets``) come first: lines and entities are counted on the text before ezdxf
loads it; every entity's numbers are checked before ezdxf draws it, and its points counted
before it is flattened.
"""

from __future__ import annotations

import io
import math
import re
from pathlib import Path

import ezdxf
import numpy as np
from ezdxf import path as dxfpath
from ezdxf import recover
from ezdxf import units as dxfunits
from ezdxf.audit import AuditError
from ezdxf.math import Vec3
from ezdxf.recover import bytes_loader

from ..errors import MeshFileError
from ..text import nearest
from . import budgets
from .rings import Ring

ENTITIES = "LWPOLYLINE POLYLINE CIRCLE ELLIPSE SPLINE LINE ARC"
LENGTHS = ("center", "radius", "start", "end", "major_axis", "vertex", "control_point",
           "fit_point")  # numbers in drawing units, checked in mm
MAX_BULGE = 1e6  # tan of a quarter of the arc's angle: 359.9998 degrees, a radius of 250,000 chords


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
        data = path.read_bytes()
        _check_size(data, path)
        doc, auditor = recover.read(io.BytesIO(data))
    except MeshFileError:  # a budget of _check_size (a ValueError too)
        raise
    except (OSError, ezdxf.DXFStructureError) as exc:
        raise MeshFileError(f"{path}: not a readable DXF ({exc})"[:200]) from None
    except (ValueError, ArithmeticError) as exc:  # ezdxf's repair on degenerate data, e.g. an
        # ELLIPSE whose axes it swaps ("Invalid major axis", "float division")
        raise MeshFileError(f"{path}: not a readable DXF (ezdxf's repair failed: "
                            f"{type(exc).__name__}: {exc})"[:200]) from None
    _refuse_dropped_ellipses(auditor, path)
    scale = _mm_per_unit(doc.header.get("$INSUNITS", 0), path)
    entities = doc.modelspace().query(ENTITIES)
    if layer is not None:
        layers = sorted({e.dxf.layer for e in doc.modelspace()})
        entities = [e for e in entities if e.dxf.layer == layer]
        if not entities:
            raise MeshFileError(f"{path}: no outlines on layer {layer!r}"
                                f"{nearest(layer, layers)}; layers: "
                                f"{', '.join(layers) or 'none'}")
    rings, pieces = [], []
    total = fitted = 0
    for entity in entities:
        name = f"{entity.dxftype()} #{entity.dxf.handle} (layer {entity.dxf.layer!r})"
        if entity.dxftype() == "POLYLINE" and not entity.is_2d_polyline:
            continue  # 3-D polylines and polyface meshes are no planar outlines
        where = f"{path}: {name}"
        _check_numbers(entity, where, scale)
        if entity.dxftype() == "SPLINE":
            fitted += len(entity.fit_points) if not len(entity.control_points) else 0
            if fitted > budgets.MAX_FIT_POINTS:
                raise MeshFileError(f"{where}: the splines have more than "
                                    f"{budgets.MAX_FIT_POINTS:,} fit points in all; at most "
                                    f"{budgets.MAX_FIT_POINTS:,} are read")
            # ezdxf makes a curve or more of every control point, and 4 chords of each
            budgets.check_points(str(path), total + 4 * len(entity.control_points), flatten)
        try:
            p = dxfpath.make_path(entity)
        except Exception as exc:  # ezdxf raises ValueError, ZeroDivisionError, ... on bad data
            raise MeshFileError(f"{where} cannot be drawn ({exc})"[:300]) from None
        total += _flattened_count(p, flatten / scale, scale, where)
        budgets.check_points(str(path), total, flatten)
        points = np.array([(v.x, v.y) for v in p.flattening(flatten / scale)]) * scale
        if len(points) < 2:
            continue
        closes = np.hypot(*(points[-1] - points[0])) <= flatten
        if _is_closed(entity) or (closes and len(points) > 3):
            rings.append(Ring(name, points[:-1] if closes else points))
        else:
            pieces.append(Ring(name, points))
    return rings, pieces


def _refuse_dropped_ellipses(auditor, path: Path) -> None:
    """Refuse an ELLIPSE with a null major axis, which ezdxf's repair removes without a word:
    the drawing would lose an outline (a one-line error naming it instead)."""
    for fix in auditor.fixes:
        if fix.code == AuditError.INVALID_MAJOR_AXIS:
            found = re.search(r"ELLIPSE\(#(\w+)\)", fix.message)
            name = f"ELLIPSE #{found[1]}" if found else "an ELLIPSE"
            raise MeshFileError(f"{path}: {name}: major axis (0, 0, 0) has no length, so the "
                                "ellipse has no size; redraw it")


def _check_size(data: bytes, path: Path) -> None:
    """Refuse a DXF over MAX_DXF_LINES, or with more than MAX_ELEMENTS entities of the kinds
    read, before ezdxf makes an object of every tag: counted with ezdxf's own tag reader,
    twenty times faster than the whole load."""
    lines = data.count(b"\n")  # ezdxf reads a tag as two lines, split at b"\n" only
    if lines > budgets.MAX_DXF_LINES:
        raise MeshFileError(f"{path}: {lines:,} lines of DXF text; at most "
                            f"{budgets.MAX_DXF_LINES:,} are read")
    kinds = set(ENTITIES.encode().split())
    found = sum(tag.code == 0 and tag.value in kinds for tag in bytes_loader(io.BytesIO(data)))
    if found > budgets.MAX_ELEMENTS:
        raise MeshFileError(f"{path}: {found:,} entities ({ENTITIES}); at most "
                            f"{budgets.MAX_ELEMENTS:,} are read")


def _mm_per_unit(units, path: Path) -> float:
    """Millimetres per drawing unit of ``$INSUNITS`` (0, unitless, is read as mm)."""
    if units == 0:
        return 1.0
    try:
        return float(dxfunits.conversion_factor(units, dxfunits.MM))
    except (ValueError, TypeError, KeyError):
        raise MeshFileError(f"{path}: $INSUNITS {units!r} is no unit weave-cut converts "
                            "(4 is mm, 0 none)") from None


def _check_numbers(entity, where: str, scale: float) -> None:
    """Refuse an entity with a number that is not finite (ezdxf flattens NaN for ever), a
    length beyond ``budgets.MAX_COORDINATE`` or a bulge beyond MAX_BULGE, an ELLIPSE whose
    ratio is not in (0, 1], a SPLINE beyond MAX_DEGREE or whose knots do not rise."""
    kind = entity.dxftype()
    fields = {key: value for key, value in entity.dxf.all_existing_dxf_attribs().items()
              if isinstance(value, (float, Vec3))}
    if kind == "LWPOLYLINE":
        rows = np.array(entity.get_points("xyb"), dtype=float).reshape(-1, 3)
        fields.update(vertex=rows[:, :2], bulge=rows[:, 2])
    elif kind == "POLYLINE":
        fields.update(vertex=[v.dxf.location for v in entity.vertices],
                      bulge=[v.dxf.bulge for v in entity.vertices])
    elif kind == "SPLINE":
        fields.update(control_point=entity.control_points, fit_point=entity.fit_points,
                      knot=entity.knots, weight=entity.weights)
    for key, value in fields.items():
        values = np.asarray(value, dtype=float).reshape(-1)
        what = key.replace("_", " ")
        if key in LENGTHS:
            budgets.check_coordinates(where, values, scale, what)
        elif not np.isfinite(values).all():
            raise MeshFileError(f"{where}: {what} {values[~np.isfinite(values)][0]} is not a "
                                "finite number")
    bulge = np.abs(np.asarray(fields.get("bulge", []), dtype=float))
    if (bulge > MAX_BULGE).any():
        raise MeshFileError(f"{where}: bulge {bulge.max():.3g} is beyond {MAX_BULGE:g}")
    if kind == "ELLIPSE" and not 0 < entity.dxf.ratio <= 1:
        raise MeshFileError(f"{where}: ratio {entity.dxf.ratio:g} of the axes is not in (0, 1]")
    if kind == "SPLINE":
        if not 1 <= entity.dxf.degree <= budgets.MAX_DEGREE:
            raise MeshFileError(f"{where}: degree {entity.dxf.degree}; splines of degree 1 to "
                                f"{budgets.MAX_DEGREE} are read")
        knots = np.array(entity.knots)
        span = float(knots[-1]) - float(knots[0]) if len(knots) else 1.0  # inf, not a warning
        if np.any(knots[1:] < knots[:-1]) or not 0 < span < math.inf:
            raise MeshFileError(f"{where}: its knots must rise from the first to the last, "
                                f"over a finite span (found {knots[0]:g} to {knots[-1]:g})")


def _flattened_count(p, tolerance: float, scale: float, where: str) -> float:
    """Points ezdxf's flattening gives ``p`` (an estimate: 4 chords a curve at least, more
    where it bends), once its control points are checked (within MAX_COORDINATE)."""
    vertices = np.array([(v.x, v.y) for v in p.control_vertices()], dtype=float).reshape(-1, 2)
    budgets.check_coordinates(where, vertices, scale)
    total, start = 1.0, p.start
    for command in p.commands():
        control = [start, *(getattr(command, k) for k in ("ctrl", "ctrl1", "ctrl2")
                            if hasattr(command, k)), command.end]
        start = command.end
        if len(control) > 2:
            total += max(4, budgets.bezier_pieces(np.array([(v.x, v.y) for v in control]),
                                                  tolerance))
        else:
            total += 1
    return total


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
