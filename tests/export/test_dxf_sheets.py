"""DXF as a laser program reads it, through ezdxf: millimetres, metric, line weights shown;
every kind of entity of a later sheet (cut rings, open lines, fills, text) moved right by the
widths of the sheets before it plus a 10 mm gap; layer names a CAD program accepts; colours
by index for programs that ignore true colours; provenance in comments; same bytes each time."""

from __future__ import annotations

import io

import ezdxf
import ezdxf.comments
import numpy as np
import pytest
import shapely
from ezdxf import colors

from weavecut.export import dxf
from weavecut.layout.drawing import (
    Drawing, Layer, Sheet, Style, Text, polygons_from_shapely, polylines_from_lines,
)

GAP = 10.0


def read(drawing: Drawing):
    return ezdxf.read(io.StringIO(dxf.render(drawing).decode("utf-8")))


def everything(name: str = "sheet") -> tuple[Layer, ...]:
    """A cut ring with a hole, a filled square, an open line and a text, all inside a 20 mm
    square at the sheet's origin."""
    ring = shapely.Polygon([(1, 1), (9, 1), (9, 9), (1, 9)], [[(3, 3), (6, 3), (6, 6), (3, 6)]])
    return (Layer("cut", "cut", (polygons_from_shapely([ring], Style("#ff0000", 0.1)),)),
            Layer("paint", "paint", (polygons_from_shapely(
                [shapely.box(11, 11, 19, 19)], Style(None, 0, "#00ff00")),)),
            Layer("fold", "score", (polylines_from_lines([[(2, 12), (8, 18)]],
                                                         Style("#0000ff", 0.2)),)),
            Layer("label", "label", (Text(15, 5, name, 2.0, "middle"),)))


def extents(doc, layer: str) -> dict[str, np.ndarray]:
    """Per entity type, the (x, y) points on ``layer`` (HATCH: its boundary vertices)."""
    msp = doc.modelspace()
    out = {}
    for kind in ("LWPOLYLINE", "HATCH", "TEXT"):
        pts = []
        for e in msp.query(f'{kind}[layer=="{layer}"]'):
            if kind == "LWPOLYLINE":
                pts += e.get_points("xy")
            elif kind == "HATCH":
                pts += [tuple(v)[:2] for path in e.paths for v in path.vertices]
            else:
                pts.append(tuple(e.get_placement()[1])[:2])
        if pts:
            out[kind] = np.array(pts, dtype=float)
    return out


def test_every_entity_of_a_later_sheet_moves_right_by_the_sheets_before_it():
    widths = (40.0, 25.0, 30.0)
    doc = read(Drawing(tuple(Sheet(w, 20, everything(f"s{n}")) for n, w in enumerate(widths))))
    first = {layer: extents(doc, f"{layer}-1") for layer in ("cut", "fold", "label")}
    first["fill"] = extents(doc, "paint-1-00ff00")
    offsets = [0.0, widths[0] + GAP, widths[0] + widths[1] + 2 * GAP]
    for n, dx in enumerate(offsets):
        for layer, reference in first.items():
            name = f"{layer}-{n + 1}" if layer != "fill" else f"paint-{n + 1}-00ff00"
            got = extents(doc, name)
            assert set(got) == set(reference), name
            for kind in got:
                np.testing.assert_allclose(got[kind], reference[kind] + [dx, 0], atol=1e-9,
                                           err_msg=f"{name} {kind}")
    # and the first sheet is where the drawing put it
    np.testing.assert_allclose(first["label"]["TEXT"], [[15, 5]])
    assert sorted(map(tuple, first["fill"]["HATCH"].tolist())) == \
        [(11, 11), (11, 19), (19, 11), (19, 19)]
    # sheets do not overlap: each starts right of where the one before ends
    texts = sorted((t.dxf.text, tuple(t.get_placement()[1])[0])
                   for t in doc.modelspace().query("TEXT"))
    assert [t for t, _ in texts] == ["s0", "s1", "s2"]



@pytest.mark.parametrize("plain", [False, True])  # ezdxf's writer, and the cut files' own
@pytest.mark.parametrize("widths", [(210.0,), (40.0, 25.5, 30.0)])
def test_the_headers_extents_and_limits_are_the_sheets(plain, widths):
    """Walk of issue #29: a cut page's DXF said ezdxf's 420 x 297 mm limits and no extents.
    Its limits and extents are its sheets, from the origin at the first sheet's bottom-left
    corner; every entity lies inside them."""
    sheets = tuple(Sheet(w, 297.0 - 10 * n, everything(f"s{n}")[:1 if plain else 4])
                   for n, w in enumerate(widths))
    doc = read(Drawing(sheets))
    right, top = sum(widths) + GAP * (len(widths) - 1), 297.0
    assert tuple(doc.header["$LIMMIN"]) == (0, 0) and tuple(doc.header["$LIMMAX"]) == (right, top)
    assert tuple(doc.header["$EXTMIN"]) == (0, 0, 0)
    assert tuple(doc.header["$EXTMAX"]) == (right, top, 0)
    from ezdxf import bbox
    box = bbox.extents(doc.modelspace())
    assert box.has_data and 0 <= box.extmin.x and 0 <= box.extmin.y
    assert box.extmax.x <= right and box.extmax.y <= top
    assert not doc.audit().has_errors


def test_one_sheet_keeps_its_layer_names():
    doc = read(Drawing((Sheet(20, 20, everything()),)))
    names = {layer.dxf.name for layer in doc.layers}
    assert {"cut", "fold", "label", "paint-00ff00"} <= names
    assert not any(n.endswith("-1") for n in names)


def test_header_says_millimetres_metric_and_shows_line_weights():
    doc = read(Drawing((Sheet(20, 20, everything()),)))
    assert doc.dxfversion == "AC1018"  # R2004: the oldest DXF with true colours
    assert doc.header["$INSUNITS"] == 4 and doc.units == ezdxf.units.MM
    assert doc.header["$MEASUREMENT"] == 1  # metric
    assert doc.header["$LWDISPLAY"] == 1
    # and declares nothing it does not use: no dashed linetype a laser program would cut as
    # dashes, no text style naming a font the maker's machine may lack
    assert [lt.dxf.name for lt in doc.linetypes] == ["ByBlock", "ByLayer", "Continuous"]
    assert [st.dxf.name for st in doc.styles] == ["Standard"]


def test_closed_rings_open_lines_and_odd_parity_fills():
    doc = read(Drawing((Sheet(20, 20, everything()),)))
    msp = doc.modelspace()
    cuts = msp.query('LWPOLYLINE[layer=="cut"]')
    assert [c.closed for c in cuts] == [True, True]  # the ring and its hole
    assert shapely.Polygon(cuts[0].get_points("xy"), [cuts[1].get_points("xy")]).area == \
        pytest.approx(64 - 9)
    (fold,) = msp.query('LWPOLYLINE[layer=="fold"]')
    assert not fold.closed
    (hatch,) = msp.query("HATCH")
    assert hatch.dxf.solid_fill == 1 and hatch.dxf.hatch_style == 0  # odd parity
    assert all(p.is_closed for p in hatch.paths)
    assert hatch.rgb == (0, 255, 0) and hatch.dxf.color == 3  # green is ACI 3


@pytest.mark.parametrize("role, colour", [("cut", 1), ("score", 5), ("engrave", 7),
                                          ("paint", 8), ("label", 7), ("guide", 9)])
def test_layer_colours_by_role_and_hidden_layers_off(role, colour):
    shown = Layer("shown", role, (polylines_from_lines([[(0, 0), (1, 1)]]),))
    hidden = Layer("hidden", role, (polylines_from_lines([[(0, 0), (1, 1)]]),
                                    polygons_from_shapely([shapely.box(0, 0, 1, 1)],
                                                          Style(None, 0, "#123456"))),
                   visible=False)
    doc = read(Drawing((Sheet(20, 20, (shown, hidden)),)))
    assert doc.layers.get("shown").color == colour and doc.layers.get("shown").is_on()
    assert doc.layers.get("hidden").is_off()
    assert doc.layers.get("hidden-123456").is_off()  # its fills are hidden with it


def test_fill_layers_in_their_colour_by_index_and_true_colour():
    teal = "#127A7A"  # upper case: the layer name is lower case all the same
    layer = Layer("tiles", "paint", (polygons_from_shapely(
        [shapely.box(0, 0, 1, 1), shapely.box(2, 0, 3, 1)], Style(None, 0, None),
        fills=[teal, None]),))
    doc = read(Drawing((Sheet(20, 20, (layer,)),)))
    entry = doc.layers.get("tiles-127a7a")
    assert entry.rgb == (0x12, 0x7A, 0x7A)
    # the index is the nearest of AutoCAD's 255 colours
    distance = lambda i: sum((a - b) ** 2 for a, b in zip(colors.aci2rgb(i), entry.rgb))  # noqa: E731
    assert entry.color in range(1, 256)
    assert distance(entry.color) == min(distance(i) for i in range(1, 256))
    (hatch,) = doc.modelspace().query("HATCH")  # the unfilled square makes none
    assert len(hatch.paths) == 1


def test_true_colours_and_line_weights():
    layers = (Layer("ink", "paint", (polylines_from_lines([[(0, 0), (1, 1)]],
                                                         Style("#0a0b0c", 0.27)),)),
              Layer("cut", "cut", (polylines_from_lines([[(0, 0), (1, 1)]],
                                                        Style("#0a0b0c", 0.27)),)),
              Layer("hair", "paint", (polylines_from_lines([[(0, 0), (1, 1)]],
                                                          Style("#000000", 0.0)),)),
              Layer("label", "label", (Text(1, 1, "x", 2.0, fill="#0000FF"),)))
    msp = read(Drawing((Sheet(20, 20, layers),))).modelspace()
    (ink,) = msp.query('LWPOLYLINE[layer=="ink"]')
    (cut,) = msp.query('LWPOLYLINE[layer=="cut"]')
    (hair,) = msp.query('LWPOLYLINE[layer=="hair"]')
    (text,) = msp.query("TEXT")
    assert ink.rgb == (10, 11, 12) and cut.rgb == (10, 11, 12)
    assert ink.dxf.lineweight == 25  # 0.27 mm: 0.25 is the nearest of DXF's weights
    assert cut.dxf.lineweight == -1  # BYLAYER: a laser cuts hairlines
    assert hair.rgb == (0, 0, 0) and hair.dxf.lineweight == -1  # 0 mm: no weight
    assert text.rgb == (0, 0, 255) and text.dxf.lineweight == -1  # text has no line weight
    # the outline of a polygon keeps its weight off laser layers too
    ring = Layer("ring", "guide", (polygons_from_shapely([shapely.box(0, 0, 5, 5)],
                                                         Style("#0a0b0c", 0.5)),))
    (outline,) = read(Drawing((Sheet(20, 20, (ring,)),))).modelspace().query("LWPOLYLINE")
    assert outline.closed and outline.dxf.lineweight == 50


@pytest.mark.parametrize("width, weight", [(0.51, 50), (0.52, 53), (0.05, 5), (3.0, 211)])
def test_line_weight_is_the_nearest_dxf_weight_in_hundredths_of_a_mm(width, weight):
    ink = Layer("ink", "paint", (polylines_from_lines([[(0, 0), (1, 1)]], Style("#0a0b0c", width)),))
    (line,) = read(Drawing((Sheet(20, 20, (ink,)),))).modelspace().query("LWPOLYLINE")
    assert line.dxf.lineweight == weight


@pytest.mark.parametrize("anchor, align", [("start", "BOTTOM_LEFT"),
                                           ("middle", "BOTTOM_CENTER"),
                                           ("end", "BOTTOM_RIGHT")])
def test_text_anchor_height_and_angle(anchor, align):
    label = Layer("l", "label", (Text(12.5, 7.25, "Ab", 3.5, anchor, -20.0),))
    (text,) = read(Drawing((Sheet(20, 20, (label,)),))).modelspace().query("TEXT")
    placement, point, *_ = text.get_placement()
    assert placement.name == align
    assert tuple(point)[:2] == (12.5, 7.25)
    assert text.dxf.height == 3.5 and text.dxf.rotation == -20.0


def test_layer_names_without_characters_cad_refuses():
    label = Layer('a<b>c/d\\e"f:g;h?i*j|k=l`m nX', "label", (Text(1, 1, "x", 2.0),))
    doc = read(Drawing((Sheet(20, 20, (label,)),)))
    (text,) = doc.modelspace().query("TEXT")
    assert text.dxf.layer == "a_b_c_d_e_f_g_h_i_j_k_l_m nX"
    assert len(doc.audit().errors) == 0


def test_comments_carry_title_and_metadata_on_one_line_each():
    drawing = Drawing((Sheet(20, 20, everything()),), "a  title\nover lines",
                      (("generator", "weave-cut 1"), ("command", "weave-cut  a\tb")))
    data = dxf.render(drawing).decode()
    comments = [t.value for t in ezdxf.comments.from_stream(io.StringIO(data))]
    assert comments == ["title: a title over lines", "generator: weave-cut 1",
                        "command: weave-cut a b"]


def test_text_beyond_the_code_page_is_escaped_and_reads_back():
    label = Layer("l", "label", (Text(1, 1, "Ä ∑ 字", 2.0),))
    data = dxf.render(Drawing((Sheet(20, 20, (label,)),), "β"))
    raw = data.decode("cp1252")  # the file's code page; what it lacks is escaped
    assert "Ä \\U+2211 \\U+5b57" in raw and "title: \\U+03b2" in raw
    doc = ezdxf.read(io.StringIO(raw))
    assert doc.header["$DWGCODEPAGE"] == "ANSI_1252"
    (text,) = doc.modelspace().query("TEXT")
    assert ezdxf.decode_dxf_unicode(text.dxf.text) == "Ä ∑ 字"


def test_same_bytes_every_time_and_ezdxf_left_as_found():
    before = ezdxf.options.write_fixed_meta_data_for_testing
    drawing = Drawing((Sheet(20, 20, everything()), Sheet(10, 10, everything())), "t")
    assert dxf.render(drawing) == dxf.render(drawing)
    assert ezdxf.options.write_fixed_meta_data_for_testing == before


@pytest.mark.parametrize("laser", ["lightburn", "epilog-uls", "ponoko"])
def test_every_laser_line_has_its_preset_colour_in_the_dxf(laser, tmp_path):
    """A puzzle with engraved numbers, as a CAD or laser program resolves each entity's colour
    (its true colour, else its layer's colour index; index 7 is black on a white sheet): cut,
    score and engrave lines are the colours the laser preset names for them (the summary and
    README.txt say so)."""
    from click.testing import CliRunner

    from weavecut import presets
    from weavecut.cli import cli

    result = CliRunner().invoke(cli, ["-q", "puzzle", "--levels", "2", "--size", "20cm",
                                      "--numbers", "--laser", laser, "-o", str(tmp_path)])
    assert result.exit_code == 0, result.output
    preset = presets.load("laser", laser)
    seen = set()
    for path in tmp_path.glob("*.dxf"):
        doc = ezdxf.readfile(path)
        for e in doc.modelspace():
            role = e.dxf.layer.split("-")[0]
            if e.has_dxf_attrib("true_color"):
                rgb = tuple(e.rgb)
            else:
                aci = doc.layers.get(e.dxf.layer).dxf.color
                rgb = (0, 0, 0) if aci == 7 else tuple(colors.aci2rgb(aci))
            assert "#%02x%02x%02x" % rgb == preset[role]["colour"].lower(), (path.name, role)
            seen.add(role)
    assert seen == {"cut", "score", "engrave"}
