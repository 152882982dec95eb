"""SVG details a cutter or Inkscape depends on, read back with an XML parser: the page in mm
whatever its size (also beyond 100 m, where short number formats lose digits), coordinates to
the micrometre, zero written without a sign, open lines never filled, fills even-odd, opacity
only where it is not 1, and every sheet of several in its own frame."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.export import svg
from weavecut.layout.drawing import (
    Drawing, Layer, Sheet, Style, Text, polygons_from_rings, polygons_from_shapely,
    polylines_from_lines,
)

NS = "{http://www.w3.org/2000/svg}"
INK = "{http://www.inkscape.org/namespaces/inkscape}"


def paths(root) -> list[ET.Element]:
    return list(root.iter(f"{NS}path"))


def numbers(d: str) -> np.ndarray:
    return np.array([float(v) for v in re.findall(r"[-+]?[\d.]+(?:e[-+]?\d+)?", d)])


@settings(max_examples=30, deadline=None)
@given(x=st.floats(0, 3e5), y=st.floats(0, 3e5), width=st.floats(1, 4e5))
def test_every_coordinate_reads_back_to_the_micrometre(x, y, width):
    # a sheet up to 400 m, a point anywhere on it: the written numbers are the point to
    # within half a micrometre (3 decimals), however many digits they need
    height = max(width, y + 1)
    lines = Layer("l", "cut", (polylines_from_lines([[(x, y), (x + 0.5, y)]]),))
    root = ET.fromstring(svg.render(Drawing((Sheet(width, height, (lines,)),))))
    (path,) = paths(root)
    got = numbers(path.get("d")).reshape(-1, 2)
    np.testing.assert_allclose(got, [[x, height - y], [x + 0.5, height - y]], atol=5e-4 + 1e-9)
    assert float(root.get("width").removesuffix("mm")) == pytest.approx(width, abs=5e-4)
    assert float(root.get("height").removesuffix("mm")) == pytest.approx(height, abs=5e-4)
    assert root.get("width").endswith("mm") and root.get("height").endswith("mm")
    assert numbers(root.get("viewBox")) == pytest.approx([0, 0, width, height], abs=5e-4)


@pytest.mark.parametrize("x", [100000.5, 123456.789, 99999.5])
def test_large_coordinates_keep_their_decimals(x):
    lines = Layer("l", "cut", (polylines_from_lines([[(x, 1.25), (x + 1, 2.0)]]),))
    root = ET.fromstring(svg.render(Drawing((Sheet(x + 2.25, 10, (lines,)),))))
    (path,) = paths(root)
    np.testing.assert_allclose(numbers(path.get("d")), [x, 8.75, x + 1, 8], atol=5e-4)
    assert float(root.get("width")[:-2]) == pytest.approx(x + 2.25, abs=5e-4)
    text = Layer("t", "label", (Text(x, 1.0, "far", 2.0),))
    (t,) = ET.fromstring(svg.render(Drawing((Sheet(x + 10, 10, (text,)),)))).iter(f"{NS}text")
    assert float(t.get("x")) == pytest.approx(x, abs=5e-4)


def test_zero_is_written_without_a_sign():
    # a point a hair below zero rounds to 0, written "0" (not "-0": the same drawing and its
    # mirror image give the same text there)
    lines = Layer("l", "cut", (polylines_from_lines([[(-1e-5, 10 + 1e-5), (5, 5)]]),))
    root = ET.fromstring(svg.render(Drawing((Sheet(10, 10, (lines,)),))))
    (path,) = paths(root)
    assert path.get("d").startswith("M0,0 ")
    assert svg._n(-1e-5) == "0"


def test_open_lines_are_never_filled_and_closed_rings_are_even_odd():
    style = Style("#ff0000", 0.25, "#00ff00", 0.4)
    layer = Layer("x", "paint", (
        polylines_from_lines([[(0, 0), (5, 5), (10, 0)]], style),
        polygons_from_shapely([shapely.Polygon([(0, 0), (9, 0), (9, 9), (0, 9)],
                                               [[(3, 3), (6, 3), (6, 6), (3, 6)]])], style)))
    line, ring = paths(ET.fromstring(svg.render(Drawing((Sheet(10, 10, (layer,)),)))))
    assert line.get("fill") == "none" and line.get("fill-rule") is None
    assert ring.get("fill") == "#00ff00" and ring.get("fill-rule") == "evenodd"
    for p in (line, ring):
        assert (p.get("stroke"), p.get("stroke-width"), p.get("stroke-linejoin"),
                p.get("opacity")) == ("#ff0000", "0.25", "round", "0.4")
    assert ring.get("d").count("M") == 2 and ring.get("d").count("Z") == 2


def test_unstroked_unfilled_and_opaque_shapes_say_so():
    layer = Layer("x", "paint", (
        polygons_from_rings([np.array([[0.0, 0], [1, 0], [0, 1]])], Style(None, 0.3, None)),
        polygons_from_rings([np.array([[0.0, 0], [1, 0], [0, 1]])],
                            Style(None, 0.3, "#0000ff", 1.0))))
    bare, filled = paths(ET.fromstring(svg.render(Drawing((Sheet(10, 10, (layer,)),)))))
    assert (bare.get("fill"), bare.get("stroke")) == ("none", "none")
    assert bare.get("stroke-width") is None and bare.get("stroke-linejoin") is None
    assert bare.get("fill-rule") is None
    assert filled.get("fill") == "#0000ff" and filled.get("opacity") is None  # 1: not written


def test_text_size_angle_and_position():
    label = Layer("l", "label", (Text(12.5, 3.25, "Ab", 3.5, "start", 45.0, "#00ff00"),))
    (t,) = ET.fromstring(svg.render(Drawing((Sheet(20, 10, (label,)),)))).iter(f"{NS}text")
    # cap height 3.5 mm is a DejaVu font size of 3.5 / 0.7 = 5 mm; y flipped: 10 - 3.25
    assert (t.get("x"), t.get("y"), t.get("font-size"), t.get("text-anchor"), t.get("fill")) == \
        ("12.5", "6.75", "5", "start", "#00ff00")
    assert t.get("font-family").startswith("DejaVu Sans")
    # the model turns counter-clockwise, SVG (y down) clockwise: -45 about the insertion point
    angle, cx, cy = numbers(t.get("transform"))
    assert (angle, cx, cy) == (-45, 12.5, 6.75)


def test_without_metadata_no_description():
    root = ET.fromstring(svg.render(Drawing((Sheet(10, 10),), "alone")))
    assert root.find(f"{NS}title").text == "alone"
    assert root.find(f"{NS}desc") is None


def test_several_sheets_each_framed_named_and_with_hidden_layers_hidden():
    hidden = Layer("help", "guide", (polylines_from_lines([[(0, 0), (1, 1)]]),), visible=False)
    shown = Layer("cut", "cut", (polylines_from_lines([[(0, 0), (1, 1)]]),))
    sheets = (Sheet(30, 20, (shown,), "front"), Sheet(15, 25, (shown, hidden)),
              Sheet(5, 5, ()))
    root = ET.fromstring(svg.render(Drawing(sheets)))
    assert (root.get("width"), root.get("height")) == ("70mm", "25mm")  # 30+15+5 + 2 gaps
    groups = [g for g in root if g.tag == f"{NS}g"]
    assert [g.get(f"{INK}label") for g in groups] == ["front", "sheet 2", "sheet 3"]
    assert all(g.get(f"{INK}groupmode") == "layer" for g in groups)
    shifts = [numbers(g.get("transform")).tolist() for g in groups]
    assert shifts == [[0, 5], [40, 0], [65, 20]]  # side by side, standing on one floor
    for g, sheet in zip(groups, sheets):
        frame = g.find(f"{NS}rect")
        assert (float(frame.get("width")), float(frame.get("height"))) == \
            (sheet.width, sheet.height)
        assert (frame.get("fill"), frame.get("stroke"), frame.get("stroke-width")) == \
            ("none", "#cccccc", "0.3")
        assert float(frame.get("x", 0)) == 0 and float(frame.get("y", 0)) == 0  # at its sheet's corner
    inner = [child for child in groups[1] if child.tag == f"{NS}g"]
    assert [(g.get(f"{INK}label"), g.get("style")) for g in inner] == \
        [("cut", None), ("help", "display:none")]


def test_several_polygons_in_one_path_and_strokes_around_each_fill():
    two = [shapely.box(1, 1, 3, 3), shapely.box(5, 1, 7, 3)]
    plain = Layer("cut", "cut", (polygons_from_shapely(two, Style("#ff0000", 0.2)),))
    filled = Layer("tiles", "paint", (polygons_from_shapely(
        two, Style("#0000ff", 0.4), fills=["#00ff00", "#ffff00"]),))
    root = ET.fromstring(svg.render(Drawing((Sheet(10, 10, (plain, filled)),))))
    cut, green, yellow = paths(root)
    # both squares, y flipped, in one path
    assert sorted(map(tuple, numbers(cut.get("d")).reshape(-1, 2).tolist())) == \
        sorted([(1, 9), (3, 9), (3, 7), (1, 7), (5, 9), (7, 9), (7, 7), (5, 7)])
    assert cut.get("d").count("M") == 2 and cut.get("d").count("Z") == 2
    # path data a viewer reads: closed subpaths of numbers and nothing else between them
    number = r"-?\d+(\.\d+)?"
    ring = rf"M{number},{number}( {number},{number})*Z"
    assert all(re.fullmatch(rf"({ring})+", p.get("d")) for p in (cut, green, yellow))
    for p, fill in [(green, "#00ff00"), (yellow, "#ffff00")]:
        assert (p.get("fill"), p.get("stroke"), p.get("stroke-width")) == \
            (fill, "#0000ff", "0.4")


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(*[st.one_of(st.floats(-1e6, 1e6), st.integers(-10**6, 10**6),
                                      st.sampled_from([0.0, -0.0, 4e-4, -6e-4, 0.0005, 1e15,
                                                       -2.5e16, 1e17]))] * 2),
                max_size=20), st.floats(0, 1e5))
def test_points_of_a_path_are_written_number_by_number_as_decimal_writes_them(xy, height):
    # the path's points are formatted all at once; each number is what _decimal makes of it
    coords = np.array(xy, dtype=float).reshape(-1, 2)
    flipped = np.round(np.column_stack([coords[:, 0], height - coords[:, 1]]), 3) + 0.0
    expected = [f"{svg._decimal(x)},{svg._decimal(y)}" for x, y in flipped.tolist()]
    assert svg._points(coords, height) == expected
