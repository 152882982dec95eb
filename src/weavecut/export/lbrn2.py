"""LightBurn project writer (.lbrn2): one sheet of a Drawing as a project ready to cut.

LightBurn's format is not published; this writes only what LightBurn's own files show (the
reference files in ``tests/export/lightburn_reference``, saved by LightBurn 1.7.08):

- the root ``LightBurnProject`` (``FormatVersion`` 1: .lbrn2), ``UIPrefs`` that run the layers
  by priority and the inner shapes of a layer before the outer ones;
- one ``CutSetting type="Cut"`` per laser layer of the sheet (role cut, score or engrave), in
  the order they run: engraving, then scoring, then the cut layers in the Drawing's order (inner
  cuts, the frame's hole, the outer outline last, as the layouts number them); its ``index`` is
  LightBurn's layer number (00 black, 01 blue, 02 red: the role's colour when it is one of
  these; further layers take 03, 04, ...), its ``name`` the Drawing layer's, with the
  operation's speed (mm/s), power (per cent) and passes, and its ``priority``;
- every ring and polyline as a ``Shape Type="Path"`` in millimetres at true size, y up with the
  sheet's lower-left corner at the origin (the Drawing's own coordinates), an identity
  ``XForm``, vertices without control points (``c0x1c1x1``) and straight primitives: a closed
  ring (a polygon's ring, or a polyline that returns to its start) as ``LineClosed``, an open
  polyline as ``L0 1L1 2...`` (no closing segment: boxes.py's LightBurn writer once closed open
  paths and drew extra lines);
- a ``Notes`` text shown on opening, one line of items split by `` | ``: the title, the
  provenance (weave-cut's version and the command), the sheet size, the material, the kerf and
  every layer's settings.

Numbers are fixed-point decimals (no exponent: readers such as lbrnts take ``[-0-9.]``
only), rounded to ``DECIMALS``; the same drawing gives the same bytes. Text on a laser layer is
refused: layouts engrave text as single strokes (``layout.strokefont``). Layers of other roles
(paint, label, guide) are not for the laser and are left out.
"""

from __future__ import annotations

import numpy as np

from .. import __version__
from ..errors import ExportError
from ..layout.drawing import Drawing, Layer, Polygons, Polylines, Text, vectors
from ..layout.lasersetup import ROLES, LaserJob

SUFFIX = "lbrn2"
APP_VERSION = "1.7.08"  # the LightBurn whose files this writes like (the reference files)
DECIMALS = 4  # mm: 0.1 micrometre
PALETTE = ("#000000", "#0000ff", "#ff0000")  # LightBurn's layers 00, 01, 02
NOTE_SEPARATOR = " | "  # between the note's items: it is one line (LightBurn's files show no
# line break in a note, and lbrnts reads "&#10;" as those five characters)
N_LAYERS = 30  # C00..C29 (30 and 31 are LightBurn's tool layers)
UI_PREFS = (("Optimize_ByLayer", "0"), ("Optimize_ByPriority", "1"),
            ("Optimize_InnerToOuter", "1"))


def render(drawing: Drawing, job: LaserJob | None = None) -> bytes:
    """The LightBurn project of ``drawing``'s only sheet with ``job``'s settings."""
    if job is None:
        raise ExportError("a LightBurn project needs the laser's settings (a LaserJob)")
    if len(drawing.sheets) != 1:
        raise ExportError(f"a LightBurn project holds one sheet; {drawing.title!r} has "
                          f"{len(drawing.sheets)}: write one file per sheet")
    sheet = drawing.sheets[0]
    layers = laser_layers(sheet.layers)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<LightBurnProject AppVersion="{APP_VERSION}" FormatVersion="1" '
           'MaterialHeight="0" MirrorX="False" MirrorY="False">',
           "    <UIPrefs>",
           *(f'        <{key} Value="{value}"/>' for key, value in UI_PREFS),
           "    </UIPrefs>"]
    for priority, (layer, index, _) in enumerate(layers):
        op = job.operation(layer.role)
        out += ['    <CutSetting type="Cut">',
                f'        <index Value="{index}"/>',
                f'        <name Value="{_escape(layer.name)}"/>',
                f'        <minPower Value="{_number(op.power)}"/>',
                f'        <maxPower Value="{_number(op.power)}"/>',
                f'        <speed Value="{_number(op.speed)}"/>',
                f'        <numPasses Value="{op.passes}"/>',
                f'        <priority Value="{priority}"/>',
                "    </CutSetting>"]
    for layer, index, paths in layers:
        for xy, closed in paths:
            out += [f'    <Shape Type="Path" CutIndex="{index}">',
                    "        <XForm>1 0 0 1 0 0</XForm>",
                    f"        <VertList>{_vertices(xy)}</VertList>",
                    f"        <PrimList>{_primitives(len(xy), closed)}</PrimList>",
                    "    </Shape>"]
    out += [f'    <Notes ShowOnLoad="1" Notes="{_escape(_notes(drawing, layers, job))}"/>',
            "</LightBurnProject>", ""]
    return "\n".join(out).encode("utf-8")


def laser_layers(layers: tuple[Layer, ...]) -> list[tuple[Layer, int, list]]:
    """(layer, LightBurn index, paths) of every laser layer with a path, in the order they run
    (``ROLES``, then the Drawing's order); paths as (xy rounded to ``DECIMALS``, closed)."""
    found = [(layer, _paths(layer)) for layer in layers if layer.role in ROLES]
    found = sorted([f for f in found if f[1]], key=lambda f: ROLES.index(f[0].role))
    wanted = {layer.role: PALETTE.index(_colour(layer)) for layer, _ in reversed(found)
              if _colour(layer) in PALETTE}
    spare = iter(range(len(PALETTE), N_LAYERS))  # 00-02 stay the colours they are
    out, given = [], set()
    for layer, paths in found:
        index = wanted.get(layer.role)
        if index is None or index in given:
            index = next(spare, None)
            if index is None:
                raise ExportError(f"a LightBurn project has {N_LAYERS} layers; this sheet "
                                  f"needs {len(found)}")
        given.add(index)
        out.append((layer, index, paths))
    return out


def _colour(layer: Layer) -> str | None:
    """The stroke colour of the layer's first stroked shape (lower case)."""
    for shape in vectors(layer.shapes):
        stroke = getattr(getattr(shape, "style", None), "stroke", None)
        if stroke:
            return stroke.lower()
    return None


def _paths(layer: Layer) -> list[tuple[np.ndarray, bool]]:
    """Every ring (closed; a ring never repeats its first point) and polyline of ``layer`` with
    at least two points; a polyline whose last point is its first (after rounding) is a closed
    ring without the repeat."""
    paths = []
    for shape in vectors(layer.shapes):  # a picture's lines: a laser cuts or scores them
        if isinstance(shape, Text):
            raise ExportError(f"layer {layer.name!r} holds text {shape.text!r}; a laser layer "
                              "takes text as single strokes (layout.strokefont)")
        if isinstance(shape, Polygons):
            pieces = [(ring, True) for ring in shape.rings()]
        elif isinstance(shape, Polylines):
            pieces = [(line, False) for line in shape.lines()]
        else:
            continue
        for xy, closed in pieces:
            xy = np.round(np.asarray(xy, dtype=float), DECIMALS) + 0.0
            if not closed and len(xy) > 2 and (xy[0] == xy[-1]).all():
                xy, closed = xy[:-1], True
            if len(xy) >= 2:
                paths.append((xy, closed and len(xy) >= 3))
    return paths


def _vertices(xy: np.ndarray) -> str:
    return "".join(f"V{_decimal(x)} {_decimal(y)}c0x1c1x1" for x, y in xy.tolist())


def _primitives(n: int, closed: bool) -> str:
    """``LineClosed`` for a closed ring, else the n - 1 lines of an open polyline."""
    return "LineClosed" if closed else "".join(f"L{i} {i + 1}" for i in range(n - 1))


def _notes(drawing: Drawing, layers, job: LaserJob) -> str:
    sheet = drawing.sheets[0]
    meta = dict(drawing.metadata)
    lines = [drawing.title]
    if "generator" not in meta:
        lines.append(f"generator: weave-cut {__version__}")
    lines += [f"{key}: {value}" for key, value in drawing.metadata]
    lines += [f"sheet: {_number(sheet.width)} x {_number(sheet.height)} mm, its lower-left corner "
              "at the origin (0, 0), y up: start from absolute coordinates",
              f"material: {job.material}" if job.material else "material: not named",
              f"kerf: {job.kerf or 'the outlines are as drawn; no layer has a Kerf Offset'}",
              "layers, in the order they run (priority):"]
    for layer, index, paths in layers:
        op = job.operation(layer.role)
        lines.append(f"C{index:02d} {layer.name} ({layer.role}, {len(paths)} "
                     f"path{'s' if len(paths) != 1 else ''}): "
                     f"{_number(op.speed)} mm/s, {_number(op.power)} % power, {op.passes} "
                     f"pass{'es' if op.passes != 1 else ''}")
    lines.append("speeds and powers come from the material preset: test them on a scrap first")
    return NOTE_SEPARATOR.join(lines)


def _escape(text: str) -> str:
    """``text`` as an XML attribute value on one line (the five XML entities)."""
    text = " ".join(text.split())  # no line breaks or tabs: the references show none
    for raw, ref in (("&", "&amp;"), ("<", "&lt;"), (">", "&gt;"), ('"', "&quot;")):
        text = text.replace(raw, ref)
    return text


def _number(x: float) -> str:
    return _decimal(round(float(x), DECIMALS) + 0.0)


def _decimal(x: float) -> str:
    """``x`` (already rounded to ``DECIMALS``) in fixed point without trailing zeros."""
    text = f"{x:.{DECIMALS}f}".rstrip("0").rstrip(".")
    return "0" if text in ("", "-0") else text
