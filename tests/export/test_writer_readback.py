"""A small drawing with every kind of shape (a polygon with a hole, fills per polygon, open
lines, a hairline, rotated and anchored text, a hidden layer, two sheets), written as SVG and
DXF and read back by an XML parser and ezdxf: what a reader sees is what the Drawing says,
worked out here by hand from the SVG and DXF specifications."""

from __future__ import annotations

import functools
import io
import re
import xml.etree.ElementTree as ET

import ezdxf
import ezdxf.comments
import numpy as np
import pytest
import shapely

from weavecut.export import dxf, svg
from weavecut.layout.drawing import (
    Drawing, Layer, Sheet, Style, Text, polygons_from_shapely, polylines_from_lines,
)

NS = "{http://www.w3.org/2000/svg}"
INK = "{http://www.inkscape.org/namespaces/inkscape}"
RED, TEAL, SAND = "#ff0000", "#127a7a", "#e0c080"

FRAME = shapely.Polygon([(10, 10), (50, 10), (50, 40), (10, 40)],
                        [[(20, 20), (30, 20), (30, 30), (20, 30)]])
SQUARE = shapely.box(60, 10, 70, 20)
TRIANGLE = shapely.Polygon([(75, 10), (85, 10), (75, 25)])


def drawing() -> Drawing:
    cut = Layer("outline", "cut", (polygons_from_shapely([FRAME], Style(RED, 0.1)),))
    tiles = Layer("tiles", "paint", (polygons_from_shapely(
        [SQUARE, TRIANGLE, FRAME], Style(None, 0.0, None, 0.5), fills=[TEAL, SAND, TEAL]),))
    lines = Layer("folds", "score", (polylines_from_lines(
        [[(0, 0), (5, 5), (10, 0)], [(1, 60), (2, 70)]], Style("#0000ff", 0.0)),))
    label = Layer("labels", "label", (Text(40, 50, "A1", 4.2, "middle", 30.0, "#123456"),
                                      Text(5, 70, "tab", 2.1, "end")))
    hidden = Layer("guide lines", "guide", (polylines_from_lines([[(0, 1), (9, 1)]]),),
                   visible=False)
    first = Sheet(100, 80, (cut, tiles, lines, label, hidden))
    second = Sheet(40, 30, (Layer("outline", "cut", (polygons_from_shapely(
        [shapely.box(1, 2, 11, 12)], Style(RED, 0.1)),)),), "back")
    return Drawing((first, second), "two sheets", (("generator", "test"), ("command", "x")))


def one_sheet() -> Drawing:
    d = drawing()
    return Drawing(d.sheets[:1], d.title, d.metadata)


def subpaths(d: str) -> list[np.ndarray]:
    """Every 'M x,y x,y ... [Z]' part of a path's d, as points."""
    return [np.array([[float(v) for v in p.split(",")] for p in part.rstrip("Z").split()])
            for part in d.split("M")[1:]]


def layers(root) -> dict[str, ET.Element]:
    return {g.get(f"{INK}label"): g for g in root.iter(f"{NS}g")
            if g.get(f"{INK}groupmode") == "layer"}


def test_svg_one_sheet_reads_back_as_drawn():
    root = ET.fromstring(svg.render(one_sheet()))
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == \
        ("100mm", "80mm", "0 0 100 80")
    assert root.find(f"{NS}title").text == "two sheets"
    assert root.find(f"{NS}desc").text == "generator: test; command: x"
    g = layers(root)
    assert list(g) == ["outline", "tiles", "folds", "labels", "guide lines"]
    assert [g[k].get("id") for k in g] == ["cut-outline", "paint-tiles", "score-folds",
                                           "label-labels", "guide-guide-lines"]
    assert g["guide lines"].get("style") == "display:none"
    assert all(g[k].get("style") is None for k in list(g)[:-1])

    # the cut: one path, exterior and hole as closed sub-paths, y flipped (80 - y)
    (cut,) = g["outline"].iter(f"{NS}path")
    assert cut.get("d").count("Z") == 2
    outer, hole = subpaths(cut.get("d"))
    assert shapely.Polygon(outer, [hole]).equals(
        shapely.Polygon([(x, 80 - y) for x, y in FRAME.exterior.coords],
                        [[(x, 80 - y) for x, y in FRAME.interiors[0].coords]]))
    assert (cut.get("fill"), cut.get("stroke"), cut.get("stroke-width"),
            cut.get("stroke-linejoin")) == ("none", RED, "0.1", "round")
    assert cut.get("fill-rule") is None and cut.get("opacity") is None

    # fills: one path per colour (sorted), even-odd so the frame's hole stays open
    fills = list(g["tiles"].iter(f"{NS}path"))
    assert [p.get("fill") for p in fills] == sorted([TEAL, SAND])
    for p in fills:
        assert (p.get("fill-rule"), p.get("opacity"), p.get("stroke")) == \
            ("evenodd", "0.5", "none")
        assert p.get("stroke-width") is None
    teal, sand = (shapely.MultiPolygon([shapely.Polygon(r) for r in subpaths(p.get("d"))])
                  for p in fills)
    flip = lambda geom: shapely.transform(geom, lambda xy: xy * [1, -1] + [0, 80])  # noqa: E731
    assert sand.equals(flip(TRIANGLE))
    assert functools.reduce(shapely.symmetric_difference, teal.geoms).equals(
        flip(shapely.union(SQUARE, FRAME)))

    # open lines stay open; a hairline is a quarter millimetre wide, a width every viewer
    # draws (no vector-effect, which librsvg 2.54 ignores)
    (fold,) = g["folds"].iter(f"{NS}path")
    assert "Z" not in fold.get("d") and fold.get("fill") == "none"
    assert (fold.get("stroke-width"), fold.get("vector-effect"), fold.get("style")) == \
        ("0.25", None, None)
    assert cut.get("vector-effect") is None  # a stroke of a width keeps it
    a, b = subpaths(fold.get("d"))
    np.testing.assert_array_equal(a, [[0, 80], [5, 75], [10, 80]])
    np.testing.assert_array_equal(b, [[1, 20], [2, 10]])

    # text at its point (y flipped), cap height / 0.7 as font size, anchor, turned clockwise
    # in SVG's y-down frame by the angle the model turns counter-clockwise
    t1, t2 = g["labels"].iter(f"{NS}text")
    assert (t1.text, t1.get("x"), t1.get("y"), t1.get("fill"), t1.get("text-anchor")) == \
        ("A1", "40", "30", "#123456", "middle")
    assert float(t1.get("font-size")) == pytest.approx(6.0)
    assert re.fullmatch(r"rotate\(-30(\.0)?,\s*40,\s*30\)", t1.get("transform"))
    assert (t2.get("x"), t2.get("y"), t2.get("text-anchor"), t2.get("transform")) == \
        ("5", "10", "end", None)
    assert float(t2.get("font-size")) == pytest.approx(3.0)


def test_svg_sheets_side_by_side_bottom_aligned():
    root = ET.fromstring(svg.render(drawing()))
    # 100 + 10 (gap) + 40 wide, as high as the highest sheet
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == \
        ("150mm", "80mm", "0 0 150 80")
    sheets = [g for g in root if g.tag == f"{NS}g"]
    assert [s.get(f"{INK}label") for s in sheets] == ["sheet 1", "back"]
    assert [s.get("id") for s in sheets] == ["sheet-1", "sheet-2"]
    shifts = [tuple(map(float, re.findall(r"[-\d.]+", s.get("transform")))) for s in sheets]
    assert shifts == [(0.0, 0.0), (110.0, 50.0)]  # the lower sheet sits on the same floor
    frames = [s.find(f"{NS}rect") for s in sheets]
    assert [(f.get("width"), f.get("height"), f.get("fill")) for f in frames] == \
        [("100", "80", "none"), ("40", "30", "none")]
    (square,) = subpaths(layers(sheets[1])["outline"].find(f"{NS}path").get("d"))
    # within its own 30 mm high sheet: y flipped as 30 - y
    assert shapely.Polygon(square).equals(shapely.box(1, 30 - 12, 11, 30 - 2))


def read_dxf(data: bytes):
    return ezdxf.read(io.StringIO(data.decode("utf-8")))


def test_dxf_reads_back_as_drawn():
    doc = read_dxf(dxf.render(drawing()))
    assert len(doc.audit().errors) == 0
    msp = doc.modelspace()
    names = {layer.dxf.name: layer for layer in doc.layers}
    # role colours for laser software; fill layers in their own colour; hidden stays off
    assert names["outline-1"].color == 1 and names["outline-2"].color == 1
    assert names["folds-1"].color == 5 and names["labels-1"].color == 7
    assert names["guide lines-1"].is_off() and not names["folds-1"].is_off()
    assert names["tiles-1-127a7a"].rgb == (0x12, 0x7A, 0x7A)
    assert names["tiles-1-e0c080"].rgb == (0xE0, 0xC0, 0x80)

    cuts = msp.query('LWPOLYLINE[layer=="outline-1"]')
    assert [e.closed for e in cuts] == [True, True]
    assert shapely.Polygon(cuts[0].get_points("xy"), [cuts[1].get_points("xy")]).equals(FRAME)
    # pure red on a cut layer is a true colour; the second sheet is 110 mm to the right
    assert all(e.rgb == (255, 0, 0) for e in cuts)
    (back,) = msp.query('LWPOLYLINE[layer=="outline-2"]')
    assert shapely.Polygon(back.get_points("xy")).equals(shapely.box(111, 2, 121, 12))

    hatches = {h.dxf.layer: h for h in msp.query("HATCH")}
    assert set(hatches) == {"tiles-1-127a7a", "tiles-1-e0c080"}
    teal = hatches["tiles-1-127a7a"]
    assert teal.rgb == (0x12, 0x7A, 0x7A) and teal.dxf.solid_fill == 1
    assert len(teal.paths) == 3  # the square, the frame and its hole (odd parity)
    assert teal.dxf.hatch_style == 0

    folds = msp.query('LWPOLYLINE[layer=="folds-1"]')
    assert [e.closed for e in folds] == [False, False]
    np.testing.assert_array_equal(folds[0].get_points("xy"), [(0, 0), (5, 5), (10, 0)])
    assert all(e.rgb == (0, 0, 255) for e in folds)  # blue is not black: a true colour

    (a1,) = [t for t in msp.query("TEXT") if t.dxf.text == "A1"]
    assert (a1.dxf.height, a1.dxf.rotation) == (4.2, 30.0)
    assert tuple(a1.get_placement()[1])[:2] == (40, 50) and a1.rgb == (0x12, 0x34, 0x56)
    (tab,) = [t for t in msp.query("TEXT") if t.dxf.text == "tab"]
    assert tab.get_placement()[0].name == "BOTTOM_RIGHT"
    assert tab.dxf.layer == "labels-1"

    text = io.StringIO(dxf.render(drawing()).decode())
    comments = [tag.value for tag in ezdxf.comments.from_stream(text)]
    assert comments[:3] == ["title: two sheets", "generator: test", "command: x"]


def test_dxf_black_on_a_laser_layer_stays_bylayer():
    black = Layer("cut", "cut", (polylines_from_lines([[(0, 0), (1, 1)]], Style("#000000", 0.3)),))
    drawn = Layer("ink", "paint", (polylines_from_lines([[(0, 0), (1, 1)]],
                                                        Style("#000000", 0.3)),))
    doc = read_dxf(dxf.render(Drawing((Sheet(10, 10, (black, drawn)),))))
    (cut,) = doc.modelspace().query('LWPOLYLINE[layer=="cut"]')
    (ink,) = doc.modelspace().query('LWPOLYLINE[layer=="ink"]')
    assert cut.rgb is None and cut.dxf.lineweight == -1  # BYLAYER, hairline
    assert ink.rgb == (0, 0, 0) and ink.dxf.lineweight == 30  # 0.3 mm
