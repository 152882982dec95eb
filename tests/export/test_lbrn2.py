"""The LightBurn writer against LightBurn's own files and an XML parser: it writes only the
elements and attributes LightBurn's files hold (tests/export/lightburn_reference), every point
where the Drawing says to 1e-4 mm, y up, open polylines open and rings closed, the layers in
the order they must run, the same bytes every time. (Read back by lbrnts and held against the
DXF: tests/test_lightburn_readback.py.)"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut import __version__, export
from weavecut.errors import ExportError
from weavecut.export import lbrn2
from weavecut.layout.drawing import (Drawing, Layer, Sheet, Style, Text, polygons_from_rings,
                                     polylines_from_lines)
from weavecut.layout.lasersetup import LaserJob, Operation, laser_job, material

REFERENCE = Path(__file__).parent / "lightburn_reference"
JOB = LaserJob({"cut": Operation(12.5, 90.0, 2), "score": Operation(100.0, 20.0),
                "engrave": Operation(150.0, 15.0)}, "test board", "as drawn")
RED, BLUE, BLACK = Style("#ff0000", 0.0), Style("#0000ff", 0.0), Style("#000000", 0.0)
VERTEX = re.compile(r"V(-?\d+(?:\.\d+)?) (-?\d+(?:\.\d+)?)c0x1c1x1")


def kinds(root: ET.Element) -> tuple[set, set]:
    """(parent tag, tag) of every element and (tag, attribute) of every attribute."""
    pairs, attributes = {(None, root.tag)}, set()
    for parent in root.iter():
        attributes |= {(parent.tag, a) for a in parent.attrib}
        pairs |= {(parent.tag, child.tag) for child in parent}
    return pairs, attributes


def sample() -> Drawing:
    """A sheet with every laser role, two cut layers and a layer that is not for the laser."""
    layers = (Layer("outer", "cut", (polygons_from_rings([[(5, 5), (95, 5), (95, 55)]], RED),)),
              Layer("paint", "paint", (polygons_from_rings([[(0, 0), (1, 0), (1, 1)]]),)),
              Layer("inner", "cut", (polygons_from_rings([[(20, 20), (30, 20), (30, 30)]],
                                                         RED),)),
              Layer("numbers", "engrave", (polylines_from_lines([[(40, 40), (41, 42)]],
                                                                BLACK),)),
              Layer("ring", "score", (polylines_from_lines([[(10, 10), (12, 10), (12, 12),
                                                              (10, 10)]], BLUE),)))
    return Drawing((Sheet(100.0, 60.0, layers, "s"),), "a sample", (("command", "x & <y>"),))


def parsed(drawing: Drawing, job: LaserJob = JOB) -> ET.Element:
    return ET.fromstring(export.render(drawing, "lbrn2", job))


def test_writes_only_what_lightburn_writes():
    theirs = [kinds(ET.parse(p).getroot()) for p in sorted(REFERENCE.glob("*.lbrn2"))]
    assert len(theirs) == 2
    pairs, attributes = kinds(parsed(sample()))
    assert pairs <= set().union(*(p for p, _ in theirs))
    assert attributes <= set().union(*(a for _, a in theirs))
    root = parsed(sample())
    assert root.get("FormatVersion") == "1"  # .lbrn2, as the references (0 is .lbrn)
    for path in root.iter("Shape"):
        assert path.get("Type") == "Path" and path.find("XForm").text == "1 0 0 1 0 0"
        assert VERTEX.sub("", path.find("VertList").text) == ""


def test_layers_run_engraving_and_scoring_first_inner_cuts_before_the_outline():
    root = parsed(sample())
    settings_ = [{c.tag: c.get("Value") for c in s} for s in root.iter("CutSetting")]
    assert [s["name"] for s in settings_] == ["numbers", "ring", "outer", "inner"]
    assert [int(s["priority"]) for s in settings_] == [0, 1, 2, 3]
    # LightBurn's layer numbers: 00 black, 01 blue, 02 red (the roles' colours), then 03
    assert [int(s["index"]) for s in settings_] == [0, 1, 2, 3]
    assert {s.get("type") for s in root.iter("CutSetting")} == {"Cut"}
    by_name = {s["name"]: s for s in settings_}
    assert (by_name["inner"]["speed"], by_name["inner"]["maxPower"],
            by_name["inner"]["minPower"], by_name["inner"]["numPasses"]) == ("12.5", "90", "90",
                                                                            "2")
    assert (by_name["ring"]["speed"], by_name["numbers"]["maxPower"]) == ("100", "15")
    assert {p.get("Value") for p in root.find("UIPrefs")} == {"0", "1"}
    assert root.find("UIPrefs/Optimize_ByPriority").get("Value") == "1"
    assert root.find("UIPrefs/Optimize_InnerToOuter").get("Value") == "1"


def test_a_returning_polyline_is_closed_an_open_one_lists_its_lines():
    root = parsed(sample())
    index = {s.find("name").get("Value"): s.find("index").get("Value")
             for s in root.iter("CutSetting")}
    shapes = {s.get("CutIndex"): s for s in root.iter("Shape")}
    ring = shapes[index["ring"]]  # (10,10) (12,10) (12,12) back to (10,10)
    assert ring.find("PrimList").text == "LineClosed"
    assert len(VERTEX.findall(ring.find("VertList").text)) == 3
    assert shapes[index["numbers"]].find("PrimList").text == "L0 1"
    assert "paint" not in index and len(shapes) == 4  # not a laser layer


def test_the_note_names_weave_cut_the_command_the_sheet_and_every_layer():
    notes = parsed(sample()).find("Notes")
    text = notes.get("Notes")
    assert notes.get("ShowOnLoad") == "1"
    assert f"weave-cut {__version__}" in text and "command: x & <y>" in text
    assert "sheet: 100 x 60 mm" in text and "material: test board" in text
    assert "C02 outer (cut, 1 path): 12.5 mm/s, 90 % power, 2 passes" in text.split(" | ")


def test_material_presets_give_the_layers_their_settings():
    mat = material("poplar-3mm")
    job = laser_job(mat)
    assert job.operation("cut") == Operation(mat["cut_speed"], 100.0, 1)
    assert job.operation("engrave") == Operation(150.0, 15.0, 1)
    root = parsed(sample(), job)
    cut = [s for s in root.iter("CutSetting") if s.find("name").get("Value") == "outer"][0]
    assert cut.find("speed").get("Value") == "20"


coordinate = st.floats(-500, 1500, allow_nan=False).map(lambda v: round(v, 6))


@settings(max_examples=40, deadline=None)
@given(lines=st.lists(st.lists(st.tuples(coordinate, coordinate), min_size=2, max_size=8),
                      min_size=1, max_size=4),
       rings=st.lists(st.lists(st.tuples(coordinate, coordinate), min_size=3, max_size=8),
                      min_size=1, max_size=4))
def test_every_point_where_the_drawing_says(lines, rings):
    layers = (Layer("r", "cut", (polygons_from_rings(rings, RED),)),
              Layer("l", "engrave", (polylines_from_lines(lines, BLACK),)))
    root = parsed(Drawing((Sheet(2000.0, 2000.0, layers),)))
    shapes = list(root.iter("Shape"))
    expected = []  # the engraving runs first, then the cut
    for line in lines:  # a polyline that returns to its start is written as a ring
        xy = np.round(np.array(line), 4)
        back = len(xy) > 2 and (xy[0] == xy[-1]).all()
        expected.append((np.array(line)[:-1] if back else np.array(line), back))
    expected += [(np.array(r), True) for r in rings]
    assert len(shapes) == len(expected)
    for shape, (xy, closed) in zip(shapes, expected):
        got = np.array([[float(x), float(y)] for x, y in
                        VERTEX.findall(shape.find("VertList").text)])
        assert got.shape == xy.shape and np.abs(got - xy).max() <= 0.5e-4 + 1e-9
        prims = shape.find("PrimList").text
        assert prims == ("LineClosed" if closed and len(xy) >= 3 else
                         "".join(f"L{i} {i + 1}" for i in range(len(xy) - 1)))


def test_same_bytes_every_time_and_no_clock():
    first = export.render(sample(), "lbrn2", JOB)
    assert first == export.render(sample(), "lbrn2", JOB)
    assert not re.search(rb"20\d\d-\d\d-\d\d|\d\d:\d\d:\d\d", first)
    assert b"e-0" not in first and b"e+" not in first  # fixed point only


def test_refusals():
    with pytest.raises(ExportError, match="needs the laser's settings"):
        export.render(sample(), "lbrn2")
    two = Drawing(sample().sheets * 2, "two")
    with pytest.raises(ExportError, match="one sheet"):
        export.render(two, "lbrn2", JOB)
    text = Drawing((Sheet(10, 10, (Layer("t", "engrave", (Text(1, 1, "7"),)),)),))
    with pytest.raises(ExportError, match="single strokes"):
        export.render(text, "lbrn2", JOB)
    assert "lbrn2" not in export.formats()  # never offered as a picture format


def test_decimals():
    assert [lbrn2._decimal(v) for v in (0.0, -0.0, 12.5, -3.25, 1234567.1234, 1e-5)] == \
        ["0", "0", "12.5", "-3.25", "1234567.1234", "0"]
