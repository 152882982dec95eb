"""The SVG writer's document as svgwrite built it (main at bfa049d): the oracle for
``weavecut.export.svg._document``, which writes the same text without svgwrite. The numbers,
path data, styles and sheet placement are the writer's own (tested on their own)."""

from __future__ import annotations

import svgwrite

from weavecut.export.svg import _n, _paths
from weavecut.layout.drawing import Drawing, Sheet, Text


def document(drawing: Drawing, page: Sheet, placed) -> bytes:
    dwg = svgwrite.Drawing(size=(f"{_n(page.width)}mm", f"{_n(page.height)}mm"),
                           viewBox=f"0 0 {_n(page.width)} {_n(page.height)}", debug=False)
    dwg.attribs["xmlns:inkscape"] = "http://www.inkscape.org/namespaces/inkscape"
    meta = "; ".join(f"{k}: {v}" for k, v in drawing.metadata)
    dwg.set_desc(title=drawing.title, desc=meta or None)
    for n, (sheet, dx) in enumerate(placed):
        parent = dwg
        if len(placed) > 1:
            parent = _group(dwg, f"sheet-{n + 1}", sheet.name or f"sheet {n + 1}")
            parent.translate(dx, page.height - sheet.height)
            parent.add(dwg.rect((0, 0), (sheet.width, sheet.height), fill="none",
                                stroke="#cccccc", stroke_width=0.3))
            dwg.add(parent)
        for layer in sheet.layers:
            g = _group(dwg, f"{layer.role}-{layer.name}".replace(" ", "-"), layer.name)
            if not layer.visible:
                g.attribs["style"] = "display:none"
            for shape in layer.shapes:
                for element in _elements(dwg, shape, sheet.height):
                    g.add(element)
            parent.add(g)
    return dwg.tostring().encode("utf-8")


def _group(dwg, ident: str, label: str):
    g = dwg.g(id=ident)
    g.attribs["inkscape:groupmode"] = "layer"
    g.attribs["inkscape:label"] = label
    return g


def _elements(dwg, shape, height: float):
    if isinstance(shape, Text):
        yield _text(dwg, shape, height)
    else:
        for d, style in _paths(shape, height):
            yield dwg.path(d=d, **style)


def _text(dwg, t: Text, height: float):
    y = height - t.y
    el = dwg.text(t.text, insert=(_n(t.x), _n(y)), fill=t.fill,
                  font_size=_n(t.size / 0.7), font_family="DejaVu Sans, Arial, sans-serif",
                  text_anchor=t.anchor)
    if t.angle:
        el.rotate(-t.angle, center=(_n(t.x), _n(y)))
    return el
