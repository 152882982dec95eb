"""An SVG read back by an XML parser, against the Drawing it was written from."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from weavecut.layout.drawing import Drawing, Polygons, Polylines, Raster, Text

SVG_NS = "{http://www.w3.org/2000/svg}"
LABEL = "{http://www.inkscape.org/namespaces/inkscape}label"
POINT = re.compile(r"-?\d+(?:\.\d+)?(?:e-?\d+)?,-?\d+(?:\.\d+)?(?:e-?\d+)?")


def assert_svg_shows(drawing: Drawing, data: bytes) -> None:
    """Every sheet and layer of ``drawing`` is an Inkscape layer (in order), every text is a
    <text> with its string, every point of its polygons and polylines is in a path, and every
    picture is an <image> of its size."""
    root = ET.fromstring(data)
    assert root.get("width").endswith("mm") and root.get("height").endswith("mm")
    many = len(drawing.sheets) > 1
    labels, shapes = [], []
    for n, sheet in enumerate(drawing.sheets if many else drawing.sheets[:1]):
        labels += [sheet.name or f"sheet {n + 1}"] if many else []
        labels += [layer.name for layer in sheet.layers]
        shapes += [s for layer in sheet.layers for s in layer.shapes]
    assert [g.get(LABEL) for g in root.iter(f"{SVG_NS}g")] == labels
    assert [t.text for t in root.iter(f"{SVG_NS}text")] == \
        [s.text for s in shapes if isinstance(s, Text)]
    points = sum(len(POINT.findall(p.get("d", ""))) for p in root.iter(f"{SVG_NS}path"))
    points -= 4 * many * len(drawing.sheets)  # the sheet frames are rects, not paths
    assert points == sum(len(s.coords) for s in shapes if isinstance(s, (Polygons, Polylines)))
    assert [(float(i.get("width")), float(i.get("height"))) for i in root.iter(f"{SVG_NS}image")
            ] == [(round(s.width, 3), round(s.height, 3)) for s in shapes
                  if isinstance(s, Raster)]
