"""Closed outlines of an SVG drawing, in millimetres, curves flattened to a tolerance.

svgelements parses the file: it applies every ``transform``, the ``viewBox`` and the
``width``/``height`` units (mm, cm, in, pt, px at 96 per inch, as Inkscape and browsers do),
and turns rects, circles, ellipses, polygons, polylines and lines into paths. Here each
closed subpath becomes one ring and each open one a piece (``rings.enclosed_faces`` finds the
faces that pieces enclose). Hidden elements
(``display:none``, such as a hidden Inkscape layer) are skipped by svgelements. The y axis is
turned round (SVG's points down) so that the drawing reads the same way up.

The budgets (``budgets``) come first: elements and path data are counted on the XML, each
``<use>`` as the copy svgelements makes of it, before svgelements reads the file; every
segment's numbers are checked and its chords counted before it is flattened.
"""

from __future__ import annotations

import io
import itertools
import math
import re
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import svgelements as se

from ..errors import MeshFileError
from ..text import nearest
from . import budgets
from .rings import Ring

MM_PER_PX = 25.4 / 96  # svgelements works in CSS pixels, 96 per inch
INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"
USE = ("use", "{http://www.w3.org/2000/svg}use")
XLINK_HREF = "{http://www.w3.org/1999/xlink}href"
GEOMETRY = ("d", "points", "transform")  # the attributes svgelements parses number by number
TOKEN = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[A-Za-z]")
ELEMENTS = "elements"
PATH_DATA = "path data (d, points, transform)"
COUNT_CAP = 10**15  # counts of <use> copies stop growing here (they would reach 10^1000)


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
        data = path.read_bytes()
        _check_size(data, path)
        document = se.SVG.parse(_Whole(data), reify=True)
    except MeshFileError:
        raise
    except Exception as exc:  # svgelements raises bare ParseError, ValueError, ... on bad XML
        raise MeshFileError(f"{path}: not a readable SVG ({type(exc).__name__}: "
                            f"{str(exc)[:120]})") from None
    shapes = list(_shapes(document, layer))
    if layer is not None and not shapes:
        names = _layer_names(document)
        raise MeshFileError(f"{path}: no shapes in a layer or group named {layer!r}"
                            f"{nearest(layer, names)}; layers: {', '.join(names) or 'none'}")
    rings, pieces = [], []
    tolerance = flatten / MM_PER_PX
    to_mm = np.array([MM_PER_PX, -MM_PER_PX]) * _unit_fix(document)
    total = 0
    for label, shape in shapes:
        for k, subpath in enumerate(abs(se.Path(shape)).as_subpaths()):  # transform applied
            name = label if k == 0 else f"{label} (subpath {k + 1})"
            counts = _counts(subpath, tolerance, to_mm[0], f"{path}: {name}")
            total += sum(counts)
            budgets.check_points(str(path), total, flatten)
            points, closed = _flattened(subpath, counts, tolerance)
            if len(points) < 2:
                continue
            ring = Ring(name, points * to_mm)
            (rings if closed else pieces).append(ring)
    return rings, pieces


def _check_size(data: bytes, path: Path) -> None:
    """Refuse an SVG over MAX_ELEMENTS, MAX_PATH_DATA or MAX_PATH_TEXT before svgelements makes
    an object of every element, every ``<use>`` copy and every number: counted as the XML is
    read (stopping at the first element over), each ``<use>`` standing for a copy of the
    element it names, as svgelements expands it."""
    own, parts, ids, links, open_ = [], [], {}, {}, []  # per element: path data, parts
    text = [0, 0]  # path data so far: numbers and commands, characters

    def start(tag: str, attributes: dict) -> None:
        if len(own) == budgets.MAX_ELEMENTS:
            _refuse(path, f"more than {budgets.MAX_ELEMENTS:,}", ELEMENTS, budgets.MAX_ELEMENTS)
        k = len(own)
        if open_:
            parts[open_[-1]].append(k)
        parts.append([])
        open_.append(k)
        geometry = [attributes[key] for key in GEOMETRY if key in attributes]
        text[1] += sum(map(len, geometry))
        if text[1] > budgets.MAX_PATH_TEXT:
            _refuse(path, f"more than {budgets.MAX_PATH_TEXT:,} characters of", PATH_DATA,
                    budgets.MAX_PATH_TEXT)
        left = budgets.MAX_PATH_DATA - text[0]
        own.append(sum(_tokens(value, left + 1) for value in geometry))
        text[0] += own[-1]
        if own[-1] > left:
            _refuse(path, f"more than {budgets.MAX_PATH_DATA:,} numbers and commands of",
                    PATH_DATA, budgets.MAX_PATH_DATA)
        if "id" in attributes:
            ids[attributes["id"]] = k
        if tag in USE:  # svgelements: href over xlink:href, the id after the first character
            links[k] = attributes.get("href", attributes.get(XLINK_HREF))

    parser = ET.XMLParser(target=_Target(start, lambda tag: open_.pop()))
    parser.feed(data)  # whole: fed 16 KiB at a time, a long tag costs its length squared
    parser.close()
    for k, url in links.items():
        if url is not None and url[1:] in ids:
            parts[k].append(ids[url[1:]])
    elements, numbers = _expanded(parts, own, {k: name for name, k in ids.items()}, path)
    copies = f" once <use> copies are made (the file has {len(own):,} elements)"
    if elements > budgets.MAX_ELEMENTS:
        _refuse(path, budgets.amount(elements), ELEMENTS + copies, budgets.MAX_ELEMENTS)
    if numbers > budgets.MAX_PATH_DATA:
        _refuse(path, f"{budgets.amount(numbers)} numbers and commands of", PATH_DATA + copies,
                budgets.MAX_PATH_DATA)


class _Target:
    """An ElementTree parser target that only calls back (no tree is built)."""

    def __init__(self, start, end):
        self.start, self.end = start, end

    def close(self):
        return None


def _refuse(path: Path, count: str, what: str, limit: int):
    raise MeshFileError(f"{path}: {count} {what}; at most {limit:,} are read")


def _tokens(text: str | None, cap: int) -> int:
    """Numbers and commands in ``text``, counting no further than ``cap``."""
    return 0 if not text else sum(1 for _ in itertools.islice(TOKEN.finditer(text), cap))


def _expanded(parts: list[list[int]], own: list[int], names: dict[int, str],
              path: Path) -> tuple[int, int]:
    """(elements, path data) under element 0 with every ``<use>`` followed, without recursion
    (a chain of ``<use>`` can be as long as the file)."""
    done: dict[int, tuple[int, int]] = {}
    open_ = set()  # elements whose parts are being counted: a <use> of one of them loops
    stack = [(0, False)]
    while stack:
        k, parts_done = stack.pop()
        if parts_done:
            open_.discard(k)
            done[k] = (min(COUNT_CAP, 1 + sum(done[q][0] for q in parts[k])),
                       min(COUNT_CAP, own[k] + sum(done[q][1] for q in parts[k])))
        elif k not in done:
            if k in open_:
                raise MeshFileError(f"{path}: a <use> copies an element that holds it "
                                    f"(id {names.get(k)!r})")
            open_.add(k)
            stack.append((k, True))
            stack.extend((q, False) for q in parts[k] if q not in done)
    return done[0]


class _Whole(io.BytesIO):
    """A stream that gives all it holds at the first read: ElementTree's iterparse reads 16 KiB
    at a time, and expat reads a tag across n reads n times over (a 20 MB path took 14 s)."""

    def read(self, size: int = -1) -> bytes:
        return super().read()


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


def _counts(subpath, tolerance: float, mm: float, where: str) -> list[float]:
    """Chords of every drawn segment of a subpath (``_pieces``), once its numbers are checked
    (finite, within ``budgets.MAX_COORDINATE``; ``mm`` per px)."""
    counts = []
    for segment in subpath:
        if isinstance(segment, (se.Move, se.Close)):
            continue
        if isinstance(segment, se.Arc):
            budgets.check_coordinates(where, [segment.rx, segment.ry], mm, "arc radius")
        budgets.check_coordinates(where, _control_points(segment), mm)
        counts.append(_pieces(segment, tolerance))
    return counts


def _control_points(segment) -> np.ndarray:
    """(k, 2) start, control points (an arc: its centre) and end of a segment, in px."""
    middle = {se.QuadraticBezier: ("control",), se.CubicBezier: ("control1", "control2"),
              se.Arc: ("center",)}.get(type(segment), ())
    return np.array([segment.start, *(getattr(segment, k) for k in middle), segment.end],
                    dtype=float)


def _flattened(subpath, counts: list[float], tolerance: float) -> tuple[np.ndarray, bool]:
    """Points of one subpath (px), each curve split into its ``counts`` chords so no chord
    strays beyond ``tolerance``."""
    pieces = []
    closed = False
    drawn = iter(counts)
    for segment in subpath:
        if isinstance(segment, se.Move):
            pieces.append(np.array([[segment.end.x, segment.end.y]]))
            continue
        if isinstance(segment, se.Close):
            closed = True
            continue
        t = np.linspace(0.0, 1.0, int(next(drawn)) + 1)[1:]
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


def _pieces(segment, tolerance: float) -> float:
    """How many chords keep a segment within ``tolerance`` of its polyline (``math.inf`` when
    too many to count).

    A chord of a curve with second derivative at most M strays by at most M / (8 n^2) when the
    parameter range [0, 1] is cut into n equal parts; for an arc of radius r, the sagitta of
    an angle step a is r (1 - cos(a / 2)).
    """
    if isinstance(segment, se.Line):
        return 1
    if isinstance(segment, (se.QuadraticBezier, se.CubicBezier)):
        return budgets.bezier_pieces(_control_points(segment), tolerance)
    if isinstance(segment, se.Arc):
        r = max(abs(segment.rx), abs(segment.ry))
        sweep = abs(segment.sweep)
        if r <= tolerance:
            return max(1, math.ceil(sweep / (math.pi / 2)))
        step = 2 * math.acos(1 - tolerance / r)
        return max(1, math.ceil(sweep / step)) if step > 0 else math.inf  # 0: r >> tolerance
    return 1
