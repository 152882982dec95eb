"""DXF writer: R2004, millimetres ($INSUNITS = 4), one layer per Drawing layer, closed
LWPOLYLINEs for stroked rings. Sheets after the first are placed to the right of it.

Colours: a layer has its role's colour (cut red, score blue, engrave green, as laser software
expects); a shape drawn in a colour of its own carries it as a true colour (R2004 is the
oldest DXF with true colours), except black on a cut, score or engrave layer, which stays
BYLAYER. Filled polygons become solid HATCHes, one layer per fill colour
(``<layer>-<rrggbb>``, in that true colour), so a weave keeps one layer per strand colour.

The title and metadata (generator, command) open the file as 999 comment groups, as LibreCAD
stamps its own files; every reader skips comments, ``ezdxf.comments`` reads them back. Text is
in the file's code page (ANSI_1252), other characters escaped as ``\\U+XXXX`` as ezdxf does.
"""

from __future__ import annotations

import contextlib
import functools
import io

import ezdxf
import numpy as np
from ezdxf import colors
from ezdxf.enums import TextEntityAlignment
from ezdxf.lldxf.const import VALID_DXF_LINEWEIGHTS

from ..layout.drawing import Drawing, Layer, Polygons, Polylines, Text

SUFFIX = "dxf"
DECIMALS = 6  # mm: 1 nm, far below any cutter; the last bits of a float never reach the file
VERSION = "R2004"
# a layer's colour index by role: red cuts, blue scores, black (7: black on white) engraving,
# as the laser presets (templates/laser/) colour the lines themselves
ROLE_COLOURS = {"cut": 1, "score": 5, "engrave": 7, "paint": 8, "label": 7, "guide": 9}
LASER_ROLES = {"cut", "score", "engrave"}
ALIGN = {"start": "BOTTOM_LEFT", "middle": "BOTTOM_CENTER", "end": "BOTTOM_RIGHT"}


@contextlib.contextmanager
def _fixed_metadata():
    """ezdxf stamps GUIDs and times; fix them so the same drawing gives the same bytes."""
    old = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = old


def render(drawing: Drawing) -> bytes:
    with _fixed_metadata():
        doc = ezdxf.new(VERSION, setup=False)
        doc.units = ezdxf.units.MM
        doc.header["$INSUNITS"] = 4
        doc.header["$MEASUREMENT"] = 1
        doc.header["$LWDISPLAY"] = 1
        msp = doc.modelspace()
        lines: dict[str, str] = {}  # the LWPOLYLINEs' text by handle (see _lwpolyline)
        dx = 0.0
        for n, sheet in enumerate(drawing.sheets):
            suffix = "" if len(drawing.sheets) == 1 else f"-{n + 1}"
            for layer in sheet.layers:
                for shape in layer.shapes:
                    _add(doc, msp, shape, layer, layer.name + suffix, dx, lines)
            dx += sheet.width + 10.0
        # ezdxf adds the CLASSES of the entity types in use in set order; fix the order first
        doc.classes.add_required_classes(doc.dxfversion)
        doc.classes.classes = dict(sorted(doc.classes.classes.items()))
        buf = io.StringIO()
        doc.write(buf)
    comments = "".join(f"999\n{key}: {' '.join(value.split())}\n"
                       for key, value in [("title", drawing.title), *drawing.metadata])
    return doc.encode(comments + _with_lines(buf.getvalue(), lines))


def _lwpolyline(doc, msp, xy: list, close: bool, attribs: dict, lines: dict) -> None:
    """An LWPOLYLINE, written as ezdxf writes it (the same tags and numbers) with the next
    handle of ezdxf's sequence, without ezdxf's entity object (creating and exporting one costs
    about 0.15 ms: a cut sheet holds thousands); none for no points, as ezdxf does."""
    handle = doc.entitydb.next_handle()
    if not xy:
        return
    text = [f"  0\nLWPOLYLINE\n  5\n{handle}\n330\n{msp.block_record_handle}\n100\nAcDbEntity\n"
            f"  8\n{attribs['layer']}\n"]
    text += [f"{code}\n{attribs[key]}\n" for code, key in (("370", "lineweight"),
                                                          ("420", "true_color")) if key in attribs]
    text.append(f"100\nAcDbPolyline\n 90\n{len(xy)}\n 70\n{1 if close else 0}\n")
    text += [f" 10\n{x}\n 20\n{y}\n" for x, y in xy]
    lines[handle] = "".join(text)


def _with_lines(dxf: str, lines: dict) -> str:
    """``dxf`` with the LWPOLYLINEs put into its ENTITIES section, every entity in the order
    of its handle (the order ezdxf made them in)."""
    head, _, rest = dxf.partition("  2\nENTITIES\n")
    body, end = rest[:rest.index("  0\nENDSEC\n")], rest[rest.index("  0\nENDSEC\n"):]
    tags = body.split("\n")[:-1]
    starts = [i for i in range(0, len(tags), 2) if tags[i] == "  0"] + [len(tags)]
    made = [(int(tags[a + 3], 16), "\n".join(tags[a:b]) + "\n") for a, b in
            zip(starts[:-1], starts[1:])]
    ours = [(int(handle, 16), text) for handle, text in lines.items()]
    return (head + "  2\nENTITIES\n" + "".join(t for _, t in sorted(made + ours))
            + end)


def _add(doc, msp, shape, layer: Layer, name: str, dx: float, lines: dict) -> None:
    if isinstance(shape, Text):
        attribs = _attribs(doc, layer, name, shape.fill)
        msp.add_text(shape.text, height=shape.size, rotation=shape.angle,
                     dxfattribs=attribs).set_placement(
            tuple(_mm(np.array([shape.x, shape.y]), dx)),
            align=TextEntityAlignment[ALIGN[shape.anchor]])
        return
    if isinstance(shape, Polylines):
        if shape.style.stroke:
            attribs = _attribs(doc, layer, name, shape.style.stroke, shape.style.stroke_width)
            for line in shape.lines():
                _lwpolyline(doc, msp, _mm(line, dx), False, attribs, lines)
        return
    rings = shape.rings()
    po = shape.polygon_rings().tolist()
    fills = shape.fills or (shape.style.fill,) * shape.n_polygons
    by_fill: dict[str, list[int]] = {}
    for i, fill in enumerate(fills):
        if fill:
            by_fill.setdefault(fill, []).append(i)
    for fill in sorted(by_fill):
        fill_layer = _layer(doc, layer, f"{name}-{fill.lstrip('#').lower()}", fill)
        hatch = msp.add_hatch(dxfattribs={"layer": fill_layer})
        hatch.set_solid_fill(_aci(fill), style=0, rgb=_rgb(fill))  # odd parity: holes open
        for i in by_fill[fill]:
            for ring in rings[po[i]:po[i + 1]]:
                hatch.paths.add_polyline_path(_mm(ring, dx), is_closed=True)
    if shape.style.stroke:
        attribs = _attribs(doc, layer, name, shape.style.stroke, shape.style.stroke_width)
        for ring in rings:
            _lwpolyline(doc, msp, _mm(ring, dx), True, attribs, lines)


def _mm(xy, dx: float) -> list:
    """Coordinates moved ``dx`` along x and rounded to ``DECIMALS`` (no negative zero)."""
    return (np.round(xy + (dx, 0.0), DECIMALS) + 0.0).tolist()


def _attribs(doc, layer: Layer, name: str, colour: str, width: float = 0.0) -> dict:
    """Entity attributes: the layer, a true colour unless black on a laser layer, and the
    line weight nearest ``width`` mm off laser layers (where lines are hairlines)."""
    attribs = {"layer": _layer(doc, layer, name)}
    if not (colour.lower() == "#000000" and layer.role in LASER_ROLES):
        attribs["true_color"] = colors.rgb2int(_rgb(colour))
    if width > 0 and layer.role not in LASER_ROLES:
        attribs["lineweight"] = min(VALID_DXF_LINEWEIGHTS, key=lambda w: abs(w - 100 * width))
    return attribs


def _layer(doc, layer: Layer, name: str, colour: str | None = None) -> str:
    """The DXF layer ``name`` (created on first use): the role's colour, or ``colour``."""
    name = _layer_name(name)
    if name not in doc.layers:
        entry = doc.layers.add(name, color=ROLE_COLOURS[layer.role] if colour is None
                               else _aci(colour))
        if colour is not None:
            entry.rgb = _rgb(colour)
        if not layer.visible:
            entry.off()
    return name


def _rgb(hex_colour: str) -> tuple[int, int, int]:
    h = hex_colour.lstrip("#")
    return (int(h[0:2], 16), int(h[2:4], 16), int(h[4:6], 16))


@functools.lru_cache(maxsize=None)
def _aci(hex_colour: str) -> int:
    """The nearest AutoCAD colour index, for programs that ignore true colours."""
    r, g, b = _rgb(hex_colour)
    return min(range(1, 256), key=lambda i: sum((a - c) ** 2 for a, c in
                                                 zip(colors.aci2rgb(i), (r, g, b))))


def _layer_name(name: str) -> str:
    bad = '<>/\\":;?*|=`'
    return "".join("_" if ch in bad else ch for ch in name)
