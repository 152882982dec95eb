"""SVG writer: width/height and viewBox in mm, one Inkscape layer per Drawing layer; a stroke of
width 0 (a laser hairline) is drawn one screen pixel wide at any zoom."""

from __future__ import annotations

import numpy as np
import svgwrite

from ..layout.drawing import Drawing, Polygons, Polylines, Sheet, Style, Text

SUFFIX = "svg"
DECIMALS = 3
# a hairline (stroke width 0): one screen pixel at any zoom, as cairo and Inkscape write it, so
# it shows on screen; LightBurn ignores stroke widths, Inkscape prints it as a 0-width line
HAIRLINE = {"stroke_width": "1", "vector_effect": "non-scaling-stroke",
            "style": "-inkscape-stroke:hairline"}


def render(drawing: Drawing) -> bytes:
    """The first sheet as one SVG document, or every sheet side by side as top-level layers."""
    if len(drawing.sheets) == 1:
        return _document(drawing, drawing.sheets[0], [(drawing.sheets[0], 0.0)])
    gap = 10.0
    width = sum(s.width for s in drawing.sheets) + gap * (len(drawing.sheets) - 1)
    height = max(s.height for s in drawing.sheets)
    placed, x = [], 0.0
    for sheet in drawing.sheets:
        placed.append((sheet, x))
        x += sheet.width + gap
    return _document(drawing, Sheet(width, height), placed)


def _document(drawing: Drawing, page: Sheet, placed) -> bytes:
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
    elif isinstance(shape, Polylines):
        pts = _points(shape.coords, height)
        d = " ".join("M" + " ".join(pts[a:b]) for a, b in _pairs(shape.offsets))
        yield dwg.path(d=d, **_style(shape.style, closed=False))
    elif isinstance(shape, Polygons):
        pts = _points(shape.coords, height)
        rings = ["M" + " ".join(pts[a:b]) + "Z" for a, b in _pairs(shape.ring_offsets)]
        po = shape.polygon_rings().tolist()
        paths = ["".join(rings[a:b]) for a, b in zip(po[:-1], po[1:])]
        if shape.fills is None:  # one path for the whole batch
            yield dwg.path(d="".join(paths), **_style(shape.style, closed=True))
            return
        by_fill: dict[str, list[str]] = {}
        for d, fill in zip(paths, shape.fills):
            by_fill.setdefault(fill, []).append(d)
        for fill in sorted(by_fill):
            style = Style(shape.style.stroke, shape.style.stroke_width, fill, shape.style.opacity)
            yield dwg.path(d="".join(by_fill[fill]), **_style(style, closed=True))


def _text(dwg, t: Text, height: float):
    y = height - t.y
    el = dwg.text(t.text, insert=(_n(t.x), _n(y)), fill=t.fill,
                  font_size=_n(t.size / 0.7), font_family="DejaVu Sans, Arial, sans-serif",
                  text_anchor=t.anchor)
    if t.angle:
        el.rotate(-t.angle, center=(_n(t.x), _n(y)))
    return el


def _style(style: Style, closed: bool) -> dict:
    out = {"fill": style.fill if (closed and style.fill) else "none",
           "stroke": style.stroke or "none"}
    if style.stroke:
        out.update({"stroke_width": _n(style.stroke_width)} if style.stroke_width > 0
                   else HAIRLINE)
        out["stroke_linejoin"] = "round"
    if closed and style.fill:
        out["fill_rule"] = "evenodd"
    if style.opacity < 1:
        out["opacity"] = _n(style.opacity)
    return out


def _pairs(offsets):
    o = np.asarray(offsets).tolist()
    return zip(o[:-1], o[1:])


def _points(coords, height: float) -> list[str]:
    """Every point as ``x,y`` (y flipped), each number as ``_decimal`` writes it: below 1e16
    that is its ``repr`` without a trailing ".0", so one ``repr`` of the list serves all."""
    xy = np.round(np.column_stack([coords[:, 0], height - coords[:, 1]]), DECIMALS) + 0.0
    if not len(xy):
        return []
    if not np.abs(xy).max() < 1e16:  # 1e+16 and up (or not finite): number by number
        text = [_decimal(v) for v in xy.ravel().tolist()]
        return [f"{x},{y}" for x, y in zip(text[::2], text[1::2])]
    text = repr(xy.tolist()).replace(".0,", ",").replace(".0]", "]")
    return text[2:-2].replace("], [", "\0").replace(", ", ",").split("\0")


def _n(x: float) -> str:
    return _decimal(round(float(x), DECIMALS) + 0.0)


def _decimal(x: float) -> str:
    """``x`` (rounded to ``DECIMALS``, no negative zero) in fixed point without trailing
    zeros: every decimal kept however large ``x`` is (``:g`` keeps six digits: 1234.57). The
    shortest repr of a float rounded to 3 decimals is that (below 1e16), but for ".0"."""
    text = repr(x)
    if "e" in text:  # 1e+16 and up, and below 1e-4 (not rounded to DECIMALS)
        return f"{x:.{DECIMALS}f}".rstrip("0").rstrip(".")
    return text[:-2] if text.endswith(".0") else text
