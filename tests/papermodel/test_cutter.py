"""Strips cut by machine: print-and-cut pages with registration marks and their cut
files, and strips laser-cut from coloured card. The files are read back with ezdxf and an XML
parser; the mark geometry is rebuilt from the preset's TOML values, not from the code's."""

from __future__ import annotations

import json
import re
import tomllib
import xml.etree.ElementTree as ET
from dataclasses import replace
from functools import lru_cache
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from weavecut import export, inputs, presets
from weavecut.layout.drawing import Polygons, Polylines, Text
from weavecut.layout.labels import text_box
from weavecut.layout.lasersetup import laser
from weavecut.papermodel import cardkit, cutter_words, lasercard, printcut
from weavecut.papermodel.book import strand_book
from weavecut.papermodel.pages import CUT, PageArea
from weavecut.subdivision import subdivide
from weavecut.units import to_mm
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

A4 = (210.0, 297.0)
CUTTERS = ("silhouette", "cricut", "scanncut")
SVG = "{http://www.w3.org/2000/svg}"


@lru_cache(maxsize=None)
def weaves():
    return tuple(snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2)))


@lru_cache(maxsize=None)
def cut_book(name: str, bleed: float = printcut.BLEED):
    """The print-and-cut book of cutter ``name``, laid out as ``strands --cutter`` lays it."""
    machine = printcut.cutter(name)
    book = strand_book(list(weaves()), palette("maritime-4"), A4, 20.0, machine.margin,
                       limit=machine.limit(*A4), gap=printcut.WASTE, bleed=bleed,
                       **({"words": cutter_words.cutter_words(machine, Path("sq.pdf"))} if bleed
                          else {}))
    return machine, printcut.with_marks(book, machine)


def preset_values(name: str) -> dict:
    """The preset's values in mm, read from its TOML file by tomllib (not by weave-cut)."""
    doc = tomllib.loads(presets.find("cutters", name).read_text())
    return {k: (to_mm(v) if k not in ("name", "description", "marks", "brand") else v)
            for k, v in doc.items()}


def layer_polygons(sheet, name: str) -> list:
    return [g for layer in sheet.layers if layer.name == name for s in layer.shapes
            if isinstance(s, Polygons) for g in s.to_shapely().tolist()]


def svg_rings(path: Path) -> list[np.ndarray]:
    """Closed rings of every path in the SVG, in the page's frame (y up, mm)."""
    root = ET.parse(path).getroot()
    height = float(root.get("viewBox").split()[3])
    rings = []
    for p in root.iter(f"{SVG}path"):
        for sub in p.get("d").split("M")[1:]:
            xy = np.array(re.findall(r"-?[\d.]+(?:e-?\d+)?", sub), dtype=float).reshape(-1, 2)
            rings.append(np.column_stack([xy[:, 0], height - xy[:, 1]]))
    return rings


def dxf_rings(path: Path, layer: str) -> list[np.ndarray]:
    doc = ezdxf.readfile(path)
    return [np.array([(x, y) for x, y, *_ in e.get_points()])
            for e in doc.modelspace().query(f'LWPOLYLINE[layer=="{layer}"]')]


def assert_coincide(printed: list, cut_rings: list[np.ndarray], tol: float = 0.01) -> None:
    """Every printed outline has exactly one cut outline within ``tol`` mm (Hausdorff), and
    there are as many cut outlines as printed ones."""
    cut = np.array([shapely.Polygon(r) for r in cut_rings], dtype=object)
    assert len(cut) == len(printed)
    far = np.array([[shapely.hausdorff_distance(p, c) for c in cut] for p in printed])
    assert (np.sort(far, axis=1)[:, 0] < tol).all()
    assert sorted(np.argmin(far, axis=1).tolist()) == list(range(len(cut)))


# --- print and cut -------------------------------------------------------------------------

@pytest.mark.parametrize("name", CUTTERS)
@pytest.mark.parametrize("fmt", ["svg", "dxf"])
def test_cut_file_is_registered_to_the_printed_page(name, fmt, tmp_path):
    _, book = cut_book(name)
    files = printcut.cut_files(book)
    assert [n for n, _ in files] == list(book.strip_pages)
    for n, drawing in files:
        page = book.drawing.sheets[n - 1]
        assert (drawing.sheets[0].width, drawing.sheets[0].height) == (page.width, page.height)
        path = tmp_path / f"p{n}.{fmt}"
        export.write(drawing, path)
        rings = svg_rings(path) if fmt == "svg" else dxf_rings(path, "cut")
        # the page transform is the identity: the cut file has the page's size and frame, its
        # outlines those of the strips on the page (printed without cut lines, see below)
        assert_coincide([p.cut for k, p in book.pieces if k == n], rings)
        # and nothing else (the README: "no frame: only the cuts"): no entity on another
        # layer, no shape besides the paths
        if fmt == "dxf":
            assert len(ezdxf.readfile(path).modelspace()) == len(rings)
        else:
            shapes = [e for e in ET.parse(path).getroot().iter()
                      if e.tag.split("}")[-1] in ("path", "rect", "line", "polyline", "polygon",
                                                  "circle", "ellipse", "text")]
            assert len(shapes) == len(drawing.sheets[0].layers) == 1


def painted(sheet) -> list[tuple[shapely.Geometry, str]]:
    """(polygon, fill) of every painted polygon of ``sheet``."""
    return [(g, fill) for layer in sheet.layers if layer.role == "paint"
            for s in layer.shapes if isinstance(s, Polygons)
            for g, fill in zip(s.to_shapely().tolist(), s.fills or [s.style.fill] * s.n_polygons)]


def legend(sheet) -> list[str]:
    """The texts of the page's furniture (title, legend, scale bar)."""
    return [s.text for layer in sheet.layers if layer.name == "page" for s in layer.shapes
            if isinstance(s, Text)]


def assert_bled(sheet, strips, bleed: float) -> None:
    """No stroke in the cut colour and no "cut" legend entry on ``sheet``; a band ``bleed``
    wide outside every strip's cut line is painted, in that strip's colours only, and by
    nothing that reaches past that strip's own bleed (a neighbour's)."""
    assert not [s for layer in sheet.layers for s in layer.shapes
                if isinstance(s, (Polygons, Polylines))
                and (s.style.stroke or "").lower() == CUT.stroke.lower()]
    assert "cut" not in legend(sheet)
    # nor a tile's thin outline along the cut line: it would show on the strip's edge too
    stroked = shapely.union_all([
        g for layer in sheet.layers for s in layer.shapes if getattr(s, "style", None)
        and s.style.stroke for g in (
            shapely.boundary(s.to_shapely()).tolist() if isinstance(s, Polygons)
            else [shapely.LineString(xy) for xy in s.lines()] if isinstance(s, Polylines)
            else [])])
    for s in strips:
        edge = shapely.boundary(s.cut)
        assert shapely.intersection(stroked, edge.buffer(0.05)).length < 0.05 * edge.length
    paint = painted(sheet)
    grown = [shapely.buffer(s.cut, bleed + 1e-6) for s in strips]
    for s, room in zip(strips, grown):
        band = shapely.buffer(s.cut, 0.98 * bleed).difference(s.cut)  # 0.98: round-off
        over = [(g, fill) for g, fill in paint if g.intersection(band).area > 1e-9]
        assert over, s.label
        colours = {*s.fills, *(() if s.flap is None else (s.flap_fill,))}
        assert {fill for _, fill in over} <= colours, s.label
        assert all(room.covers(g) for g, _ in over), s.label
        assert band.difference(shapely.union_all([g for g, _ in over])).area < 1e-6 * band.area
    # two bleeds never meet: the strips are packed more than two bleeds apart
    assert all(not a.intersects(b) for i, a in enumerate(grown) for b in grown[i + 1:])


@pytest.mark.parametrize("name", CUTTERS)
def test_a_print_and_cut_page_prints_no_cut_line_and_bleeds_the_strips_colours(name):
    """A cutter that cuts 0.3-0.5 mm off the printed page would leave a printed cut line (or
    white paper) on the strip's edge: print-and-cut pages print no cut line and no "cut" legend
    entry, and every strip's colours reach ``BLEED`` past its cut line, clear of its
    neighbours' (packed ``WASTE`` apart); no tile outline runs along the cut line either.
    Planted: the bleed 0 (the cut lines printed again), the cut lines printed over the bleed,
    the tiles' outlines kept along it, or the bleed half as wide, fails."""
    assert 2 * printcut.BLEED < printcut.WASTE  # a blank gap between two strips' bleeds
    machine, book = cut_book(name)
    assert printcut.BLEED < machine.clearance  # and between a bleed and the marks
    for n in book.strip_pages:
        assert_bled(book.drawing.sheets[n - 1], [p for k, p in book.pieces if k == n],
                    printcut.BLEED)
    for sheet in book.drawing.sheets:  # page 1's and page 2's legends say no "cut" either
        assert "on top" not in legend(sheet) or "cut" not in legend(sheet)
    assert "on top" in legend(book.drawing.sheets[0])
    _, plain = cut_book(name, 0.0)  # without a bleed the page is as printed for scissors
    sheet = plain.drawing.sheets[plain.strip_pages[0] - 1]
    with pytest.raises(AssertionError):
        assert_bled(sheet, [p for k, p in plain.pieces if k == plain.strip_pages[0]],
                    printcut.BLEED)
    assert layer_polygons(sheet, "cut") and "bleed" not in {x.name for x in sheet.layers}


@pytest.mark.parametrize("name", CUTTERS)
def test_marks_lie_where_the_preset_says(name):
    v = preset_values(name)
    machine, book = cut_book(name)
    w, h = A4
    i, n, t = v["inset"], v["length"], v["thickness"]
    for number in book.strip_pages:
        sheet = book.drawing.sheets[number - 1]
        marks = layer_polygons(sheet, "registration")
        if v["marks"] == "frame":  # Design Space prints its own round the print image
            assert marks == [] and machine.own_marks
            continue
        else:
            # (page corner the mark sits in, its kind): Type 1 has the square top-left
            kinds = {(0, 1): "square" if v["marks"] == "square-and-corners" else "L",
                     (1, 1): "L", (0, 0): "L"}
            if v["marks"] == "corners":
                kinds[(1, 0)] = "L"
            assert len(marks) == len(kinds)
            for (cx, cy), kind in kinds.items():
                x = (i, i + n) if cx == 0 else (w - i - n, w - i)
                y = (i, i + n) if cy == 0 else (h - i - n, h - i)
                mine = [m for m in marks if np.allclose(m.bounds, (x[0], y[0], x[1], y[1]))]
                assert len(mine) == 1
                m = mine[0]
                assert m.area == pytest.approx(n * n if kind == "square" else 2 * n * t - t * t)
                outer = shapely.Point(x[cx], y[cy])  # the L's corner faces the page's corner
                inner = shapely.Point(x[1 - cx], y[1 - cy])
                assert m.covers(outer) and m.covers(inner) == (kind == "square")
        # inside the printable margin, clear of every strip by the clearance
        printable = shapely.box(printcut.PRINTER_EDGE, printcut.PRINTER_EDGE,
                                w - printcut.PRINTER_EDGE, h - printcut.PRINTER_EDGE)
        assert all(printable.covers(m) for m in marks)
        strips = [p.outline for k, p in book.pieces if k == number]
        gap = min(shapely.distance(m, s) for m in marks for s in strips)
        assert gap >= v["clearance"] - 1e-9
        # and clear of the page's furniture: no text box touches a mark
        texts = [text_box(s) for layer in sheet.layers for s in layer.shapes
                 if isinstance(s, Text)]
        assert not any(m.intersects(b) for m in marks for b in texts)


def test_strips_stay_inside_the_area_the_cutter_reads():
    v = preset_values("cricut")
    _, book = cut_book("cricut")
    w, h = A4
    area = shapely.box((w - v["max_width"]) / 2, (h - v["max_height"]) / 2,
                       (w + v["max_width"]) / 2, (h + v["max_height"]) / 2)
    assert v["max_width"] == pytest.approx(6.75 * 25.4)
    assert all(area.covers(p.outline) for _, p in book.pieces)


def test_a_cricut_page_is_a_print_image_design_space_prints_and_cuts_round():
    """Cricut Design Space prints the image it is given with its own sensor marks and cuts the
    outline of what the image covers: each strip page's print image paints exactly that
    page's cut outlines (no cut line, mark, title or legend in it), within 6.75 x 9.25 in;
    page 1 and the steps send the maker to the print images, not to printing the PDF's
    pages. Planted: the page furniture left in the image, or a strip left out, fails."""
    machine, book = cut_book("cricut")
    assert machine.own_marks and not printcut.cutter("silhouette").own_marks
    for n, drawing in printcut.print_files(book):
        (sheet,) = drawing.sheets
        assert {layer.name for layer in sheet.layers} <= {"strips", "arrows", "labels"}
        painted = shapely.union_all([g for layer in sheet.layers if layer.role == "paint"
                                     for s in layer.shapes if isinstance(s, Polygons)
                                     for g in s.to_shapely().tolist()])
        cuts = shapely.union_all([p.cut for k, p in book.pieces if k == n])
        assert painted.symmetric_difference(cuts).area < 1e-6 * cuts.area
        x0, y0, x1, y1 = painted.bounds
        assert x1 - x0 <= 6.75 * 25.4 and y1 - y0 <= 9.25 * 25.4
    from weavecut.kitpage.document import _purpose  # the kit page's card says what it is for
    assert "Design Space" in _purpose([".svg"], drawing, {})
    words = cutter_words.cutter_words(machine, Path("kit/sq.pdf"))
    said = words.sources(book) + " " + words.cut
    assert "sq-pNN-print.svg" in said and "sensor marks" in said and "Flatten" in said
    assert "do not print the strip pages" in said and "registration marks" not in said


def test_cut_geometry_is_ready_to_cut():
    _, book = cut_book("silhouette")
    report = printcut.cut_report([p.outline for _, p in book.pieces])
    assert report.simple and report.duplicates == 0 and report.n_outlines == len(book.pieces)
    assert report.min_feature >= preset_values("silhouette")["min_feature"]
    assert report.length == pytest.approx(sum(p.outline.length for _, p in book.pieces))


def test_cut_report_finds_what_a_knife_trips_on():
    a, b = shapely.box(0, 0, 10, 10), shapely.box(10, 0, 20, 10)  # one shared side
    assert printcut.cut_report([a, b]).duplicates == 1
    assert printcut.cut_report([a, shapely.box(12, 0, 20, 10)]).duplicates == 0
    bowtie = shapely.Polygon([(0, 0), (10, 10), (10, 0), (0, 10)])
    assert not printcut.cut_report([bowtie]).simple
    holed = shapely.box(0, 0, 10, 10).difference(shapely.box(4, 4, 6, 6))
    assert not printcut.cut_report([holed]).simple
    # the narrowest feature is bisected on a 0.05 mm grid: a 0.8 mm strip, which a disc 0.8 mm
    # across fits only to rounding, reads 0.75 or 0.8
    assert printcut.cut_report([shapely.box(0, 0, 30, 0.8)]).min_feature == pytest.approx(
        0.8, abs=0.05 + 1e-9)
    # a V cut 10 mm into a 30 x 20 mm piece, 1.2 mm wide at its mouth: by hand, its corner
    # (15, 20) lies 10 x 1.2 / hypot(1.2, 10) = 1.19 mm from the other side; no part of the
    # paper is that thin (the old label tab's shoulder was such a notch)
    notch = shapely.Polygon([(0, 0), (30, 0), (30, 20), (16.2, 20), (15, 10), (15, 20), (0, 20)])
    assert printcut.cut_report([notch]).min_feature == pytest.approx(12 / np.hypot(1.2, 10))
    assert printcut.cut_report([shapely.box(0, 0, 30, 20)]).min_feature >= 19.95


def test_cut_order_starts_near_the_cutters_home():
    outlines = [shapely.box(x, y, x + 5, y + 5) for x in (10, 100) for y in (10, 200)]
    rings = printcut.ordered_outlines(outlines, (0.0, 297.0))
    assert shapely.Point(rings[0][0]).distance(shapely.box(10, 200, 15, 205)) < 1e-9
    assert all(np.allclose(r[0], r[-1]) for r in rings)


def test_a_cutter_preset_is_checked(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('marks = "square-and-corners"\ninset = "2mm"\nlength = "5mm"\n'
                   'thickness = "0.5mm"\nclearance = "2mm"\nmin_feature = "1mm"\n')
    with pytest.raises(printcut.CutterError, match="home printers"):
        printcut.cutter(str(bad)).check(*A4)
    bad.write_text(bad.read_text().replace("square-and-corners", "circles"))
    with pytest.raises(presets.PresetError, match="circles"):
        printcut.cutter(str(bad))


# --- laser from coloured card --------------------------------------------------------------

@lru_cache(maxsize=None)
def card(sheet=A4, kerf=0.1):
    book = strand_book(list(weaves()), palette("maritime-4"), sheet, 20.0,
                       lasercard.SHEET_MARGIN)
    return book, lasercard.card_sheets([p for _, p in book.pieces], book.colours, laser(),
                                       kerf, sheet)


def test_every_strip_once_on_a_sheet_of_its_colour(tmp_path):
    book, cut = card()
    seen = []
    for n, (drawing, colour, pieces) in enumerate(zip(cut.sheets, cut.colours, cut.pieces)):
        assert dict(drawing.metadata)["card"] == colour
        assert {book.colours[p.strand] for p in pieces} == {colour}
        seen += [p.label for p in pieces]
        path = tmp_path / f"sheet{n}.dxf"
        export.write(drawing, path)
        rings = dxf_rings(path, "cut")
        kerf = [shapely.buffer(p.cut, 0.05, join_style="mitre", mitre_limit=8.0)
                for p in pieces]
        assert_coincide(kerf, rings)
        polys = [shapely.Polygon(r) for r in rings]
        sheet = shapely.box(0, 0, *A4)
        assert all(sheet.contains(p) for p in polys)
        for i, a in enumerate(polys):  # no two strips overlap (a cut needs the gap)
            assert all(a.distance(b) >= 0.1 - 1e-6 for b in polys[i + 1:])
    assert sorted(seen) == sorted(p.label for _, p in book.pieces)
    assert len(set(cut.colours)) == len(set(book.colours))


def test_engraved_text_lies_inside_its_strip_with_a_margin(tmp_path):
    _, cut = card()
    for n, (drawing, pieces) in enumerate(zip(cut.sheets, cut.pieces)):
        path = tmp_path / f"sheet{n}.dxf"
        export.write(drawing, path)
        lines = [shapely.LineString(r) for r in dxf_rings(path, "engrave") if len(r) > 1]
        assert lines
        inner = [shapely.buffer(p.cut, -lasercard.ENGRAVE_MARGIN + 1e-3,
                                join_style="mitre") for p in pieces]
        tree = shapely.STRtree(inner)
        for line in lines:
            assert any(inner[j].covers(line) for j in tree.query(line))
        # every strip carries its ID, and the IDs of the strands on top where it goes under
        for p, (coords, offsets, owner) in zip(pieces, cut.texts[n]):
            assert len(coords) and shapely.buffer(p.cut, -0.999).covers(
                shapely.MultiPoint(coords))
            # one label per printed one, and no two labels of a strip touch
            assert len(set(owner.tolist())) == len(p.texts)
            point_owner = np.repeat(owner, np.diff(offsets))
            hulls = [shapely.MultiPoint(coords[point_owner == k]).convex_hull
                     for k in range(len(p.texts))]
            assert not any(a.intersects(b) for i, a in enumerate(hulls) for b in hulls[i + 1:])
    assert cut.smallest_label >= lasercard.MIN_ENGRAVED


def test_the_card_colour_page_names_every_strands_card(tmp_path):
    """Page 3 of the card's instructions: "card navy (#0b3c5d): sheet 1" (or "sheets 1, 2":
    the colour by the palette's own name) then "strands A1, A3, ...": every strand once, under
    its colour, on the sheets that hold it; then how much of each sheet its strips fill from
    the top-left corner, which the cut lines read back from the sheet's DXF must fit."""
    book, cut = card()
    named_in_toml = dict(zip(*(tomllib.loads(presets.find("palettes", "maritime-4").read_text())[k]
                               for k in ("colours", "colour_names"))))
    page = cardkit.card_colour_sheet(cut, PageArea(*A4, 10.0), "test", laser(),
                                     called=palette("maritime-4").called)
    texts = [t.text for layer in page.layers for t in layer.shapes if isinstance(t, Text)]
    heads = [k for k, t in enumerate(texts) if t.startswith("card ") and ": sheet" in t]
    assert len(heads) == len(set(book.colours))
    named = {}
    for k in heads:
        name, _, sheets = texts[k].removeprefix("card ").partition(": ")
        colour = re.fullmatch(r"(.+) \((#[0-9a-f]{6})\)", name)
        assert colour and colour[1] == named_in_toml[colour[2]]
        colour = colour[2]
        numbers = [int(n) for n in re.sub(r"sheets? ", "", sheets).split(", ")]
        assert [cut.colours[n - 1] for n in numbers] == [colour] * len(numbers)
        runs, _, used = texts[k + 1].removeprefix("strands ").partition("; ")
        for label in strip_names(runs):
            assert label not in named
            assert any(p.label.split(" ")[0] == label for n in numbers for p in cut.pieces[n - 1])
            named[label] = colour
        sizes = re.findall(r"(\d+) x (\d+) mm", used)
        assert len(sizes) == len(numbers) and used.endswith("at the top left")
        for n, (w, h) in zip(numbers, sizes):
            path = tmp_path / f"sheet{n}.dxf"
            export.write(cut.sheets[n - 1], path)
            xy = np.concatenate(dxf_rings(path, "cut"))
            height = cut.sheets[n - 1].sheets[0].height
            edge = lasercard.SHEET_MARGIN  # the stated size keeps the margin round the strips
            assert abs(int(w) - (xy[:, 0].max() + edge)) <= 1.0
            assert abs(int(h) - (height - xy[:, 1].min() + edge)) <= 1.0
    strips = {p.label.split(" ")[0]: book.colours[p.strand] for _, p in book.pieces}
    assert named == strips


def strip_names(runs: str) -> list[str]:
    """The strip IDs of "A1, A3-A5" (an independent reading of ``strip_runs``)."""
    out = []
    for part in runs.split(", "):
        first, _, last = part.partition("-")
        if not last:
            out.append(first)
            continue
        head = first.rstrip("0123456789")
        out += [f"{head}{n}" for n in range(int(first[len(head):]), int(last[len(head):]) + 1)]
    return out


@pytest.mark.parametrize("name, shows", [("lightburn", True), ("ponoko", False)])
def test_card_cut_lines_show_on_screen_where_the_laser_program_allows(name, shows, tmp_path):
    """LightBurn ignores stroke widths: its cut and engrave lines are hairlines, written
    0.25 mm wide (about a pixel at 96 dpi), so a card sheet rendered at 96 dpi shows its red
    cut lines; Ponoko's rules ask for 0.01 mm lines, which stay so (and stay invisible on
    screen). Read back with an XML parser and rendered with rsvg-convert."""
    import shutil
    import subprocess

    from PIL import Image

    book, _ = card()
    las = laser(name)
    cut = lasercard.card_sheets([p for _, p in book.pieces], book.colours, las, 0.1, A4)
    path = tmp_path / "sheet.svg"
    export.write(cut.sheets[0], path)
    ink = las.style("cut").stroke
    paths = [p for p in ET.parse(path).getroot().iter("{http://www.w3.org/2000/svg}path")
             if p.get("stroke") == ink]
    assert paths
    for p in paths:
        assert p.get("vector-effect") is None
        assert p.get("stroke-width") == ("0.25" if shows else "0.01")
    if shutil.which("rsvg-convert") is None:
        pytest.skip("rsvg-convert is not installed")
    png = tmp_path / "sheet.png"
    subprocess.run(["rsvg-convert", "-d", "96", "-p", "96", "-b", "white", "-o", str(png),
                    str(path)], check=True)
    rgb = np.asarray(Image.open(png).convert("RGB")).astype(int)
    target = np.array([int(ink[i:i + 2], 16) for i in (1, 3, 5)])
    near = (np.abs(rgb - target).max(axis=2) < 60).sum()
    assert (near > 1000) == shows  # the outlines of every strip, a pixel wide


def test_engraving_and_scoring_come_before_the_cut():
    _, cut = card()
    roles = [layer.role for layer in cut.sheets[0].sheets[0].layers]
    assert roles == ["engrave", "score", "cut"]


# --- the command ---------------------------------------------------------------------------

def test_strands_cutter_and_laser_card_commands(tmp_path):
    from weavecut.cli import cli as main

    runner = CliRunner()
    out = tmp_path / "sq.pdf"
    res = runner.invoke(main, ["strands", "square-grid:2x2", "--tile-size", "20mm",
                               "--cutter", "silhouette", "--json", "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert json.loads(res.output)["label_violations"] == 0  # the marks cover no text
    info = json.loads(res.output)["cutter"]
    assert info["closed_simple"] and info["duplicate_segments"] == 0
    assert sorted(Path(f).name for f in info["cut_files"]) == ["sq-p03-cut.dxf", "sq-p03-cut.svg"]
    res = runner.invoke(main, ["strands", "square-grid:2x2", "--tile-size", "20mm",
                               "--laser-card", "--material", "card-300gsm-12in", "--json",
                               "-o", str(tmp_path / "card")])
    assert res.exit_code == 0, res.output
    info = json.loads(res.output)
    assert info["sheet_mm"] == pytest.approx([304.8, 304.8])
    assert (tmp_path / "card" / "strands-assembly.pdf").is_file()
    assert len(list((tmp_path / "card").glob("strands-card-*.dxf"))) == info["sheets"]
    fine = tmp_path / "fine.toml"  # a cutter that wants features of 50 mm is warned
    fine.write_text(presets.find("cutters", "silhouette").read_text().replace(
        'min_feature = "1mm"', 'min_feature = "50mm"'))
    res = runner.invoke(main, ["strands", "square-grid:2x2", "--tile-size", "20mm", "--cutter",
                               str(fine), "-o", str(tmp_path / "fine.pdf")])
    assert res.exit_code == 0 and "drag knife tears below 50 mm" in res.output
    for args, message in ((["--cutter", "nope", "-o", "x.pdf"], "unknown cutter"),
                          (["--cutter", "cricut", "--laser-card", "-o", "x"], "not both"),
                          (["--material", "card-300gsm", "-o", "x.pdf"], "--laser-card")):
        res = runner.invoke(main, ["strands", "square-grid:2x2", *args[:-1],
                                   str(tmp_path / args[-1])])
        assert res.exit_code != 0 and message in res.output and "Traceback" not in res.output


def test_a_label_tab_is_cut_with_its_strip_and_its_id_engraved_on_it(tmp_path):
    """A strip whose ID sits on a label tab (the pentagon flower's border strips at 23 cm): the
    laser cuts the tab with the strip, engraves the ID on the tab and the line where the tab is
    cut off; read back from the DXF."""
    from weavecut.papermodel.strip_labels import label_flap

    book, _ = card()
    pieces = []
    for _, p in book.pieces[:6]:  # six strips given tabs, as the border strips have
        with_tab, label = label_flap(p, p.label)
        pieces.append(replace(with_tab, texts=(label, *p.texts[1:])))
    assert all(p.flap is not None for p in pieces)
    cut = lasercard.card_sheets(pieces, book.colours, laser(), 0.1, A4)
    for n, (drawing, placed) in enumerate(zip(cut.sheets, cut.pieces)):
        path = tmp_path / f"sheet{n}.dxf"
        export.write(drawing, path)
        rings = [shapely.Polygon(r) for r in dxf_rings(path, "cut")]
        for p in placed:
            assert sum(r.buffer(1e-3).covers(p.flap) for r in rings) == 1  # the tab is cut
        # one closed, simple ring per strip: no slit where the tab meets its tile
        assert all(r.exterior.is_simple and r.is_valid for r in rings)
        engraved = [shapely.LineString(r) for r in dxf_rings(path, "engrave") if len(r) > 1]
        for p, (coords, offsets, owner) in zip(placed, cut.texts[n]):
            id_strokes = shapely.MultiPoint(coords[np.repeat(owner, np.diff(offsets)) == 0])
            assert p.flap.covers(id_strokes)  # the ID engraved on the tab
            edge = shapely.buffer(p.flap_edge, 1e-3)
            assert any(edge.covers(line) and line.length > 1.0 for line in engraved)


def test_a_cutter_is_named_by_its_preset(tmp_path):
    """Each preset names itself (the name reports print); a file of one's own keeps its name."""
    for name in ("cricut", "scanncut", "silhouette"):
        assert printcut.cutter(name).name == name
    own = tmp_path / "cameo.toml"
    text = (Path(__file__).resolve().parents[2] / "templates/cutters/silhouette.toml").read_text()
    own.write_text(text.replace('name = "silhouette"', 'name = "my cameo"'))
    assert printcut.cutter(str(own)).name == "my cameo"


@pytest.mark.parametrize("name", CUTTERS)
def test_a_cut_file_starts_at_the_outline_corner_nearest_the_top_left(name, tmp_path):
    """Desktop cutters park their knife at the mat's top-left corner: each page's cut file,
    written and read back as SVG (y down, the page's top-left at 0, 0), starts cutting at the
    corner of any outline on the page nearest to that corner, and no other page corner is
    nearer to where it starts."""
    _, book = cut_book(name)
    for n, drawing in printcut.cut_files(book):
        path = tmp_path / f"p{n}.svg"
        export.write(drawing, path)
        root = ET.parse(path).getroot()
        w, h = (float(v) for v in root.get("viewBox").split()[2:])
        d = [p.get("d") for p in root.iter(f"{SVG}path")]
        rings = [np.array(re.findall(r"-?[\d.]+(?:e-?\d+)?", sub), dtype=float).reshape(-1, 2)
                 for path_d in d for sub in path_d.split("M")[1:]]
        start = rings[0][0]
        corners = np.concatenate(rings)
        assert np.hypot(*start) == pytest.approx(np.hypot(*corners.T).min(), abs=1e-3)
        others = np.array([(w, 0.0), (0.0, h), (w, h)])
        assert (np.hypot(*(others - start).T) > np.hypot(*start)).all()


def test_the_card_page_has_a_100_mm_bar_as_its_strip_is_drawn_at_100_percent():
    """Page 3 draws a strip "at 100 %": a maker checks the print against a 100 mm bar with
    ticks every 10 mm."""
    _, cut = card()
    page = cardkit.card_colour_sheet(cut, PageArea(*A4, 10.0), "test", laser())
    shapes = [s for layer in page.layers for s in layer.shapes]
    said = " ".join(s.text for s in shapes if isinstance(s, Text))
    assert re.findall(r"drawn at (\d+) %", said) == ["100"]
    assert "100 mm: check this at 100 % scale" in said
    (line,) = [s.coords for s in shapes if isinstance(s, Polylines) and len(s.coords) == 2
               and np.isclose(s.coords[:, 1], s.coords[0, 1]).all()
               and np.isclose(np.ptp(s.coords[:, 0]), 100.0)]
    (ticks,) = [s for s in shapes if isinstance(s, Polylines) and len(s.offsets) == 12]
    x = np.unique(np.round(ticks.coords[:, 0], 6))
    assert np.allclose(np.diff(x), 10.0) and x[0] == line[:, 0].min()


@pytest.mark.parametrize("box", [(0.0, 0.0, 190.0, 150.0), (0.0, 0.0, 8.0, 60.0)])
def test_a_strip_figure_says_whether_it_is_true_size_as_its_caption_does(box):
    """The flag that puts the bar on the page agrees with the caption's scale: a box too
    narrow for any strip draws one smaller and says so, without claiming 100 %."""
    _, cut = card()
    shapes, true_size = cardkit.strip_figure(cut, box)
    said = " ".join(s.text for s in shapes if isinstance(s, Text))
    (percent,) = re.findall(r"drawn at (\d+) %", said)
    assert true_size == (int(percent) == 100)
    assert true_size == (box[2] > 8.0)  # no tile of 20 mm fits 8 mm


@pytest.mark.parametrize("name", CUTTERS)
def test_a_cutters_description_says_the_marks_weave_cut_prints(name):
    """Walk of issue #29: the web form's Cricut card said "black frame", though weave-cut
    prints no marks for a Cricut (Design Space prints its own): what a preset's description
    (the web card, --help) says of marks is what its strip pages carry."""
    v = preset_values(name)
    machine, book = cut_book(name)
    said = v["description"].lower()
    printed = any(layer_polygons(book.drawing.sheets[n - 1], "registration")
                  for n in book.strip_pages)
    if not printed:
        assert machine.own_marks and "frame" not in said and "design space prints its own" in said
    else:
        assert "corner" in said and "no marks" not in said
