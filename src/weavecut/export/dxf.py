"""DXF writer: R2000, millimetres ($INSUNITS = 4), one layer per Drawing layer, closed
LWPOLYLINEs for rings. Sheets after the first are placed to the right of it."""

from __future__ import annotations

import contextlib
import io

import ezdxf
from ezdxf import colors

from ..layout.drawing import Drawing, Polygons, Polylines, Text

SUFFIX = "dxf"
ROLE_COLOURS = {"cut": 1, "score": 5, "engrave": 3, "paint": 8, "label": 7, "guide": 9}
ALIGN = {"start": "LEFT", "middle": "CENTER", "end": "RIGHT"}


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
        doc = ezdxf.new("R2000", setup=False)
        doc.units = ezdxf.units.MM
        doc.header["$INSUNITS"] = 4
        doc.header["$MEASUREMENT"] = 1
        for key, value in drawing.metadata:
            doc.header.custom_vars.append(key, value)
        msp = doc.modelspace()
        dx = 0.0
        for n, sheet in enumerate(drawing.sheets):
            for layer in sheet.layers:
                name = layer.name if len(drawing.sheets) == 1 else f"{layer.name}-{n + 1}"
                name = _layer_name(name)
                if name not in doc.layers:
                    entry = doc.layers.add(name, color=ROLE_COLOURS.get(layer.role, 7))
                    if not layer.visible:
                        entry.off()
                for shape in layer.shapes:
                    _add(msp, shape, name, dx)
            dx += sheet.width + 10.0
        buf = io.StringIO()
        doc.write(buf)
    return buf.getvalue().encode("utf-8")


def _add(msp, shape, layer: str, dx: float) -> None:
    attribs = {"layer": layer}
    if isinstance(shape, Text):
        msp.add_text(shape.text, height=shape.size, rotation=shape.angle,
                     dxfattribs=attribs).set_placement(
            (shape.x + dx, shape.y), align=ezdxf.enums.TextEntityAlignment[
                {"start": "BOTTOM_LEFT", "middle": "BOTTOM_CENTER", "end": "BOTTOM_RIGHT"}[
                    shape.anchor]])
        return
    if shape.style.stroke and shape.style.stroke != "#000000":
        attribs["true_color"] = colors.rgb2int(_rgb(shape.style.stroke))
    if isinstance(shape, Polygons):
        for ring in shape.rings():
            msp.add_lwpolyline((ring + (dx, 0.0)).tolist(), close=True, dxfattribs=attribs)
    elif isinstance(shape, Polylines):
        for line in shape.lines():
            msp.add_lwpolyline((line + (dx, 0.0)).tolist(), close=False, dxfattribs=attribs)


def _rgb(hex_colour: str) -> tuple[int, int, int]:
    h = hex_colour.lstrip("#")
    return (int(h[0:2], 16), int(h[2:4], 16), int(h[4:6], 16))


def _layer_name(name: str) -> str:
    bad = '<>/\\":;?*|=`'
    return "".join("_" if ch in bad else ch for ch in name)
