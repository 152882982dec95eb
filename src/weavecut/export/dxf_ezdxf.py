"""The DXF writer's part done by ezdxf: drawings with text or fills (TEXT, HATCH), and the
empty document the text writer fills in (``skeleton``; ``dxf_skeleton.py`` is its output).

Regenerate ``dxf_skeleton.py`` after an ezdxf upgrade (a test compares it)::

    python -m weavecut.export.dxf_ezdxf > src/weavecut/export/dxf_skeleton.py
"""

from __future__ import annotations

import contextlib
import functools
import io

import ezdxf
import numpy as np
from ezdxf import colors
from ezdxf.enums import TextEntityAlignment

from ..layout.drawing import Drawing, Layer, Text
from .dxf_text import (ROLE_COLOURS, VERSION, comments, encode, entities, extent, fills,
                       layer_name, mm, rgb, tags)

ALIGN = {"start": "BOTTOM_LEFT", "middle": "BOTTOM_CENTER", "end": "BOTTOM_RIGHT"}
BOUNDS = (1234.5, 6789.25)  # a size no empty document writes: where its bounds go


@contextlib.contextmanager
def _fixed_metadata():
    """ezdxf stamps GUIDs and times; fix them so the same drawing gives the same bytes."""
    old = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = old


def render(drawing: Drawing) -> bytes:
    return encode(comments(drawing) + _document(drawing, size=extent(drawing)))


def _document(drawing: Drawing, spare: int = 0, size: tuple[float, float] | None = None) -> str:
    """The DXF text of ``drawing`` (without the comments); ``spare`` handles are used up
    after its entities (to see which handles of the document follow them); its limits and
    extents from the origin to ``size`` (``dxf_text.extent``), ezdxf's defaults for None."""
    with _fixed_metadata():
        doc = _Ezdxf()
        entities(drawing, doc)
        for _ in range(spare):
            doc.handle()
        if size is not None:  # the header's extents too: ezdxf takes them from the model
            msp = doc.doc.modelspace()  # space only where they are not at the origin
            msp.reset_extents((0.0, 0.0, 0.0), (*size, 0.0))
            msp.reset_limits((0.0, 0.0), size)
            doc.doc.active_layout().reset_limits((0.0, 0.0), size)  # the paper (LibreCAD's)
            doc.doc.header["$EXTMIN"], doc.doc.header["$EXTMAX"] = (0.0, 0.0, 0.0), (*size, 0.0)
        # ezdxf adds the CLASSES of the entity types in use in set order; fix the order first
        doc.doc.classes.add_required_classes(doc.doc.dxfversion)
        doc.doc.classes.classes = dict(sorted(doc.doc.classes.classes.items()))
        buf = io.StringIO()
        doc.doc.write(buf)
    return _with_lines(buf.getvalue(), doc.lines)


class _Ezdxf:
    """An ezdxf document that ``dxf.entities`` fills: LWPOLYLINEs as text (see ``add``), text
    and fills as ezdxf entities."""

    def __init__(self) -> None:
        self.doc = doc = ezdxf.new(VERSION, setup=False)
        doc.units = ezdxf.units.MM
        doc.header["$INSUNITS"] = 4
        doc.header["$MEASUREMENT"] = 1
        doc.header["$LWDISPLAY"] = 1
        self.msp = doc.modelspace()
        self.lines: dict[str, str] = {}  # the LWPOLYLINEs' text by handle

    def handle(self) -> str:
        return self.doc.entitydb.next_handle()

    def add(self, handle: str, text: str) -> None:
        """An LWPOLYLINE's text, without ezdxf's entity object (creating and exporting one
        costs about 0.15 ms: a cut sheet holds thousands)."""
        self.lines[handle] = text

    def layer(self, layer: Layer, name: str, colour: str | None = None) -> str:
        """The DXF layer ``name`` (created on first use): the role's colour, or ``colour``."""
        name = layer_name(name)
        if name not in self.doc.layers:
            entry = self.doc.layers.add(name, color=ROLE_COLOURS[layer.role] if colour is None
                                        else _aci(colour))
            if colour is not None:
                entry.rgb = rgb(colour)
            if not layer.visible:
                entry.off()
        return name

    def text(self, shape: Text, layer: Layer, name: str, dx: float) -> None:
        attribs = {"layer": self.layer(layer, name)}
        attribs.update({"lineweight" if code == "370" else "true_color": value
                        for code, value in tags(layer, shape.fill)})
        self.msp.add_text(shape.text, height=shape.size, rotation=shape.angle,
                          dxfattribs=attribs).set_placement(
            tuple(mm(np.array([shape.x, shape.y]), dx)[0].tolist()),
            align=TextEntityAlignment[ALIGN[shape.anchor]])

    def fills(self, shape, layer: Layer, name: str, dx: float) -> None:
        """One solid HATCH per fill colour, on a layer of that colour."""
        rings = shape.rings()
        po = shape.polygon_rings().tolist()
        by_fill: dict[str, list[int]] = {}
        for i, fill in enumerate(fills(shape)):
            if fill:
                by_fill.setdefault(fill, []).append(i)
        for fill in sorted(by_fill):
            fill_layer = self.layer(layer, f"{name}-{fill.lstrip('#').lower()}", fill)
            hatch = self.msp.add_hatch(dxfattribs={"layer": fill_layer})
            hatch.set_solid_fill(_aci(fill), style=0, rgb=rgb(fill))  # odd parity: holes open
            for i in by_fill[fill]:
                for ring in rings[po[i]:po[i + 1]]:
                    hatch.paths.add_polyline_path(mm(ring, dx).tolist(), is_closed=True)


def _with_lines(dxf: str, lines: dict) -> str:
    """``dxf`` with the LWPOLYLINEs put into its ENTITIES section, every entity in the order
    of its handle (the order ezdxf made them in)."""
    head, _, rest = dxf.partition("  2\nENTITIES\n")
    body, end = rest[:rest.index("  0\nENDSEC\n")], rest[rest.index("  0\nENDSEC\n"):]
    tags_ = body.split("\n")[:-1]
    starts = [i for i in range(0, len(tags_), 2) if tags_[i] == "  0"] + [len(tags_)]
    made = [(int(tags_[a + 3], 16), "\n".join(tags_[a:b]) + "\n") for a, b in
            zip(starts[:-1], starts[1:])]
    ours = [(int(handle, 16), text) for handle, text in lines.items()]
    return (head + "  2\nENTITIES\n" + "".join(t for _, t in sorted(made + ours))
            + end)


@functools.lru_cache(maxsize=None)
def _aci(hex_colour: str) -> int:
    """The nearest AutoCAD colour index, for programs that ignore true colours."""
    r, g, b = rgb(hex_colour)
    return min(range(1, 256), key=lambda i: sum((a - c) ** 2 for a, c in
                                                 zip(colors.aci2rgb(i), (r, g, b))))


def skeleton() -> dict:
    """The empty drawing's document cut where a drawing fills it in: ``PARTS`` of text with a
    ``SLOTS`` entry between each two: ``"layer count"``, ``"layers"`` (their records, before
    the layer table ends), ``"entities"``, a limit's or an extent's value (``("w", ezdxf's
    default line)``, "h", or "0": the origin's), or the handle (int) an object written after the
    entities has in the empty document (it moves on by the handles a drawing uses). Also the
    first handle a drawing takes, the layers there already, and the handles a layer record
    or an entity refers to."""
    spare = 0x10000
    empty = Drawing(())
    with _fixed_metadata():
        probe = _Ezdxf()
    first = str(probe.doc.entitydb.handles)
    lines = _document(empty).splitlines(keepends=True)
    moved = _document(empty, spare).splitlines(keepends=True)
    bounded = _document(empty, size=BOUNDS).splitlines(keepends=True)
    assert len(lines) == len(moved) == len(bounded)
    cuts = []  # (line, slot, lines replaced)
    for i, (a, b, c) in enumerate(zip(lines, moved, bounded)):
        if a != b:
            assert int(b, 16) - int(a, 16) == spare and int(a, 16) >= int(first, 16), (a, b)
            cuts.append((i, int(a, 16), 1))
        elif a != c:  # a limit or extent: the width, the height or the origin's 0
            key = {repr(BOUNDS[0]): "w", repr(BOUNDS[1]): "h", "0.0": "0"}[c.strip()]
            cuts.append((i, (key, a), 1))
    table = _after(lines, ["  0\n", "TABLE\n", "  2\n", "LAYER\n"], 0)
    count = _after(lines, [" 70\n"], table)
    cuts.append((count, "layer count", 1))
    cuts.append((_after(lines, ["  0\n", "ENDTAB\n"], table) - 2, "layers", 0))
    section = _after(lines, ["  2\n", "ENTITIES\n"], 0)
    assert lines[section:section + 2] == ["  0\n", "ENDSEC\n"]
    cuts.append((section, "entities", 0))
    parts, slots, at = [], [], 0
    for line, slot, width in sorted(cuts, key=lambda c: c[0]):
        parts.append("".join(lines[at:line]))
        slots.append(slot)
        at = line + width
    parts.append("".join(lines[at:]))
    names = [layer.dxf.name for layer in probe.doc.layers]
    assert int(lines[count]) == len(names)
    return {"FIRST_HANDLE": int(first, 16), "LAYERS": tuple(names),
            "LAYER_TABLE": probe.doc.layers.head.dxf.handle,
            "PLOT_STYLE": probe.doc.layers.get("0").dxf.plotstyle_handle,
            "MODELSPACE": probe.msp.block_record_handle, "SLOTS": tuple(slots),
            "PARTS": tuple(parts)}


def _after(lines: list[str], tags_: list[str], start: int) -> int:
    """The index of the line after the first run of ``tags_`` from ``start``."""
    for i in range(start, len(lines) - len(tags_) + 1):
        if lines[i:i + len(tags_)] == tags_:
            return i + len(tags_)
    raise ValueError(f"no {tags_!r} in ezdxf's document")


def skeleton_source() -> str:
    """The source of ``dxf_skeleton.py`` (handles in hexadecimal, as DXF writes them)."""
    made = skeleton()
    parts = made.pop("PARTS")
    made["FIRST_HANDLE"] = f"0x{made['FIRST_HANDLE']:X}"
    made["SLOTS"] = "(" + ", ".join(f"0x{s:X}" if isinstance(s, int) else repr(s)
                                    for s in made["SLOTS"]) + ")"
    head = ("# over 400 lines: ezdxf's empty document as data, made by "
            "dxf_ezdxf.skeleton_source\n"
            f'"""The empty R2004 document ezdxf {ezdxf.__version__} writes for weave-cut '
            "(millimetres, fixed meta data),\ncut where a drawing fills it in (see "
            "``dxf_ezdxf.skeleton``). Made by\n``python -m weavecut.export.dxf_ezdxf``; "
            'do not edit."""\n\n')
    body = "".join(f"{key} = {value if key in ('FIRST_HANDLE', 'SLOTS') else repr(value)}\n"
                   for key, value in made.items())
    texts = "".join('    """' + part.replace("\\", "\\\\") + '""",\n' for part in parts)
    return head + body + f"PARTS = (\n{texts})\n"


if __name__ == "__main__":
    print(skeleton_source(), end="")
