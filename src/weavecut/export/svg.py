"""SVG writer: width/height and viewBox in mm, one Inkscape layer per Drawing layer; a stroke of
width 0 (a laser hairline) is written ``HAIRLINE`` mm wide, a width every viewer draws; a
picture (Raster) is an ``<image>`` holding its PNG.

The text is written as svgwrite wrote it through ElementTree (the tests hold svgwrite as the
oracle): attributes sorted by name, empty ones left out, an element without content closed as
``<name />``; without svgwrite's import (0.05 s) and its element objects.
"""

from __future__ import annotations

import base64

import numpy as np

from ..layout.drawing import Drawing, Polygons, Polylines, Raster, Sheet, Style, Text
from . import picture
from .numbers import shortest

SUFFIX = "svg"
DECIMALS = 3
# a hairline (stroke width 0) in mm, about one pixel at 96 dpi so it shows on screen. Not
# Inkscape's hairline (1 px with vector-effect non-scaling-stroke): librsvg 2.54 (GNOME's
# viewers) ignores the vector-effect and draws such a line 1 mm wide, so engraved labels blot.
# A line of any width is a line to LightBurn (it ignores stroke widths), Inkscape and the laser
# programs that read SVG; presets whose drivers need thinner lines (Epilog/ULS, Ponoko) give
# their own width, which is written as it is
HAIRLINE = 0.25
NAMESPACES = {"xmlns": "http://www.w3.org/2000/svg", "xmlns:ev": "http://www.w3.org/2001/xml-events",
              "xmlns:inkscape": "http://www.inkscape.org/namespaces/inkscape",
              "xmlns:xlink": "http://www.w3.org/1999/xlink"}


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
    root = {"width": f"{_n(page.width)}mm", "height": f"{_n(page.height)}mm",
            "viewBox": f"0 0 {_n(page.width)} {_n(page.height)}", "baseProfile": "full",
            "version": "1.1", **NAMESPACES}
    meta = "; ".join(f"{k}: {v}" for k, v in drawing.metadata)
    body = [_element("title", text=drawing.title)]
    if meta:
        body.append(_element("desc", text=meta))
    body.append(_element("defs"))
    for n, (sheet, dx) in enumerate(placed):
        layers = [_layer(layer, sheet.height) for layer in sheet.layers]
        if len(placed) > 1:
            frame = _element("rect", {"x": 0, "y": 0, "width": sheet.width,
                                      "height": sheet.height, "fill": "none",
                                      "stroke": "#cccccc", "stroke-width": 0.3})
            body.append(_group(f"sheet-{n + 1}", sheet.name or f"sheet {n + 1}", [frame, *layers],
                               transform=f"translate({dx},{page.height - sheet.height})"))
        else:
            body += layers
    return _element("svg", root, body).encode("utf-8")


def _layer(layer, height: float) -> str:
    # the points of all the layer's lines and rings written at once (a guide has a shape
    # per number), then handed out shape by shape
    drawn = [s.coords for s in layer.shapes if isinstance(s, (Polygons, Polylines))]
    pts = _points(np.concatenate(drawn), height) if drawn else []
    ends = np.cumsum([len(c) for c in drawn]).tolist()
    spans = iter(zip([0, *ends], ends))
    return _group(f"{layer.role}-{layer.name}".replace(" ", "-"), layer.name,
                  [e for shape in layer.shapes for e in _elements(
                      shape, height, pts, spans)],
                  style=None if layer.visible else "display:none")


def _group(ident: str, label: str, content: list[str], **attributes) -> str:
    return _element("g", {"id": ident, "inkscape:groupmode": "layer", "inkscape:label": label,
                          **attributes}, content)


def _element(name: str, attributes: dict | None = None, content: list[str] = (),
             text: str = "") -> str:
    """``<name attributes>text content</name>`` as ElementTree writes it: the attributes (as
    ``str`` of each, none that is None or empty) sorted by name, escaped; ``<name ... />``
    without text or content."""
    items = sorted((k, str(v)) for k, v in (attributes or {}).items() if v is not None)
    head = "<" + name + "".join(f' {k}="{_escape(v, True)}"' for k, v in items if v)
    if text or content:
        return f"{head}>{_escape(text)}{''.join(content)}</{name}>"
    return head + " />"


def _escape(text: str, attribute: bool = False) -> str:
    text = text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    if attribute:
        for char, code in (('"', "&quot;"), ("\r", "&#13;"), ("\n", "&#10;"), ("\t", "&#09;")):
            text = text.replace(char, code)
    return text


def _elements(shape, height: float, pts, spans):
    """The elements of ``shape``: a Text's, a Raster's ``<image>``, or the paths of a
    Polylines or Polygons whose points are ``pts[a:b]`` for the next (a, b) of ``spans``."""
    if isinstance(shape, Text):
        yield _text(shape, height)
    elif isinstance(shape, Raster):
        yield _image(shape, height)
    else:
        a, b = next(spans)
        for d, style in _paths(shape, height, pts[a:b]):
            yield _element("path", {"d": d, **style})


def _paths(shape, height: float, pts: list[str] | None = None):
    """(path data, attributes) of each path of a Polylines or Polygons shape (its points as
    written, ``pts``, if at hand): one path for all lines or all rings, or one per fill
    colour."""
    pts = _points(shape.coords, height) if pts is None else pts
    if isinstance(shape, Polylines):
        yield " ".join("M" + " ".join(pts[a:b]) for a, b in _pairs(shape.offsets)), _style(
            shape.style, closed=False)
    elif isinstance(shape, Polygons):
        rings = ["M" + " ".join(pts[a:b]) + "Z" for a, b in _pairs(shape.ring_offsets)]
        po = shape.polygon_rings().tolist()
        paths = ["".join(rings[a:b]) for a, b in zip(po[:-1], po[1:])]
        if shape.fills is None:  # one path for the whole batch
            yield "".join(paths), _style(shape.style, closed=True)
            return
        by_fill: dict[str, list[str]] = {}
        for d, fill in zip(paths, shape.fills):
            by_fill.setdefault(fill, []).append(d)
        for fill in sorted(by_fill):
            style = Style(shape.style.stroke, shape.style.stroke_width, fill, shape.style.opacity)
            yield "".join(by_fill[fill]), _style(style, closed=True)


def _text(t: Text, height: float) -> str:
    y = _n(height - t.y)
    attributes = {"x": _n(t.x), "y": y, "fill": t.fill, "font-size": _n(t.size / 0.7),
                  "font-family": "DejaVu Sans, Arial, sans-serif", "text-anchor": t.anchor}
    if t.angle:
        attributes["transform"] = f"rotate({-t.angle},{_n(t.x)},{y})"
    return _element("text", attributes, text=str(t.text))


def _image(r: Raster, height: float) -> str:
    """A picture as an ``<image>`` of its PNG (a data URI) stretched over its box in mm."""
    data = base64.b64encode(picture.png(r.pixels, picture.dpi(r))).decode("ascii")
    return _element("image", {"x": _n(r.x), "y": _n(height - r.y - r.height),
                              "width": _n(r.width), "height": _n(r.height),
                              "preserveAspectRatio": "none",
                              "xlink:href": f"data:image/png;base64,{data}"})


def _style(style: Style, closed: bool) -> dict:
    out = {"fill": style.fill if (closed and style.fill) else "none",
           "stroke": style.stroke or "none"}
    if style.stroke:
        out["stroke-width"] = _n(style.stroke_width if style.stroke_width > 0 else HAIRLINE)
        out["stroke-linejoin"] = "round"
    if closed and style.fill:
        out["fill-rule"] = "evenodd"
    if style.opacity < 1:
        out["opacity"] = _n(style.opacity)
    return out


def _pairs(offsets):
    o = np.asarray(offsets).tolist()
    return zip(o[:-1], o[1:])


def _points(coords, height: float) -> list[str]:
    """Every point as ``x,y`` (y flipped), each number as ``_decimal`` writes it."""
    xy = np.column_stack([coords[:, 0], height - coords[:, 1]]).ravel()
    points, slow = shortest(xy, DECIMALS, per=2, sep=",")
    for i in sorted(set((slow // 2).tolist())):  # 1e12 and up (or not finite): as repr does it
        points[i] = ",".join(_decimal(float(v) + 0.0) for v in np.round(xy[2 * i:2 * i + 2],
                                                                       DECIMALS))
    return points


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
