"""The DXF text writer: a drawing of strokes only (lines and rings, what a cut file holds)
written as text into the empty document ezdxf makes (``dxf_skeleton``: ezdxf's own bytes, cut
where a drawing fills in), with the handles ezdxf would give: ezdxf's bytes without loading
ezdxf (a quarter of a second). Also what ``dxf_ezdxf`` shares: the entities' order and
handles, the LWPOLYLINEs' text, colours, line weights, layer names, comments, encoding.
"""

from __future__ import annotations

import codecs

import numpy as np

from ..layout.drawing import Drawing, Layer, Polygons, Text, vectors
from . import dxf_skeleton as skeleton
from .numbers import shortest

DECIMALS = 6  # mm: 1 nm, far below any cutter; the last bits of a float never reach the file
VERSION = "R2004"
ENCODING = "cp1252"  # R2004's code page, ANSI_1252
# a layer's colour index by role: red cuts, blue scores, black (7: black on white) engraving,
# as the laser presets (templates/laser/) colour the lines themselves
ROLE_COLOURS = {"cut": 1, "score": 5, "engrave": 7, "paint": 8, "label": 7, "guide": 9}
LASER_ROLES = {"cut", "score", "engrave"}
# DXF's line weights in 1/100 mm (ezdxf.lldxf.const.VALID_DXF_LINEWEIGHTS)
LINEWEIGHTS = (0, 5, 9, 13, 15, 18, 20, 25, 30, 35, 40, 50, 53, 60, 70, 80, 90, 100, 106, 120,
               140, 158, 200, 211)
GAP = 10.0  # mm between sheets


def render(drawing: Drawing) -> bytes:
    """A drawing of strokes only (see ``plain``) as DXF."""
    doc = _Text()
    entities(drawing, doc)
    return encode(comments(drawing) + doc.document(extent(drawing)))


def extent(drawing: Drawing) -> tuple[float, float] | None:
    """(width, height) in mm, to ``DECIMALS``, of the drawing's sheets in the file from the
    origin (the first sheet's bottom-left corner): side by side, ``GAP`` apart; the file's
    limits and extents (a program that zooms or places by them sees the pages, not ezdxf's
    default 420 x 297 mm). None for no sheet (ezdxf's defaults stay)."""
    if not drawing.sheets:
        return None
    right = 0.0
    for sheet in drawing.sheets:  # as ``entities`` moves them
        right += sheet.width + GAP
    size = (right - GAP, max(s.height for s in drawing.sheets))
    return tuple(float(v) for v in mm(size, 0.0)[0])


def plain(drawing: Drawing) -> bool:
    """Whether ``drawing`` makes nothing but LWPOLYLINEs (no text, no fill). A picture is
    written as the lines it is a picture of (``vectors``): DXF has no good picture element (an
    IMAGE entity only links to a file beside the drawing), and a CAD program or a cutter wants
    the lines."""
    return not any(isinstance(shape, Text) or isinstance(shape, Polygons) and any(fills(shape))
                   for sheet in drawing.sheets for layer in sheet.layers
                   for shape in vectors(layer.shapes))


def fills(shape: Polygons) -> tuple:
    """Every polygon's fill colour (None or "" for none)."""
    return shape.fills or (shape.style.fill,) * shape.n_polygons


class _Text:
    """The document as text: ezdxf's handle sequence, layer table and entities."""

    def __init__(self) -> None:
        self.next = skeleton.FIRST_HANDLE
        self.layers = {name.lower() for name in skeleton.LAYERS}  # ezdxf's keys: no case
        self.records: list[str] = []
        self.entities: list[str] = []

    def handle(self) -> str:
        self.next += 1
        return f"{self.next - 1:X}"

    def layer(self, layer: Layer, name: str) -> str:
        name = layer_name(name)
        if name.lower() not in self.layers:
            self.layers.add(name.lower())
            colour = ROLE_COLOURS[layer.role] * (1 if layer.visible else -1)
            self.records.append(
                f"  0\nLAYER\n  5\n{self.handle()}\n330\n{skeleton.LAYER_TABLE}\n"
                "100\nAcDbSymbolTableRecord\n100\nAcDbLayerTableRecord\n"
                f"  2\n{name}\n 70\n0\n 62\n{colour}\n  6\nContinuous\n370\n-3\n"
                f"390\n{skeleton.PLOT_STYLE}\n")
        return name

    def add(self, handle: str, text: str) -> None:
        self.entities.append(text)

    def fills(self, shape, layer: Layer, name: str, dx: float) -> None:
        """None: a plain drawing has no fills."""

    def document(self, size: tuple[float, float] | None) -> str:
        """The document, its limits and extents from the origin to ``size`` (``extent``)."""
        used = self.next - skeleton.FIRST_HANDLE
        fill = {"layer count": f"{len(self.layers)}\n", "layers": "".join(self.records),
                "entities": "".join(self.entities)}
        if size is not None:  # a bound's slot: ("w", "h" or "0", ezdxf's default there)
            w, h = _points([size], 0.0)[0].split("\n 20\n")
            fill.update(w=f"{w}\n", h=f"{h}\n", **{"0": "0.0\n"})
        out = [skeleton.PARTS[0]]
        for slot, part in zip(skeleton.SLOTS, skeleton.PARTS[1:]):
            # a handle of the empty document's last objects moves by the handles used
            if isinstance(slot, tuple):
                out.append(fill.get(slot[0], slot[1]))
            else:
                out.append(fill[slot] if isinstance(slot, str) else f"{slot + used:X}\n")
            out.append(part)
        return "".join(out)


def entities(drawing: Drawing, doc) -> None:
    """Every shape of ``drawing`` into ``doc`` (``_Text`` or ezdxf's), in the order that gives
    the layers and entities their handles: sheet by sheet, layer by layer, a layer created
    where it is first used."""
    dx = 0.0
    for n, sheet in enumerate(drawing.sheets):
        suffix = "" if len(drawing.sheets) == 1 else f"-{n + 1}"
        for layer in sheet.layers:
            for shape in vectors(layer.shapes):
                name = layer.name + suffix
                if isinstance(shape, Text):
                    doc.text(shape, layer, name, dx)
                    continue
                closed = isinstance(shape, Polygons)
                if closed:
                    doc.fills(shape, layer, name, dx)
                if shape.style.stroke:
                    _lwpolylines(doc, shape, closed, layer, name, dx)
        dx += sheet.width + GAP


def _lwpolylines(doc, shape, closed: bool, layer: Layer, name: str, dx: float) -> None:
    """One LWPOLYLINE per line or ring of ``shape``, written as ezdxf writes it (the same
    tags and numbers) with the next handle of ezdxf's sequence, none for no points (as ezdxf
    does; the handle is spent)."""
    head = (f"330\n{skeleton.MODELSPACE}\n100\nAcDbEntity\n  8\n{doc.layer(layer, name)}\n"
            + "".join(f"{code}\n{value}\n" for code, value in
                      tags(layer, shape.style.stroke, shape.style.stroke_width))
            + "100\nAcDbPolyline\n 90\n")
    points = _points(shape.coords, dx)
    o = (shape.ring_offsets if closed else shape.offsets).tolist()
    for a, b in zip(o[:-1], o[1:]):
        handle = doc.handle()
        if b > a:
            xy = "\n 10\n".join(points[a:b])
            doc.add(handle, f"  0\nLWPOLYLINE\n  5\n{handle}\n{head}{b - a}\n 70\n{int(closed)}\n"
                    f" 10\n{xy}\n")


def _points(coords, dx: float) -> list[str]:
    """Every point as ``x\\n 20\\ny`` (moved ``dx`` along x and rounded to ``DECIMALS``, no
    negative zero), as ``repr`` writes floats (what ezdxf writes)."""
    xy = (np.asarray(coords, dtype=float).reshape(-1, 2) + (dx, 0.0)).ravel()
    points, slow = shortest(xy, DECIMALS, point_zero=True, per=2, sep="\n 20\n")
    # a point with a number shortest leaves (an exponent: below 1e-4, 1e16 and up; 1e9 and
    # up; not finite): both its numbers as repr writes them
    for i in sorted(set((slow // 2).tolist())):
        points[i] = "\n 20\n".join(repr(float(v) + 0.0)
                                   for v in np.round(xy[2 * i:2 * i + 2], DECIMALS))
    return points


def mm(xy, dx: float) -> np.ndarray:
    """Coordinates moved ``dx`` along x and rounded to ``DECIMALS`` (no negative zero)."""
    return np.round(np.asarray(xy, dtype=float).reshape(-1, 2) + (dx, 0.0), DECIMALS) + 0.0


def tags(layer: Layer, colour: str, width: float = 0.0) -> list[tuple[str, int]]:
    """An entity's own colour and weight, as (group code, value): its true colour unless black
    on a laser layer, and the line weight nearest ``width`` mm off laser layers (where lines
    are hairlines)."""
    out = []
    if width > 0 and layer.role not in LASER_ROLES:
        out.append(("370", min(LINEWEIGHTS, key=lambda w: abs(w - 100 * width))))
    if not (colour.lower() == "#000000" and layer.role in LASER_ROLES):
        r, g, b = rgb(colour)
        out.append(("420", (r << 16) | (g << 8) | b))
    return out


def comments(drawing: Drawing) -> str:
    """The title and metadata as 999 comment groups, one line each."""
    return "".join(f"999\n{key}: {' '.join(value.split())}\n"
                   for key, value in [("title", drawing.title), *drawing.metadata])


def _escape(error: UnicodeEncodeError) -> tuple[str, int]:
    """ezdxf's ``dxfreplace``: a character beyond the code page as ``\\U+XXXX``."""
    out = ""
    for c in error.object[error.start:error.end]:
        x = ord(c)
        if 0xDC80 <= x <= 0xDCFF:
            return codecs.lookup_error("surrogateescape")(error)
        out += "\\x%02x" % x if x <= 0xFF else "\\U+%04x" % x if x <= 0xFFFF else "\\U+%08x" % x
    return out, error.end


codecs.register_error("weavecut-dxf", _escape)


def encode(text: str) -> bytes:
    """``text`` in the file's code page, as ezdxf's ``Drawing.encode`` does it (ASCII text, as
    the code page holds it, by the ASCII codec: a hundredth of the charmap codec's time)."""
    if text.isascii():
        return text.encode("ascii")
    return text.encode(ENCODING, errors="weavecut-dxf")


def rgb(hex_colour: str) -> tuple[int, int, int]:
    h = hex_colour.lstrip("#")
    return (int(h[0:2], 16), int(h[2:4], 16), int(h[4:6], 16))


def layer_name(name: str) -> str:
    bad = '<>/\\":;?*|=`'
    return "".join("_" if ch in bad else ch for ch in name)
