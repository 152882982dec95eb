"""PDF writer (reportlab): one page per sheet at its exact size, drawn in millimetres.

``invariant=1`` drops reportlab's timestamps and random document id, so the same drawing gives
the same bytes. Hidden layers are left out. A picture (Raster) is a greyscale image XObject at
its box's exact size. Page streams are deflated binary, not also ASCII85-encoded (reportlab's
``rl_config.useA85``, a setting it documents for this): a fifth smaller and quicker to write.
"""

from __future__ import annotations

import functools
import io
from itertools import groupby

import numpy as np

from reportlab import rl_config
from reportlab.lib.colors import HexColor
from reportlab.lib.rl_accel import fp_str
from reportlab.lib.units import mm
from reportlab.pdfbase import pdfdoc
from reportlab.pdfgen import canvas
from reportlab.pdfgen.pathobject import PDFPathObject

from ..layout.drawing import Drawing, Polygons, Polylines, Raster, Style, Text
from ..numeric import cos_sin
from . import picture
from .numbers import fixed

SUFFIX = "pdf"
FONT = "Helvetica"
rl_config.useA85 = 0  # ASCII85 keeps a file 7-bit clean, which no reader needs


@functools.lru_cache(maxsize=None)
def _colour(hex_colour: str) -> HexColor:
    """reportlab's colour of ``#rrggbb``, parsed once (a page sets a few colours hundreds of
    times)."""
    return HexColor(hex_colour)


def render(drawing: Drawing) -> bytes:
    buf = io.BytesIO()
    first = drawing.sheets[0]
    c = canvas.Canvas(buf, pagesize=(first.width * mm, first.height * mm), invariant=1,
                      pageCompression=1)
    meta = dict(drawing.metadata)
    c.setTitle(drawing.title)
    c.setCreator(meta.get("generator", "weave-cut"))
    c.setProducer(meta.get("generator", "weave-cut"))
    c.setSubject(meta.get("command", ""))
    for sheet in drawing.sheets:
        c.setPageSize((sheet.width * mm, sheet.height * mm))
        c.saveState()
        c.scale(mm, mm)
        for layer in sheet.layers:
            if layer.visible:
                points = _layer_points(layer)
                for is_text, run in groupby(layer.shapes, lambda x: isinstance(x, Text)):
                    if is_text:
                        _texts(c, list(run))
                    else:
                        for shape in run:
                            _draw(c, shape, points)
        c.restoreState()
        c.showPage()
    c.save()
    return buf.getvalue()


def _layer_points(layer):
    """The points of each of ``layer``'s lines and polygons in turn (:func:`_points`), all
    written at once (a guide has a shape per number)."""
    drawn = [s.coords for s in layer.shapes if isinstance(s, (Polylines, Polygons))]
    pts = _points(np.concatenate(drawn)) if drawn else []
    ends = np.cumsum([len(c) for c in drawn]).tolist()
    return (pts[a:b] for a, b in zip([0, *ends], ends))


def _draw(c, shape, points) -> None:
    """Draw ``shape``; a line's or polygon's points (:func:`_points`) are the next of
    ``points``."""
    if isinstance(shape, Raster):
        _image(c, shape)
        return
    if isinstance(shape, Polylines):
        _stroke(c, shape.style)
        o = shape.offsets.tolist()
        c.drawPath(_path(next(points), zip(o[:-1], o[1:]), False), stroke=1, fill=0)
        return
    if isinstance(shape, Polygons):
        groups: dict[str | None, list[int]] = {}
        fills = shape.fills or (shape.style.fill,) * shape.n_polygons
        for i, fill in enumerate(fills):
            groups.setdefault(fill, []).append(i)
        po = shape.polygon_rings().tolist()
        ro = shape.ring_offsets.tolist()
        points = next(points)
        for fill in sorted(groups, key=lambda f: f or ""):
            style = Style(shape.style.stroke, shape.style.stroke_width, fill, shape.style.opacity)
            _stroke(c, style)
            rings = [(ro[r], ro[r + 1]) for i in groups[fill] for r in range(po[i], po[i + 1])]
            c.drawPath(_path(points, rings, True), stroke=1 if style.stroke else 0,
                       fill=1 if fill else 0,
                       fillMode=canvas.FILL_EVEN_ODD)  # holes stay open, however wound


ANCHOR = {"start": 0.0, "middle": 0.5, "end": 1.0}  # of its width a text starts before x


def _texts(c, texts: list[Text]) -> None:
    """A run of texts in one text object, each placed by its own text matrix: turned by its
    angle about its anchor, which lies ``ANCHOR`` of its width along its baseline (what
    drawString in a turned frame draws, without a graphics state for every text)."""
    sizes = [t.size / 0.72 for t in texts]  # the font size whose capitals are t.size tall
    cos, sin = (v.tolist() for v in cos_sin([t.angle for t in texts]))
    c.saveState()
    text = c.beginText()
    for t, size, a, b in zip(texts, sizes, cos, sin):
        shift = ANCHOR[t.anchor] * c.stringWidth(t.text, FONT, size)
        text.setFont(FONT, size)
        text.setFillColor(_colour(t.fill))
        text.setTextTransform(a, b, -b, a, t.x - a * shift, t.y - b * shift)
        text.textOut(t.text)
    c.drawText(text)
    c.restoreState()


class _Picture(pdfdoc.PDFImageXObject):
    """A Raster as an 8-bit DeviceGray image XObject: the PNG writer's zlib stream with PNG
    predictors (``DecodeParms``), not re-encoded by reportlab (which makes every image RGB)."""

    def __init__(self, name: str, raster: Raster) -> None:
        super().__init__(name)
        self.height, self.width = raster.pixels.shape
        self.bitsPerComponent = 8
        self.colorSpace = "DeviceGray"
        self.streamContent = picture.deflated(raster.pixels)

    def format(self, document) -> bytes:
        stream = pdfdoc.PDFStream(content=self.streamContent)
        stream.dictionary.dict.update({
            "Type": pdfdoc.PDFName("XObject"), "Subtype": pdfdoc.PDFName("Image"),
            "Width": self.width, "Height": self.height, "BitsPerComponent": 8,
            "ColorSpace": pdfdoc.PDFName("DeviceGray"),
            # one filter as a name, not an array: poppler pairs an array of filters with an
            # array of parameters only, and drew the rows unpredicted (sheared)
            "Filter": pdfdoc.PDFName("FlateDecode"),
            "DecodeParms": pdfdoc.PDFDictionary({
                "Predictor": 15, "Colors": 1, "BitsPerComponent": 8, "Columns": self.width})})
        return stream.format(document)


def _image(c, raster: Raster) -> None:
    """``raster`` stretched over its box, as ``canvas.drawImage`` places an image (one
    XObject per picture, named by its number in the document). Adding the XObject to the
    document is private to reportlab (``_doc``): its public ``drawImage`` takes a PIL image and
    writes it unpredicted in ASCII85, a fifth larger (edge-renders: 2.61 -> 3.14 MB); the
    public ``doForm`` draws it."""
    c._currentPageHasImages = 1  # the page's ProcSet names images
    name = f"picture{len(c._doc.idToObject)}"
    image = _Picture(name, raster)
    c._doc.Reference(image, c._doc.getXObjectName(name))
    c._doc.addForm(name, image)
    c.saveState()
    c.translate(raster.x, raster.y)
    c.scale(raster.width, raster.height)
    c.doForm(name)
    c.restoreState()


def _points(coords) -> list[str]:
    """Every point as reportlab's path operators write it (``fp_str``), all at once
    (:func:`numbers.fixed`; the few values it leaves, one by one by ``fp_str``)."""
    points, slow = fixed(coords, per=2)
    for i in sorted(set((slow // 2).tolist())):
        points[i] = fp_str(coords[i].tolist())
    return points


def _path(points: list[str], spans, close: bool) -> PDFPathObject:
    """The path through ``points[a:b]`` for each span (a, b) with points, closed or not: what
    ``moveTo``, ``lineTo`` and ``close`` would write, one string per span (and the ``n`` a
    path's first operator brings)."""
    code = []
    for a, b in spans:
        if b > a:
            line = " l ".join(points[a + 1:b])
            code.append(f"{points[a]} m" + (f" {line} l" if line else "")
                        + (" h" if close else ""))
    return PDFPathObject(["n", *code] if code else [])


def _stroke(c, style: Style) -> None:
    if style.stroke:
        c.setStrokeColor(_colour(style.stroke))
        c.setLineWidth(style.stroke_width)
    if style.fill:
        c.setFillColor(_colour(style.fill))
    c.setLineJoin(1)
    c.setStrokeAlpha(style.opacity)
    c.setFillAlpha(style.opacity)
