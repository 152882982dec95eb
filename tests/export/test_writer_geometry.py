"""Writers put every point where the Drawing says, in millimetres, read back by real readers:
an XML parser for SVG (units, viewBox, y axis pointing up in the model and down in SVG),
ezdxf for DXF (units, later sheets shifted to the right of earlier ones)."""

from __future__ import annotations

import io
import re
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.export import dxf, svg
from weavecut.layout.drawing import Drawing, Layer, Sheet, Style, polygons_from_rings

SVG_NS = "{http://www.w3.org/2000/svg}"


def triangle_sheet(width, height, x, y, name=""):
    """A sheet holding one small triangle with its first corner at (x, y) (model units, y up)."""
    ring = np.array([[x, y], [x + 5.0, y], [x, y + 3.0]])
    cut = Layer("outline", "cut", (polygons_from_rings([ring], Style("#ff0000", 0.1)),))
    return Sheet(width, height, (cut,), name)


def svg_path_points(root) -> list[np.ndarray]:
    """Every path's points, in SVG user units (y down)."""
    out = []
    for path in root.iter(f"{SVG_NS}path"):
        numbers = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", path.get("d"))]
        out.append(np.array(numbers).reshape(-1, 2))
    return out


sizes = st.floats(20, 900, allow_nan=False)


@settings(max_examples=25, deadline=None)
@given(width=sizes, height=sizes, fx=st.floats(0, 0.7), fy=st.floats(0, 0.7))
def test_svg_is_in_mm_and_flips_y(width, height, fx, fy):
    x, y = fx * width, fy * height
    root = ET.fromstring(svg.render(Drawing((triangle_sheet(width, height, x, y),))))
    assert root.get("width") == f"{svg._n(width)}mm"
    assert root.get("height") == f"{svg._n(height)}mm"
    vb = [float(v) for v in root.get("viewBox").split()]
    assert vb == pytest.approx([0, 0, width, height], abs=1e-3)
    (points,) = svg_path_points(root)
    # model y points up, SVG y points down: the corner at model (x, y) is at (x, H - y)
    assert points[0] == pytest.approx([x, height - y], abs=2e-3)
    assert points[2] == pytest.approx([x, height - y - 3.0], abs=2e-3)


def read_dxf(data: bytes):
    return ezdxf.read(io.StringIO(data.decode("utf-8")))


def test_dxf_units_and_later_sheets_shift_right():
    sheets = (triangle_sheet(100, 80, 10, 20), triangle_sheet(60, 50, 1, 2),
              triangle_sheet(30, 40, 3, 4))
    doc = read_dxf(dxf.render(Drawing(sheets)))
    assert doc.header["$INSUNITS"] == 4
    firsts = sorted(tuple(np.round(e.get_points("xy")[0], 6)) for e in
                    doc.modelspace().query("LWPOLYLINE"))
    gap = 10.0
    expected = sorted([(10.0, 20.0), (100 + gap + 1.0, 2.0), (100 + 60 + 2 * gap + 3.0, 4.0)])
    np.testing.assert_allclose(firsts, expected, atol=1e-6)
    for e in doc.modelspace().query("LWPOLYLINE"):
        assert e.closed
    assert len(doc.audit().errors) == 0
