"""Closed outlines of an SVG drawing, in millimetres, curves flattened to a tolerance.

svgelements parses the file: it applies every ``transform``, the ``viewBox`` and the
``width``/``height`` units (mm, cm, in, pt, px at 96 per inch, as Inkscape and browsers do),
and turns rects, circles, ellipses, polygons, polylines and lines into paths. Here each
closed subpath becomes one ring and each open one a piece (``rings.enclosed_faces`` finds the
faces that pieces enclose). Hidden elements
(``display:none``, such as a hidden Inkscape layer) are skipped by svgelements. The y axis is
turned round (SVG's points down) so that the drawing reads the same way up.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import svgelements as se

from ..errors import MeshFileError
from .rings import Ring

MM_PER_PX = 25.4 / 96  # svgelements works in CSS pixels, 96 per inch
INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"


def read_rings(path: Path, flatten: float,
               layer: str | None = None) -> tuple[list[Ring], list[Ring]]:
    """Closed rings and open pieces (open subpaths, lines, polylines) of the SVG at ``path``.

    Parameters
    ----------
    path : the SVG file
    flatten : largest distance, in mm, between a curve and its flattened polyline
    layer : keep only shapes in the Inkscape layer (or group) with this label or id

    Returns
    -------
    rings : closed outlines (label, (k, 2) float64 mm, counter-clockwise or not)
    pieces : open polylines, in mm
    """
    try:
        document = se.SVG.parse(str(path), reify=True)
    except Exception as exc:  # svgelements raises bare ParseError, ValueError, ... on bad XML
        raise MeshFileError(f"{path}: not a readable SVG ({type(exc).__name__}: "
                            f"{str(exc)[:120]})") from None
    shapes = list(_shapes(document, layer))
    if layer is not None and not shapes:
        raise MeshFileError(f"{path}: no shapes in a layer or group named {layer!r}; layers: "
                            f"{', '.join(_layer_names(document)) or 'none'}")
    rings, pieces = [], []
    tolerance = flatten / MM_PER_PX
    to_mm = np.array([MM_PER_PX, -MM_PER_PX]) * _unit_fix(document)
    for label, shape in shapes:
        for k, subpath in enumerate(abs(se.Path(shape)).as_subpaths()):  # transform applied
            points, closed = _flattened(subpath, tolerance)
            if len(points) < 2:
                continue
            name = label if k == 0 else f"{label} (subpath {k + 1})"
            ring = Ring(name, points * to_mm)
            (rings if closed else pieces).append(ring)
    return rings, pieces


def _unit_fix(document) -> float:
    """svgelements turns mm into px with 0.0393701 inch per mm, not 1 / 25.4, so a document
    sized in mm or cm over a viewBox (Inkscape's) comes out 5.4e-7 too large, and it reads
    CSS's quarter-millimetres (Q) as pixels: this factor undoes both, and a 50 mm square
    stays 50 mm to the last digit."""
    width = str(document.values.get("width", "")).strip().lower()
    if document.viewbox is None:
        return 1.0
    if width.endswith(("mm", "cm")):
        return 1.0 / (25.4 * 0.0393701)
    if width.endswith("q"):
        return 0.25 / MM_PER_PX
    return 1.0


def _shapes(group, layer: str | None, inside: bool = False) -> Iterator[tuple[str, se.Shape]]:
    """(label, shape) of every visible shape in document order, within ``layer`` if given."""
    for element in group:
        if isinstance(element, se.Group):
            names = {element.values.get(INKSCAPE + "label"), element.id}
            yield from _shapes(element, layer, inside or layer in names)
        elif isinstance(element, se.Shape) and (layer is None or inside):
            tag = type(element).__name__.lower()
            yield (f"<{tag} id={element.id[:40]!r}>" if element.id else f"<{tag}>"), element


def _layer_names(document) -> list[str]:
    return sorted({g.values.get(INKSCAPE + "label") or g.id for g in document.select()
                   if isinstance(g, se.Group) and (g.values.get(INKSCAPE + "label") or g.id)
                   and g is not document})


def _flattened(subpath, tolerance: float) -> tuple[np.ndarray, bool]:
    """Points of one subpath (px), each curve split so no chord strays beyond ``tolerance``."""
    pieces = []
    closed = False
    for segment in subpath:
        if isinstance(segment, se.Move):
            pieces.append(np.array([[segment.end.x, segment.end.y]]))
            continue
        if isinstance(segment, se.Close):
            closed = True
            continue
        n = _pieces(segment, tolerance)
        t = np.linspace(0.0, 1.0, n + 1)[1:]
        pieces.append(np.asarray(segment.npoint(t), dtype=float).reshape(-1, 2))
    if not pieces:
        return np.empty((0, 2)), False
    points = np.concatenate(pieces)
    ends_meet = len(points) > 2 and np.hypot(*(points[-1] - points[0])) <= tolerance
    if closed or ends_meet:
        if np.hypot(*(points[-1] - points[0])) <= tolerance:
            points = points[:-1]
        return points, True
    return points, False


def _pieces(segment, tolerance: float) -> int:
    """How many chords keep a segment within ``tolerance`` of its polyline.

    A chord of a curve with second derivative at most M strays by at most M / (8 n^2) when the
    parameter range [0, 1] is cut into n equal parts; for an arc of radius r, the sagitta of
    an angle step a is r (1 - cos(a / 2)).
    """
    if isinstance(segment, se.Line):
        return 1
    if isinstance(segment, se.QuadraticBezier):
        p = np.array([segment.start, segment.control, segment.end], dtype=float)
        m = 2 * np.hypot(*(p[0] - 2 * p[1] + p[2]))
    elif isinstance(segment, se.CubicBezier):
        p = np.array([segment.start, segment.control1, segment.control2, segment.end],
                     dtype=float)
        m = 6 * max(np.hypot(*(p[0] - 2 * p[1] + p[2])), np.hypot(*(p[1] - 2 * p[2] + p[3])))
    elif isinstance(segment, se.Arc):
        r = max(abs(segment.rx), abs(segment.ry))
        sweep = abs(segment.sweep)
        if r <= tolerance:
            return max(1, math.ceil(sweep / (math.pi / 2)))
        step = 2 * math.acos(1 - tolerance / r)
        return max(1, math.ceil(sweep / step))
    else:
        return 1
    return max(1, math.ceil(math.sqrt(m / (8 * tolerance))))
