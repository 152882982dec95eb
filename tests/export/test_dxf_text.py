"""The DXF text writer against ezdxf: a drawing of strokes only (a cut file) gets the very bytes
ezdxf gives it when every line is an ezdxf entity (layers met again in another case, the
layers ezdxf makes itself, hidden layers, empty lines, several sheets, any coordinates),
without loading ezdxf; its document skeleton is what ezdxf writes today; characters beyond the
code page are escaped as ezdxf escapes them."""

from __future__ import annotations

import io
import re

import ezdxf
import numpy as np
import pytest
from ezdxf.lldxf.const import VALID_DXF_LINEWEIGHTS
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.export import dxf, dxf_ezdxf, dxf_skeleton, dxf_text
from weavecut.layout.drawing import Drawing, Layer, Polygons, Polylines, Sheet, Style, Text
from weavecut.text import clean

from tests.fresh import modules_after

NAMES = ("cut", "Cut", "0", "DEFPOINTS", "paint 2", "a/b", "é字", "")
COLOURS = ("#000000", "#ff0000", "#12ab9f")

coordinate = st.one_of(st.floats(-1e4, 1e4, allow_nan=False), st.sampled_from(
    [0.0, -0.0, 1e-7, -5e-7, 2.5e-6, 1e17, -3.0000005]))


@st.composite
def shapes(draw):
    sizes = draw(st.lists(st.integers(0, 4), min_size=0, max_size=4))
    n = sum(sizes)
    coords = np.array(draw(st.lists(st.tuples(coordinate, coordinate), min_size=n,
                                    max_size=n)), dtype=float).reshape(-1, 2)
    offsets = np.r_[0, np.cumsum(sizes)].astype(np.int64)
    style = Style(draw(st.sampled_from((None, *COLOURS))), draw(st.sampled_from((0, 0.1, 0.27,
                                                                                 3.0))))
    if draw(st.booleans()):
        return Polylines(coords, offsets, style)
    fills = draw(st.sampled_from((None, (None,) * len(sizes), ("",) * len(sizes))))
    return Polygons(coords, offsets, style, None, fills)


layers = st.builds(Layer, st.sampled_from(NAMES), st.sampled_from(
    ("cut", "score", "engrave", "paint", "label", "guide")), st.lists(shapes(), max_size=3).map(
    tuple), st.booleans())
sheets = st.builds(Sheet, st.floats(1, 1000), st.floats(1, 1000), st.lists(
    layers, max_size=4).map(tuple))


def entity_by_entity(drawing: Drawing) -> bytes:
    """``drawing`` written through ezdxf's own API, every line an LWPOLYLINE entity: layers by
    role colour (off when hidden), a true colour unless black on a laser layer, the nearest
    line weight off laser layers, coordinates to 1 nm, sheets side by side 10 mm apart, the
    limits and extents the sheets'."""
    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    doc = ezdxf.new("R2004", setup=False)
    doc.units = ezdxf.units.MM
    doc.header["$INSUNITS"], doc.header["$MEASUREMENT"], doc.header["$LWDISPLAY"] = 4, 1, 1
    colours = {"cut": 1, "score": 5, "engrave": 7, "paint": 8, "label": 7, "guide": 9}
    dx = 0.0
    for n, sheet in enumerate(drawing.sheets):
        for layer in sheet.layers:
            name = re.sub(r'[<>/\\":;?*|=`]', "_",
                          layer.name + ("" if len(drawing.sheets) == 1 else f"-{n + 1}"))
            for shape in layer.shapes:
                if not shape.style.stroke:
                    continue
                if name not in doc.layers:
                    entry = doc.layers.add(name, color=colours[layer.role])
                    if not layer.visible:
                        entry.off()
                attribs = {"layer": name}
                laser = layer.role in ("cut", "score", "engrave")
                if not (laser and shape.style.stroke == "#000000"):
                    attribs["true_color"] = int(shape.style.stroke[1:], 16)
                if shape.style.stroke_width > 0 and not laser:
                    attribs["lineweight"] = min(VALID_DXF_LINEWEIGHTS, key=lambda w: abs(
                        w - 100 * shape.style.stroke_width))
                closed = isinstance(shape, Polygons)
                for xy in shape.rings() if closed else shape.lines():
                    msp = doc.modelspace()
                    msp.add_lwpolyline((np.round(xy + (dx, 0.0), 6) + 0.0).tolist(),
                                       close=closed, dxfattribs=attribs)
        dx += sheet.width + 10.0
    if drawing.sheets:  # limits and extents: the sheets, from the first one's corner
        size = (round(dx - 10.0, 6) + 0.0, round(max(s.height for s in drawing.sheets), 6) + 0.0)
        doc.modelspace().reset_extents((0, 0, 0), (*size, 0))
        doc.modelspace().reset_limits((0, 0), size)
        doc.active_layout().reset_limits((0, 0), size)
        doc.header["$EXTMIN"], doc.header["$EXTMAX"] = (0, 0, 0), (*size, 0)
    doc.classes.add_required_classes(doc.dxfversion)
    doc.classes.classes = dict(sorted(doc.classes.classes.items()))
    buf = io.StringIO()
    doc.write(buf)
    ezdxf.options.write_fixed_meta_data_for_testing = fixed
    comments = "".join(f"999\n{key}: {' '.join(value.split())}\n"
                       for key, value in [("title", drawing.title), *drawing.metadata])
    return doc.encode(comments + buf.getvalue())


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(sheets=st.lists(sheets, max_size=3), title=st.text(max_size=8))
def test_a_drawing_of_strokes_gets_ezdxfs_bytes(sheets, title):
    drawing = Drawing(tuple(sheets), clean(title), (("command", "weave-cut x"),))
    assert dxf.render(drawing) == entity_by_entity(drawing) == dxf_ezdxf.render(drawing)


def test_a_cut_file_is_written_without_ezdxf_and_reads_back():
    assert "ezdxf" not in modules_after(
        "import numpy as np\nfrom weavecut.export import dxf\n"
        "from weavecut.layout.drawing import Drawing, Layer, Polygons, Sheet, Style\n"
        "ring = Polygons(np.array([[0, 0], [1, 0], [1, 1.5]]), np.array([0, 3]))\n"
        "dxf.render(Drawing((Sheet(9, 9, (Layer('c', 'cut', (ring,)),)),)))")
    ring = Polygons(np.array([[0, 0], [1, 0], [1, 1.5]]), np.array([0, 3]), Style("#ff0000", 0))
    data = dxf.render(Drawing((Sheet(9, 9, (Layer("c", "cut", (ring,)),)),)))
    doc = ezdxf.read(io.StringIO(data.decode("cp1252")))
    (line,) = doc.modelspace().query("LWPOLYLINE")
    assert line.closed and line.get_points("xy") == [(0, 0), (1, 0), (1, 1.5)]
    assert line.dxf.layer == "c" and doc.layers.get("c").color == 1
    assert not doc.audit().has_errors


def test_text_and_fills_are_left_to_ezdxf():
    label = Layer("l", "label", (Text(1, 1, "x"),))
    filled = Layer("p", "paint", (Polygons(np.zeros((3, 2)), np.array([0, 3]),
                                           Style(None, 0, "#00ff00")),))
    for layer in (label, filled):
        drawing = Drawing((Sheet(9, 9, (layer,)),))
        assert not dxf_text.plain(drawing)
        assert dxf.render(drawing) == dxf_ezdxf.render(drawing)


def test_the_skeleton_is_what_ezdxf_writes_today():
    # after an ezdxf upgrade: python -m weavecut.export.dxf_ezdxf > .../dxf_skeleton.py
    with open(dxf_skeleton.__file__, encoding="utf-8") as f:
        assert f.read() == dxf_ezdxf.skeleton_source()


def test_line_weights_are_dxfs():
    assert dxf_text.LINEWEIGHTS == tuple(VALID_DXF_LINEWEIGHTS)


@settings(max_examples=200, deadline=None)
@given(text=st.text())
def test_characters_beyond_the_code_page_are_escaped_as_ezdxf_does(text):
    text = clean(text)
    assert dxf_text.encode(text) == ezdxf.new("R2004").encode(text)
