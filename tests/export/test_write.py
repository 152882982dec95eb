"""``export.write`` and ``export.render``: the format follows the file's suffix (any case, with
or without the dot), each file is what its format's own reader accepts, text is cleaned of what
no format can hold, and the written file is noted with its Drawing."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import ezdxf
import pytest
from PIL import Image

from weavecut import export
from weavecut.errors import ExportError
from weavecut.fileio import recording
from weavecut.layout.drawing import Drawing, Layer, Sheet, Text

from tests.test_readback import pdfinfo


def drawing() -> Drawing:
    label = Layer("labels", "label", (Text(10, 10, "bad\x01text", 3.0),))
    return Drawing((Sheet(40, 30, (label,)),), "title\x02", (("command", "x\x7fy"),))


def test_formats_are_the_writer_modules():
    assert export.formats() == ["dxf", "pdf", "png", "svg"]
    for fmt in export.formats():
        assert export.render(drawing(), fmt)


@pytest.mark.parametrize("fmt", ["SVG", ".svg", "Svg"])
def test_render_takes_the_format_in_any_case_with_or_without_the_dot(fmt):
    root = ET.fromstring(export.render(drawing(), fmt))
    assert root.tag == "{http://www.w3.org/2000/svg}svg"


@pytest.mark.parametrize("fmt", ["jpg", "", "model3d"])
def test_unknown_format_is_refused_in_one_line(fmt):
    with pytest.raises(ExportError) as err:
        export.render(drawing(), fmt)
    assert str(err.value) == \
        f"unknown output format {fmt!r}; choose one of ['dxf', 'pdf', 'png', 'svg']"


def test_render_cleans_text_no_format_can_hold():
    root = ET.fromstring(export.render(drawing(), "svg"))  # XML 1.0 has no \x01
    texts = [t.text for t in root.iter("{http://www.w3.org/2000/svg}text")]
    assert texts == ["bad\ufffdtext"]
    assert root.find("{http://www.w3.org/2000/svg}title").text == "title\ufffd"
    assert root.find("{http://www.w3.org/2000/svg}desc").text == "command: x\ufffdy"


def test_write_picks_the_writer_by_suffix_and_notes_the_file(tmp_path):
    with recording() as record:
        for name in ("a.svg", "b.DXF", "c.pdf", "d.png"):
            export.write(drawing(), tmp_path / name)
        export.write(drawing(), tmp_path / "e.out", "svg")  # an explicit format wins
    assert sorted(p.name for p in tmp_path.iterdir()) == \
        ["a.svg", "b.DXF", "c.pdf", "d.png", "e.out"]  # no temporary file left
    assert ET.parse(tmp_path / "a.svg").getroot().get("width") == "40mm"
    assert ezdxf.readfile(tmp_path / "b.DXF").header["$INSUNITS"] == 4
    assert pdfinfo(tmp_path / "c.pdf")["Pages"] == "1"
    with Image.open(tmp_path / "d.png") as im:
        assert im.format == "PNG"
    assert ET.parse(tmp_path / "e.out").getroot().get("height") == "30mm"
    assert list(record.files) == [(tmp_path / n).absolute() for n in
                                  ("a.svg", "b.DXF", "c.pdf", "d.png", "e.out")]
    assert all(d.title == "title\x02" for d in record.files.values())  # the Drawing as given


def test_write_in_an_unknown_format_leaves_no_file(tmp_path):
    with pytest.raises(ExportError, match="unknown output format 'txt'"):
        export.write(drawing(), tmp_path / "a.txt")
    assert not list(tmp_path.iterdir())
