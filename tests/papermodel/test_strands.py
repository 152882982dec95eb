"""Paper strands: modules from symmetry, strips, pages."""

from __future__ import annotations

import re
from functools import lru_cache

import numpy as np
import pytest
import shapely
import shapely.ops
from click.testing import CliRunner

from weavecut import export, inputs
from weavecut.layout.drawing import Polylines, Text
from weavecut.papermodel.plates import free_spot as _free_spot
from weavecut.papermodel.pages import GAP, occupied
from weavecut.papermodel.book import strand_book
from weavecut.papermodel.checks import report, sheet_checks, text_checks
from weavecut.papermodel.printcut import cut_report
from weavecut.papermodel.modules import copy_colours, plan_modules
from weavecut.papermodel.strips import build_strips, model_tiles
from weavecut.papermodel.symmetry import rotate, rotation_group, strand_orbits, tile_centres
from weavecut.mesh import Mesh
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

pytestmark = pytest.mark.slow  # whole paper-model books (the pentagon flower's), shared

PRESETS = {"square-grid": (2, 4), "pentagon-flower": (3, 5)}


@lru_cache(maxsize=None)
def weaves(spec: str, levels: int):
    return tuple(snub_weaves(subdivide(inputs.get(spec), levels)))


@lru_cache(maxsize=None)
def small_book(page: str = "a4"):
    from weavecut.units import page_size
    return strand_book(list(weaves("square-grid:2x2", 2)), palette("maritime-12"),
                       page_size(page), tile_size=20.0)


@pytest.mark.parametrize("spec", PRESETS)
def test_rotation_group_of_the_presets(spec):
    levels, k = PRESETS[spec]
    sym = rotation_group(weaves(spec, levels)[-1])
    assert sym.order == k
    orbit, size = strand_orbits(sym)
    assert (size == k).all()  # no strand is fixed by a rotation


def test_asymmetric_mesh_has_trivial_group():
    mesh = inputs.get("square-grid:2x2")
    v = mesh.vertices.copy()
    v[np.argmin(np.hypot(*v.T))] += (0.12, 0.05)  # move the centre vertex off centre
    w = snub_weaves(subdivide(Mesh(v, mesh.face_offsets, mesh.face_indices), 2))[-1]
    sym = rotation_group(w)
    assert sym.order == 1
    plan = plan_modules(w)
    assert plan.k == 1 and plan.copies.shape[1] == w.n_strands and len(plan.extras) == 0


def test_strands_fixed_by_a_rotation_are_extras():
    w = weaves("square-grid:3x2", 2)[-1]
    plan = plan_modules(w)
    assert plan.k == 2 and len(plan.extras) > 0
    perm = plan.symmetry.strand_perm
    assert (perm[plan.extras] == plan.extras).all()


@pytest.mark.parametrize("spec", [*PRESETS, "square-grid:3x2"])
def test_module_copies_cover_every_strand_once_and_are_rotations(spec):
    w = weaves(spec, PRESETS.get(spec, (2,))[0])[-1]
    plan = plan_modules(w)
    every = np.concatenate([plan.copies.ravel(), plan.extras])
    assert np.array_equal(np.sort(every), np.arange(w.n_strands))
    # copy j is copy 0 turned by j * 2 pi / k: compare the strands' own tiles geometrically
    centres = tile_centres(w)
    sym = plan.symmetry
    for j in range(plan.k):
        for a, b in zip(plan.copies[0].tolist(), plan.copies[j].tolist()):
            ta, oa = w.strand(a)
            tb, ob = w.strand(b)
            pa = rotate(centres[ta[oa]], j * sym.angle, sym.centre)
            pb = centres[tb[ob]]
            assert len(pa) == len(pb)
            d = np.hypot(*(pa[:, None] - pb[None]).transpose(2, 0, 1)).min(axis=1)
            assert d.max() < 1e-6


def test_module_strands_head_the_same_way():
    w = weaves("square-grid", 2)[-1]
    heading = -np.pi / 2 - np.pi / 4
    plan = plan_modules(w, heading)
    centres = tile_centres(w)
    for s in plan.copies[0].tolist():
        t, _ = w.strand(s)
        t = t[::-1] if plan.reversed[s] else t
        d = centres[t[-1]] - centres[t[0]]
        assert np.cos(np.arctan2(d[1], d[0]) - heading) > np.cos(np.pi / 4)


@pytest.mark.parametrize("spec", PRESETS)
def test_strip_is_one_polygon_holding_all_its_tiles(spec):
    w = weaves(spec, PRESETS[spec][0])[-1]
    plan = plan_modules(w)
    strips = build_strips(w, plan, copy_colours(plan, palette("maritime-4")), 40.0,
                          np.arange(w.n_strands))
    for strip in strips:
        assert strip.outline.geom_type == "Polygon" and not strip.outline.interiors
        assert len(strip.tiles) == np.diff(w.strand_offsets)[strip.strand]
        outside = shapely.area(shapely.difference(strip.tiles, shapely.buffer(strip.outline, 1e-6)))
        assert outside.max() < 1e-6
        # long axis along x, starting at 0
        x0, y0, x1, y1 = strip.outline.bounds
        assert abs(x0) < 1e-9 and abs(y0) < 1e-9 and x1 - x0 >= y1 - y0 - 1e-9


@pytest.mark.parametrize("page, size_mm", [("a4", (210.0, 297.0)), ("letter", (215.9, 279.4))])
def test_pdf_page_sizes(tmp_path, page, size_mm):
    out = tmp_path / "s.pdf"
    export.write(small_book(page).drawing, out)
    boxes = re.findall(rb"/MediaBox\s*\[\s*([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s*\]",
                       out.read_bytes())
    assert len(boxes) == len(small_book(page).drawing.sheets) >= 2
    for box in boxes:
        x0, y0, x1, y1 = (float(b) * 25.4 / 72 for b in box)
        assert (x0, y0) == (0.0, 0.0)
        assert abs(x1 - size_mm[0]) < 1e-3 and abs(y1 - size_mm[1]) < 1e-3


@pytest.mark.parametrize("book", ["a4", "letter", "split"])
def test_strips_do_not_overlap_and_stay_in_the_printable_area(book):
    if book == "split":  # a small page: long strips are split with a glue overlap
        b = strand_book(list(weaves("square-grid:2x2", 2)), palette("maritime-12"),
                        (120.0, 150.0), tile_size=30.0, margin=8.0)
        labels = [t.text for s in b.drawing.sheets for layer in s.layers
                  if layer.name == "labels" for t in layer.shapes]
        # the part's number by itself, or with the ID where the first own tile holds the mark
        assert any(re.fullmatch(r"([A-Z]\d+ )?2/\d", t) for t in labels)
        assert any(re.fullmatch(r"[A-Z]\d+ 2/\d", p.label) for _, p in b.pieces)
    else:
        b = small_book(book)
    x0, y0, x1, y1 = b.area.box
    inside = shapely.box(x0 - 1e-6, y0 - 1e-6, x1 + 1e-6, y1 + 1e-6)
    for n in b.strip_pages:
        outlines = occupied(b.drawing.sheets[n - 1].layers)
        assert outlines
        assert all(inside.contains(o) for o in outlines)
        for i in range(len(outlines)):
            for j in range(i + 1, len(outlines)):
                assert outlines[i].distance(outlines[j]) > GAP - 0.5


def test_scale_bar_is_100_mm_on_every_page(tmp_path):
    """The bar is as long as its caption says, in the drawing's millimetres, and its ticks
    stand every 10 mm along it from end to end (taller at 0, 50 and 100 mm): a bar drawn in
    another unit, or ticks spaced otherwise, cannot be checked with a ruler."""
    book = small_book()
    for sheet in book.drawing.sheets:
        page = next(layer for layer in sheet.layers if layer.name == "page")
        bar = next(s for s in page.shapes if isinstance(s, Polylines) and len(s.coords) == 2)
        (x0, y0), (x1, y1) = bar.coords
        (stated,) = [float(m) for t in page.shapes if isinstance(t, Text)
                     for m in re.findall(r"^(\d+(?:\.\d+)?) mm: check this", t.text)]
        assert stated == 100.0 and x1 - x0 == pytest.approx(stated, abs=1e-9) and y1 == y0
        (marks,) = [s for s in page.shapes if isinstance(s, Polylines) and s is not bar
                    and all(len(seg) == 2 and seg[0, 1] == y0 for seg in s.lines())]
        ticks = np.array([seg for seg in marks.lines()])
        assert (ticks[:, 0, 0] == ticks[:, 1, 0]).all()          # upright
        np.testing.assert_allclose(ticks[:, 0, 0] - x0, np.arange(0.0, stated + 1, 10.0),
                                   atol=1e-9)
        tall = ticks[:, 1, 1] - y0
        np.testing.assert_allclose(tall, np.where(np.arange(11) % 5 == 0, 2.0, 1.0))
    out = tmp_path / "s.svg"
    export.write(book.drawing, out)
    text = out.read_text()
    root = re.search(r'<svg [^>]*', text).group(0)
    width = re.search(r' width="([\d.]+)mm"', root).group(1)
    assert re.search(r' viewBox="0 0 ' + re.escape(width) + ' ', root)  # a user unit is 1 mm
    bars = re.findall(r'<path d="M([\d.]+),([\d.]+) ([\d.]+),([\d.]+)" fill="none" stroke="#000000" '
                      r'stroke-linejoin="round" stroke-width="0.3"', text)
    assert len(bars) == len(book.drawing.sheets)
    for xa, ya, xb, yb in bars:
        assert float(xb) - float(xa) == pytest.approx(100.0, abs=1e-3) and ya == yb


def test_every_strip_is_on_a_page_and_on_the_assembly_sheet():
    book = small_book()
    plan = book.plan
    assert all(book.pages_of(label) for label in plan.labels)
    ids = {t.text for layer in book.drawing.sheets[0].layers if layer.name == "ids"
           for t in layer.shapes}
    assert set(plan.labels) <= ids


def test_cli_writes_a_pdf(tmp_path):
    from weavecut.cli import cli
    out = tmp_path / "m.pdf"
    result = CliRunner().invoke(cli, ["strands", "square-grid:2x2", "--levels", "2",
                                      "--page", "letter", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_bytes().startswith(b"%PDF")
    bad = CliRunner().invoke(cli, ["strands", "square-grid:2x2", "-o", str(tmp_path / "m.dxf")])
    assert bad.exit_code == 2


def hexagon() -> Mesh:
    """A hexagon of six triangles (C6 after the snub step)."""
    ring = [(np.cos(a), np.sin(a)) for a in np.arange(6) * np.pi / 3]
    return Mesh.from_faces([(0.0, 0.0), *ring], [[0, i + 1, (i + 1) % 6 + 1] for i in range(6)])


@lru_cache(maxsize=None)
def user_book(layout: str = "mixed"):
    ws = snub_weaves(subdivide(hexagon(), 2))
    return strand_book(ws, palette("maritime-12"), (210.0, 297.0), tile_size=25.0,
                       layout=layout)


BOOKS = {"square-grid:2x2": small_book, "hexagon": user_book,
         "module": lambda: user_book("module")}


@lru_cache(maxsize=None)
def voronoi_book():
    """The bundled Voronoi example (examples/voronoi-patch.obj) as `strands` prints it: an
    irregular mesh with non-convex and twisted tiles, whose corner means lie outside them."""
    return strand_book(list(voronoi_weaves()), palette("maritime-12"), tile_size=20.0)


@lru_cache(maxsize=None)
def voronoi_weaves():
    from pathlib import Path
    from weavecut.mesh_io import read_valid_mesh
    obj = Path(__file__).parents[2] / "examples" / "voronoi-patch.obj"
    return tuple(snub_weaves(subdivide(read_valid_mesh(str(obj)), 2)))


def voronoi_weave():
    return voronoi_weaves()[-1]


@pytest.mark.parametrize("name", [*BOOKS, "voronoi"])
def test_every_label_is_readable(name):
    """Upright, >= 2.5 mm, inside its strip's cut line, on one fill with contrast >= 4.5, no
    overlaps, an assembly-sheet ID on its strand or on a plate whose leader ends on it (checked
    over the Drawing by text_checks, an oracle apart from the placement)."""
    book = voronoi_book() if name == "voronoi" else BOOKS[name]()
    for n in range(1, len(book.drawing.sheets) + 1):
        records = sheet_checks(book, n)
        assert records
        bad = [r for r in records if r["broken"]]
        assert not bad, bad[:5]
    rep = report(book)
    assert rep["label_violations"] == 0 and rep["smallest_text_mm"] >= 2.5
    assert rep["smallest_contrast"] >= 4.5


def test_the_checks_catch_a_bad_label():
    """Plant the bugs the checks are for: a small, upside-down, low-contrast text off its strip."""
    from weavecut.layout.drawing import Layer, Sheet, Text
    book = small_book()
    n = book.strip_pages[0]
    sheet = book.drawing.sheets[n - 1]
    bad = Text(1.0, 150.0, "A1", 2.0, "middle", 180.0, "#ffffff")
    planted = Sheet(sheet.width, sheet.height, sheet.layers + (Layer("labels", "label", (bad,)),))
    broken = text_checks(planted, book.area.box)[-1]["broken"]
    assert {"small", "upside down", "low contrast", "outside its strip"} <= set(broken)


LONG_PATH = ("weave-cut strands: /home/maker/Documents/paper models/a rather long folder name/"
             "another folder inside it/my hexagon of six triangles.obj, level 2")


@pytest.mark.parametrize("page, margin, title", [
    ((210.0, 297.0), 10.0, "weave-cut strands: square-grid:2x2, level 2 (gjpqy)"),
    ((210.0, 297.0), 18.0, "weave-cut strands: square-grid:2x2, level 2 (gjpqy)"),
    ((215.9, 279.4), 23.0, "weave-cut strands: square-grid:2x2, level 2 (gjpqy)"),
    ((150.0, 200.0), 10.0, "weave-cut strands: square-grid:2x2, level 2 (gjpqy)"),
    ((210.0, 297.0), 10.0, LONG_PATH)])
def test_page_furniture_keeps_its_texts_apart(page, margin, title):
    """Title, subtitle, page number, scale-bar caption and legend keep FURNITURE_GAP (1 mm)
    between their boxes on wide pages and narrow ones (A4 inside a cutter's marks): measured
    pairwise with shapely, and held by the page checks. A title too long even at the least
    size (a deep input path) loses its middle to "...", keeping its start and end."""
    from weavecut.layout.labels import text_box
    from weavecut.papermodel.pages import FURNITURE_GAP

    book = strand_book(weaves("square-grid:2x2", 2), palette("maritime-12"), page, 20.0,
                       margin, title=title)
    for n in (1, *book.strip_pages):
        sheet = book.drawing.sheets[n - 1]
        said = [t for layer in sheet.layers if layer.name == "page"
                for t in layer.shapes if hasattr(t, "text")]
        top = max(said, key=lambda t: (t.y, t.anchor == "start"))  # left of the page number
        head = top.text
        assert head == title or (title == LONG_PATH and "..." in head and head.endswith(
            "triangles.obj, level 2") and head.startswith("weave-cut strands: /home/"))
        assert text_box(top).bounds[2] <= page[0] - margin + 1e-9
        boxes = [text_box(t) for t in said]
        assert len(boxes) >= 7  # title, subtitle, number, caption, three legend entries
        gaps = shapely.distance(*np.broadcast_arrays(np.array(boxes)[:, None], np.array(boxes)))
        assert gaps[~np.eye(len(boxes), dtype=bool)].min() >= FURNITURE_GAP - 1e-9
        assert not [r for r in sheet_checks(book, n) if r["broken"]]


def test_the_checks_catch_touching_page_furniture():
    """A legend text planted 0.5 mm above the scale bar's caption is reported."""
    from dataclasses import replace

    from weavecut.layout.drawing import Layer, Sheet, Text
    from weavecut.layout.labels import text_box
    book = small_book()
    n = book.strip_pages[0]
    sheet = book.drawing.sheets[n - 1]
    caption = next(t for layer in sheet.layers for t in layer.shapes
                   if isinstance(t, Text) and t.text.startswith("100 mm"))
    top = text_box(caption).bounds[3]
    near = Text(caption.x, top + 0.5 + 0.05 * caption.size, "cut", caption.size, "middle")
    planted = Sheet(sheet.width, sheet.height, sheet.layers + (Layer("page", "label", (near,)),))
    broken = {r["text"]: r["broken"] for r in text_checks(planted, book.area.box)}
    assert "touches a text" in broken["cut"] and "overlaps a text" not in broken["cut"]
    away = replace(near, y=near.y + 1.0)
    planted = Sheet(sheet.width, sheet.height, sheet.layers + (Layer("page", "label", (away,)),))
    assert "touches a text" not in text_checks(planted, book.area.box)[-1]["broken"]


@pytest.mark.parametrize("name", BOOKS)
def test_virtual_assembly_reproduces_the_weave(name):
    """Every printed piece, put back by the inverse of its page transform, covers exactly the
    tiles of its strand, and every label in an under tile names the strand on top there."""
    book = BOOKS[name]()
    weave = (weaves("square-grid:2x2", 2) if name == "square-grid:2x2"
             else tuple(snub_weaves(subdivide(hexagon(), 2))))[-1]
    tiles = model_tiles(weave)
    tree = shapely.STRtree(tiles)
    covered: dict[int, float] = {}
    checked = 0
    plan = book.plan
    names = list(plan.labels)
    if book.layout == "module":  # the module print names strands by number only
        for row in plan.copies.tolist():
            for i, s in enumerate(row):
                names[s] = str(i + 1)
    for _, piece in book.pieces:
        inv = np.linalg.inv(piece.frame)
        back = shapely.transform(piece.outline, lambda xy: xy @ inv[:2, :2].T + inv[:2, 2])
        visits, _ = weave.strand(piece.strand)
        own = shapely.union_all(tiles[visits])
        assert shapely.difference(back, own).area < 1e-6 * own.area
        covered[piece.strand] = covered.get(piece.strand, 0.0) + back.area
        for t in piece.texts:
            c = text_centre(t)
            p = inv[:2, :2] @ c + inv[:2, 2]
            hit = [i for i in tree.query(shapely.Point(p)) if tiles[i].covers(shapely.Point(p))]
            if not hit or t.text in (piece.tab, piece.mark):  # a glue band, its mark
                continue
            tile = hit[0]
            if weave.tile_under[tile] == piece.strand and t.text != piece.label:
                expect = weave.tile_over[tile]
                assert t.text == names[expect]
                checked += 1
    for s, area in covered.items():  # pieces overlap only by their glue bands
        visits, _ = weave.strand(s)
        assert area >= shapely.union_all(tiles[visits]).area - 1e-6
    printed = (weave.n_strands if book.layout == "mixed"
               else plan.copies.shape[1] + len(plan.extras))
    assert len(covered) == printed and checked > 0


def text_centre(t):
    from weavecut.layout.labels import text_box
    c = text_box(t).centroid
    return np.array([c.x, c.y])


def test_module_layout_prints_the_module_once_without_copy_letters():
    book = user_book("module")
    labels = [p.label for _, p in book.pieces]
    m = book.plan.copies.shape[1]
    assert len({lab.split(" ")[0] for lab in labels}) == m + len(book.plan.extras)
    assert all(lab[0].isdigit() or lab.startswith("X") for lab in labels)
    # the module print serves every copy: module strands have one colour in every copy
    cols = np.array(book.colours)
    assert (cols[book.plan.copies] == cols[book.plan.copies[:1]]).all()


def test_copies_are_told_apart_in_the_mixed_layout():
    book = user_book()
    cols = np.array(book.colours)
    fam = palette("maritime-12").families
    family_of = {c: i for i, f in enumerate(fam) for c in f}
    for j, row in enumerate(book.plan.copies.tolist()):
        assert {family_of[c] for c in cols[row]} == {j % len(fam)}


def test_weaving_page_has_numbered_steps_and_diagrams():
    book = small_book()
    page = book.drawing.sheets[1]
    steps = next(layer for layer in page.layers if layer.name == "steps").shapes
    numbers = [t.text for t in steps if re.fullmatch(r"\d+\.", t.text)]
    assert numbers == [f"{i}." for i in range(1, len(numbers) + 1)] and len(numbers) >= 6
    text = " ".join(t.text for t in steps)
    assert "45 degrees" in text and "two" in text and "glue" in text.lower()
    diagrams = next(layer for layer in page.layers if layer.name == "diagrams").shapes
    assert len(diagrams) >= 2


def run_cli(*args):
    from weavecut.cli import cli
    return CliRunner().invoke(cli, ["strands", *map(str, args)])


def test_sizes_are_checked(tmp_path):
    out = tmp_path / "m.pdf"
    bare = run_cli("square-grid:2x2", "--tile-size", "20", "-o", out)
    assert bare.exit_code == 2 and "no unit" in bare.output and "20mm" in bare.output
    thin = run_cli("square-grid:2x2", "--tile-size", "3mm", "-o", out)
    assert thin.exit_code == 1 and "--tile-size" in thin.output and "tear" in thin.output
    assert not out.exists()
    need = float(re.search(r"--tile-size ([\d.]+)mm", thin.output).group(1))
    from weavecut.papermodel.book import SizeError, check_strip_width, strip_need
    w = weaves("square-grid:2x2", 2)[-1]
    hold = strip_need(w)  # the strips' own limit; the message may name more for the labels
    assert need >= hold
    width, warnings = check_strip_width(w, hold)
    assert 8.0 <= width < 8.5 and warnings  # 8-12 mm: a warning
    with pytest.raises(SizeError):
        check_strip_width(w, hold - 0.5)
    assert not check_strip_width(w, hold * 1.6)[1]


def test_size_sets_the_finished_width(tmp_path):
    import json
    out = tmp_path / "m.pdf"
    result = run_cli("square-grid:2x2", "--size", "14cm", "--json", "-o", out)
    assert result.exit_code == 0, result.output
    rep = json.loads(result.output)
    assert rep["pages"]["extra"] == 2 and rep["pages"]["strip"] >= 1
    assert rep["label_violations"] == 0 and rep["smallest_text_mm"] >= 2.5
    assert rep["label_tabs"] == 0  # square grid tiles hold their IDs
    assert 0 < rep["ink_fraction"] <= 1 and rep["smallest_contrast"] >= 4.5
    w = weaves("square-grid:2x2", 2)[-1]
    from weavecut.papermodel.book import tile_size_width
    assert tile_size_width(w, rep["tile_size_mm"]) == pytest.approx(140.0, rel=1e-3)


def test_assembly_ids_lie_on_their_strands_and_on_the_sheet():
    """Plant the bugs on page 1: two IDs swapped (each now lies on another strand's colour) and
    one moved into the margin; the checks name each, and the book as drawn has none."""
    from dataclasses import replace as moved
    from weavecut.layout.drawing import Layer, Sheet
    book = small_book()
    assert not [r for r in sheet_checks(book, 1) if r["broken"]]
    colour = dict(zip(book.plan.labels, book.colours))
    sheet = book.drawing.sheets[0]
    ids = next(layer for layer in sheet.layers if layer.name == "ids").shapes
    a = ids[0]
    b = next(t for t in ids if colour[t.text] != colour[a.text])
    c = next(t for t in ids if t.text not in (a.text, b.text))
    margin = moved(c, x=book.area.margin / 2, y=book.area.height / 2)
    planted = {id(a): moved(a, text=b.text), id(b): moved(b, text=a.text), id(c): margin}
    texts = tuple(planted.get(id(t), t) for t in ids)
    layers = tuple(Layer("ids", "label", texts) if layer.name == "ids" else layer
                   for layer in sheet.layers)
    bad_book = moved(book, drawing=moved(book.drawing, sheets=(
        Sheet(sheet.width, sheet.height, layers),) + book.drawing.sheets[1:]))
    broken: dict = {}
    for r in sheet_checks(bad_book, 1):
        broken.setdefault(r["text"], set()).update(r["broken"])
    assert "outside its strand" in broken[a.text] and "outside its strand" in broken[b.text]
    assert "off the sheet" in broken[margin.text]
    assert report(bad_book)["label_violations"] >= 3


@pytest.mark.parametrize("target", ["own", "other"])
def test_an_id_on_a_leader_plate_must_point_at_its_strand(target):
    """An ID moved onto a white plate beside the pattern passes when the plate's leader line ends
    on its strand, and is caught when the line ends on a strand of another colour."""
    from dataclasses import replace as moved
    from weavecut.layout.drawing import Layer, Sheet, Style, Text, polygons_from_shapely
    from weavecut.layout.labels import text_box
    book = small_book()
    colour = dict(zip(book.plan.labels, book.colours))
    sheet = book.drawing.sheets[0]
    ids = next(layer for layer in sheet.layers if layer.name == "ids").shapes
    a = ids[0]
    b = next(t for t in ids if colour[t.text] != colour[a.text])
    end = text_box(a if target == "own" else b).centroid
    label = moved(a, x=a.x + 12.0, y=a.y + 12.0, fill="#000000")
    plate = shapely.buffer(text_box(label), 0.8, join_style="mitre")
    near = shapely.ops.nearest_points(plate, end)[0]
    extra = Layer("leader", "paint", (
        polygons_from_shapely([plate], Style("#333333", 0.15, "#ffffff")),
        Polylines(np.array([[near.x, near.y], [end.x, end.y]]), np.array([0, 2]))))
    layers = []
    for layer in sheet.layers:
        if layer.name == "ids":
            layers += [extra, Layer("ids", "label", (label,) + ids[1:])]
        else:
            layers.append(layer)
    before = sum(isinstance(t, Text) for layer in layers[:layers.index(extra) + 1]
                 for t in layer.shapes)
    bad_book = moved(book, drawing=moved(book.drawing, sheets=(
        Sheet(sheet.width, sheet.height, tuple(layers)),) + book.drawing.sheets[1:]))
    record = sheet_checks(bad_book, 1)[before]
    assert record["text"] == a.text
    assert ("outside its strand" in record["broken"]) == (target == "other")


@pytest.mark.parametrize("tabs", [True, False])
def test_the_first_refusal_names_the_size_that_passes_every_check(tabs, monkeypatch):
    """The square grid 2 x 2 at level 2: strips hold from 12 mm tiles, where four end strips are
    too small for their IDs and carry them on tabs; where tabs do not help (none fits), labels
    read only from a larger size. Tiles of 5 mm are refused for the strips, and the message
    already names the size where the labels read too: that size builds with no label violation,
    and half a mm less (with tabs) or a mm less (without) is refused."""
    from weavecut.papermodel import strip_labels
    from weavecut.papermodel.book import SizeError, strip_need
    if not tabs:
        monkeypatch.setattr(strip_labels, "label_flap", lambda strip, text: None)
    ws = list(weaves("square-grid:2x2", 2))
    pal = palette("maritime-12")
    with pytest.raises(SizeError, match="tear") as thin:
        strand_book(ws, pal, tile_size=5.0)
    need = float(re.search(r"--tile-size ([\d.]+)mm", str(thin.value)).group(1))
    rep = report(strand_book(ws, pal, tile_size=need))
    assert rep["label_violations"] == 0 and rep["smallest_text_mm"] >= 2.5
    if tabs:
        assert need == strip_need(ws[-1]) and rep["label_tabs"] > 0
        with pytest.raises(SizeError, match="tear"):
            strand_book(ws, pal, tile_size=need - 0.5)
    else:
        assert need > strip_need(ws[-1]) and rep["label_tabs"] == 0
        with pytest.raises(SizeError, match="labels"):
            strand_book(ws, pal, tile_size=need - 1)


def test_a_split_strips_part_number_keeps_clear_of_its_id():
    """The house at 40 cm: strip A10 is printed in two parts and its part number ("1/2") is
    wanted where its ID already is; it must move (onto a plate over the neighbours) rather than
    print over the ID (it did before)."""
    from weavecut.layout.labels import text_box
    from weavecut.papermodel.book import labelled_pieces, tile_size_for
    from weavecut.papermodel.pages import PageArea
    from pathlib import Path
    from weavecut.mesh_io import read_valid_mesh
    house = Path(__file__).resolve().parents[2] / "examples" / "house.obj"
    ws = snub_weaves(subdivide(read_valid_mesh(house), 2))
    w = ws[-1]
    plan = plan_modules(w, heading=-np.pi / 2)
    pieces, _ = labelled_pieces(w, plan, copy_colours(plan, palette("maritime-4")),
                                tile_size_for(w, 400.0), "mixed", PageArea(210.0, 297.0, 10.0))
    split = [p for p in pieces if " " in p.label]
    assert split
    for p in split:
        boxes = [text_box(t) for t in p.texts]
        for i, a in enumerate(boxes):
            for b in boxes[i + 1:]:
                assert shapely.intersection(a, b).area < 1e-6, (p.label, p.texts)


@lru_cache(maxsize=None)
def pentagon_book():
    """The pentagon flower at the paper's 23 cm, where 70 border strips are too small for IDs."""
    from weavecut.papermodel.book import tile_size_for
    ws = list(weaves("pentagon-flower", 3))
    return strand_book(ws, palette("maritime-12"), tile_size=tile_size_for(ws[-1], 230.0))


def tab_problems(piece) -> list[str]:
    """What is wrong with ``piece``'s label tab, checked from its geometry alone: the ID must lie
    on the tab, the tab outside every tile of the strip, on an edge of an end tile that no other
    tile shares, and inside the strip's cut line."""
    from weavecut.layout.labels import text_box
    flap, tiles = piece.flap, piece.tiles
    eps = 1e-6 * max(piece.length, 1.0)
    out = []
    ids = [t for t in piece.texts if t.text == piece.label.split(" ")[0]]
    if not any(flap.buffer(1e-6).covers(text_box(t)) for t in ids):
        out.append("ID not on the tab")
    if shapely.intersection(flap, shapely.union_all(tiles)).area > 1e-6:
        out.append("tab over the strip")
    mid = piece.flap_edge.interpolate(0.5, normalized=True)
    on = np.flatnonzero(shapely.distance(shapely.get_exterior_ring(tiles), mid) < eps)
    if not {0, len(tiles) - 1} & set(on.tolist()):
        out.append("not at an end tile")
    if len(on) > 1:
        out.append("on a shared edge")
    if not piece.cut.buffer(1e-6).covers(flap) or piece.cut.geom_type != "Polygon":
        out.append("tab outside the cut line")
    return out


def test_a_label_tab_holds_the_id_outside_every_tile():
    """At 23 cm the pentagon flower's 70 two-tile border strips (14 per copy) carry their IDs on
    tabs; each tab passes the geometric oracle. Plant the bug: the same tab on the edge the two
    tiles share lies over the strip and on a shared edge, and the oracle says so."""
    from dataclasses import replace as moved
    from weavecut.layout.labels import centred_text, text_box
    book = pentagon_book()
    tabbed = [p for _, p in book.pieces if p.flap is not None]
    assert len(tabbed) == 70 and all(len(p.tiles) == 2 for p in tabbed)
    assert {p.label[1:] for p in tabbed if p.label[0] == "A"} == {
        "1", "6", "10", "13", "14", "17", "21", "22", "23", "24", "25", "30", "33", "36"}
    for p in tabbed:
        assert not tab_problems(p), (p.label, tab_problems(p))
    p = tabbed[0]  # turn and move the tab (with its ID) onto the edge the two tiles share

    def frame(edge, towards):
        a, b = np.asarray(shapely.get_coordinates(edge))[[0, -1]]
        u = (b - a) / np.hypot(*(b - a))
        n = np.array([-u[1], u[0]])
        return (a + b) / 2, u, n * np.sign(n @ (towards - (a + b) / 2))

    m0, u0, n0 = frame(p.flap_edge, np.asarray(p.flap.centroid.coords[0]))
    shared = shapely.intersection(p.tiles[0].exterior, p.tiles[1].exterior)
    m1, u1, n1 = frame(shared, np.asarray(p.tiles[1].centroid.coords[0]))
    def cross(a, b):
        return a[0] * b[1] - a[1] * b[0]

    u1 *= np.sign(cross(u0, n0) * cross(u1, n1))  # a turn, not a mirror
    turn = np.column_stack([u1, n1]) @ np.column_stack([u0, n0]).T

    def move(g):
        return shapely.transform(g, lambda xy: (xy - m0) @ turn.T + m1)

    label = next(t for t in p.texts if t.text == p.label)
    c = move(text_box(label).centroid)
    angle = label.angle + np.degrees(np.arctan2(turn[1, 0], turn[0, 0]))
    planted = moved(p, flap=move(p.flap), flap_edge=move(p.flap_edge), texts=tuple(
        centred_text((c.x, c.y), t.text, t.size, angle) if t is label else t for t in p.texts))
    assert not tab_problems(moved(planted, flap_edge=p.flap_edge, flap=p.flap, texts=p.texts))
    assert "ID not on the tab" not in tab_problems(planted)
    assert {"tab over the strip", "on a shared edge"} <= set(tab_problems(planted))


def test_the_pentagon_flower_reads_at_the_papers_23_cm():
    """Every label at least 2.5 mm, none broken (the page checks treat a tab as part of its
    strip), the tabs on the pages the packer gave them, each on one page with its strip."""
    book = pentagon_book()
    rep = report(book)
    assert rep["label_violations"] == 0 and rep["smallest_text_mm"] >= 2.5
    assert rep["label_tabs"] == 70 and rep["pages"]["strip"] <= 5
    # a tab meets its strip without a slit, and without a sliver a cutter's knife tears at
    cuts = cut_report([p.cut for _, p in book.pieces])
    assert cuts.simple and cuts.min_feature >= 1.0
    for n in book.strip_pages:
        cuts = occupied(book.drawing.sheets[n - 1].layers)
        flaps = [p.flap for k, p in book.pieces if k == n and p.flap is not None]
        assert all(any(c.buffer(1e-6).covers(f) for c in cuts) for f in flaps)
    steps = " ".join(t.text for layer in book.drawing.sheets[1].layers if layer.name == "steps"
                     for t in layer.shapes)
    assert "tab" in steps and "dashed" in steps


def test_names_left_off_the_strips_are_counted_and_said():
    """At 23 cm some under tiles of the pentagon flower cannot hold a 2.5 mm name: each such
    tile is an under tile whose name is printed nowhere near it, --json counts them, and a
    warning says so. Every other under tile's name is printed on or beside it."""
    from weavecut.layout.labels import MIN_CAP

    book = pentagon_book()
    left = 0
    for _, p in book.pieces:
        for i in np.flatnonzero(~p.over).tolist():  # under tiles
            near = shapely.buffer(p.tiles[i], 2 * MIN_CAP)
            printed = any(t.text == p.names[i] and near.contains(shapely.Point(t.x, t.y))
                          for t in p.texts)
            assert printed != (i in p.left_out)
        left += len(p.left_out)
    assert left > 0 and report(book)["names_left_out"] == left
    assert any(f"{left} under-crossing names" in w for w in book.warnings)


def crossing_callouts(sheet):
    """(pattern tiles, white plates, black lines, callout texts) of a page, from its layers."""
    from weavecut.layout.drawing import Polygons
    layers = {layer.name: layer for layer in sheet.layers}
    shapes = layers["pattern"].shapes
    plates = [g for s in shapes if isinstance(s, Polygons) and s.style.fill == "#ffffff"
              for g in s.to_shapely().tolist()]
    lines = [line for s in shapes if isinstance(s, Polylines) and s.style.stroke == "#000000"
             for line in s.lines()]
    return shapes[0].to_shapely(), plates, lines, list(layers["crossings"].shapes)


def callout_problems(sheet, weave, ids) -> list[str]:
    """Each callout text on exactly one white plate, one leader line from that plate's edge,
    ending in a tile of the pattern where the strand named first lies on top of the second."""
    from weavecut.layout.labels import text_box
    tiles, plates, lines, texts = crossing_callouts(sheet)
    out = []
    for t in texts:
        box = text_box(t)
        plate = [g for g in plates if g.covers(box)]
        lead = [e for e in lines if plate and plate[0].exterior.distance(
            shapely.Point(e[0])) < 1e-6]
        if len(plate) != 1 or len(lead) != 1:
            out.append(f"{t.text}: {len(plate)} plates, {len(lead)} leaders")
            continue
        hit = np.flatnonzero(shapely.covers(tiles, shapely.Point(lead[0][-1])))
        named = {f"{ids[weave.tile_over[k]]} over {ids[weave.tile_under[k]]}"
                 for k in hit.tolist()}
        if t.text not in named:
            out.append(f"{t.text}: its leader ends on {named}")
    return out


@pytest.mark.parametrize("name, on", [("pentagon", (3, 4)), ("voronoi", (1,))])
def test_every_unnamed_crossing_is_called_out_once_with_a_leader_to_it(name, on):
    """The crossings the strips leave unnamed (the pentagon flower at 23 cm: 155, on two pages
    of their own after the weaving page; the Voronoi example: 5, on page 1), each called out
    once ("C8 over A14": the name the strip would have carried, over the strip's ID), each
    text on a white plate whose leader line ends in a tile of the pattern where that strand
    lies on top of that strip; every text passes the page checks (>= 2.5 mm, no overlap,
    contrast, on the sheet). Plant a swapped pair of callouts: both caught."""
    from collections import Counter
    from dataclasses import replace as moved
    from weavecut.layout.drawing import Layer, Sheet
    from weavecut.layout.labels import MIN_CAP

    if name == "pentagon":
        book, weave = pentagon_book(), weaves("pentagon-flower", 3)[-1]
    else:
        book = voronoi_book()
        weave = voronoi_weave()
    want = Counter(f"{p.names[i]} over {p.label.split(' ')[0]}"
                   for _, p in book.pieces for i in p.left_out)
    assert sum(want.values()) == report(book)["names_left_out"] == {"pentagon": 155,
                                                                    "voronoi": 5}[name]
    assert book.callout_pages == (on if name == "pentagon" else ())
    assert book.strip_pages[0] == max(book.extra_pages) + 1 == max(on[-1], 2) + 1 + len(
        set(book.id_pages) - set(on))
    assert any(f"called out on {'pages 3-4' if name == 'pentagon' else 'page 1'}" in w
               for w in book.warnings)
    seen = Counter()
    for n in on:
        sheet = book.drawing.sheets[n - 1]
        assert not callout_problems(sheet, weave, book.plan.labels)
        assert not [r for r in sheet_checks(book, n) if r["broken"]]
        texts = crossing_callouts(sheet)[3]
        seen.update(t.text for t in texts)
        assert min(t.size for t in texts) >= MIN_CAP
    assert seen == want
    sheet = book.drawing.sheets[on[0] - 1]
    texts = crossing_callouts(sheet)[3]
    swapped = (moved(texts[0], text=texts[1].text), moved(texts[1], text=texts[0].text))
    layers = tuple(Layer("crossings", "label", swapped + tuple(texts[2:]))
                   if layer.name == "crossings" else layer for layer in sheet.layers)
    assert len(callout_problems(Sheet(sheet.width, sheet.height, layers), weave,
                                book.plan.labels)) == 2


@lru_cache(maxsize=None)
def pentagon_module_book():
    """The pentagon flower at 23 cm in the paper's layout: one module's strips, printed 5 times."""
    from weavecut.papermodel.book import tile_size_for
    ws = list(weaves("pentagon-flower", 3))
    return strand_book(ws, palette("maritime-12"), tile_size=tile_size_for(ws[-1], 230.0),
                       layout="module")


def crossing_leaders(sheet) -> list[tuple[str, str]]:
    """The pairs of leader lines (callouts' and IDs') of a page that meet, by their ends."""
    lines = shapely.linestrings(crossing_callouts(sheet)[2])
    i, j = shapely.STRtree(lines).query(lines, predicate="intersects")
    return [(str(lines[a]), str(lines[b])) for a, b in zip(i.tolist(), j.tolist()) if a < b]


def leaders_through_plates(sheet) -> list[str]:
    """Leader lines that run into a white plate other than at their own start (on the plate's
    edge): a leader must stay clear of every other plate and of its own plate's inside."""
    _, plates, lines, _ = crossing_callouts(sheet)
    plates = np.array(plates, dtype=object)
    out = []
    for line in lines:  # leaders, not mesh elements
        start = shapely.Point(line[0]).buffer(1e-6)
        rest = shapely.difference(shapely.LineString(line), start)
        if shapely.intersects(plates, rest).any():
            out.append(str(line.tolist()))
    return out


@pytest.mark.parametrize("name", ["pentagon", "module", "voronoi"])
def test_leader_lines_never_cross(name):
    """On the assembly sheet and every page with callouts (the pentagon flower at 23 cm: pages
    3-4, or page 3 in the module layout; the Voronoi example: page 1) no two leader lines meet,
    none runs over a plate, and each callout's leader
    still ends on a tile where its strand lies on top. Plant the bug (the slots as the first
    stacking gave them, without the 2-opt swaps): the pentagon flower's leaders cross."""
    from unittest import mock
    from weavecut.papermodel import crossings

    make = {"pentagon": pentagon_book, "module": pentagon_module_book, "voronoi": voronoi_book}
    book = make[name]()
    weave = voronoi_weave() if name == "voronoi" else weaves("pentagon-flower", 3)[-1]
    pages = [s for s in book.drawing.sheets if "crossings" in {la.name for la in s.layers}]
    callout_pages = sum(bool(crossing_callouts(s)[3]) for s in pages)
    assert callout_pages == {"pentagon": 2, "module": 1, "voronoi": 1}[name]
    for sheet in pages:  # page 1's ID leaders too
        assert not crossing_leaders(sheet), sheet.name
        assert not leaders_through_plates(sheet), sheet.name
        assert not callout_problems(sheet, weave, book.plan.labels)
    if name == "pentagon":
        with mock.patch.object(crossings, "uncrossed", lambda starts, ends: np.arange(len(ends))):
            planted = make[name].__wrapped__()
        assert all(crossing_leaders(s) for s in planted.drawing.sheets[2:4])


def instructions(book) -> str:
    """The words of the pages before the strips (assembly sheet, weaving steps, callout
    pages), each layer's lines joined, so a wrapped sentence reads whole."""
    from weavecut.layout.drawing import Text
    return " ".join(" ".join(t.text for t in layer.shapes if isinstance(t, Text))
                    for sheet in book.drawing.sheets[:len(book.extra_pages)]
                    for layer in sheet.layers)


def instruction_problems(book) -> list[str]:
    """What the instructions say that the pages do not hold: an example crossing that is
    called out nowhere (or told backwards), an example split strip that is not split so, a
    page range "p. 3-3", copies of a pattern that has no turn."""
    words = instructions(book)
    callouts = {t.text for sheet in book.drawing.sheets for layer in sheet.layers
                if layer.name == "crossings" for t in layer.shapes}
    labels = {p.label for _, p in book.pieces}
    out = []
    out += [f"example crossing {said!r}" for said in re.findall(r'"(\S+ over \S+)"', words)
            if said not in callouts]
    out += [f"{said!r} told as {over} over {under}" for said, under, over in re.findall(
        r'"(\S+ over \S+)": strip (\S+) goes under strand (\S+) at the dot', words)
        if said != f"{over} over {under}"]
    out += [f"example part {said!r}" for said in re.findall(r'"(\S+ \d+/\d+)"', words)
            if said not in labels]
    for name, n, last in re.findall(r'strip (\S+): "1/(\d+)" to "(\d+)/\d+"', words):
        if {f"{name} 1/{n}", f"{name} {last}/{n}"} - labels or last != n:
            out.append(f"example parts of {name}")
    out += [f"page range {a}-{b}" for a, b in re.findall(r"\b(\d+)-(\d+)\b", words)
            if int(a) >= int(b)]
    if book.plan.k == 1 and ("copies" in words or "turned by" in words):
        out.append("copies of a pattern without symmetry")
    return out


@pytest.mark.parametrize("name", ["pentagon", "module", "voronoi", "hexagon"])
def test_the_instructions_name_what_is_on_the_pages(name):
    """The examples in the words are the maker's own: the crossing explained is one called
    out, the split strip one printed in those parts; page ranges run forward; a pattern with
    no turn (the Voronoi example) speaks of no copies; one strip page is "p. 3" (the
    hexagon). Each check has something to check (the
    Voronoi example has split strips and callouts; the pentagon flower callout pages), and a
    planted stock example ("C8 over A14" where no such crossing is called out) is caught."""
    from dataclasses import replace as moved
    from weavecut.layout.drawing import Drawing, Layer, Sheet, Text

    book = {"pentagon": pentagon_book, "module": pentagon_module_book,
            "voronoi": voronoi_book, "hexagon": user_book}[name]()
    words = instructions(book)
    assert not instruction_problems(book)
    assert len(re.findall(r'": strip \S+ goes under', words)) == {"pentagon": 3,
                                                                   "hexagon": 0}.get(name, 2)
    if name == "hexagon":
        assert "(p. 3)" in words
    if name == "voronoi":
        assert re.search(r'strip \S+: "1/2" to', words) and "one strip each" in words
    sheet = book.drawing.sheets[1]
    stock = Text(0.0, 0.0, '"C8 over A14": strip A14 goes under strand C8 at the dot', 3.0)
    planted = Sheet(sheet.width, sheet.height, (*sheet.layers, Layer("notes", "label", (stock,))))
    sheets = list(book.drawing.sheets)
    sheets[1] = planted
    assert instruction_problems(moved(book, drawing=Drawing(tuple(sheets), "t"))) == [
        "example crossing 'C8 over A14'"]


def test_label_plates_stay_over_their_tiles_whatever_order_a_writer_paints_in():
    """A writer may paint a shape's polygons grouped by fill (the PDF writer does): within one
    shape of a strip page no two polygons of different fills overlap, so a label's plate is
    its own shape over the tiles (the house: an ID on its plate over a light under tile)."""
    from pathlib import Path

    from weavecut.cli.common import load_mesh
    from weavecut.layout.drawing import Polygons

    mesh = load_mesh(str(Path(__file__).parents[2] / "examples" / "house.obj"))
    book = strand_book(snub_weaves(subdivide(mesh, 2)), palette("maritime-12"))
    assert any(len(p.plates) for _, p in book.pieces)
    for n in book.strip_pages:
        for shape in (s for layer in book.drawing.sheets[n - 1].layers for s in layer.shapes
                      if isinstance(s, Polygons) and s.fills):
            polys, fills = shape.to_shapely(), np.array(shape.fills)
            a, b = shapely.STRtree(polys).query(polys, predicate="intersects")
            pair = (a < b) & (fills[a] != fills[b])
            assert (shapely.area(shapely.intersection(polys[a[pair]], polys[b[pair]]))
                    < 1e-6).all()


def test_a_label_takes_the_nearest_free_spot_round_its_tile():
    """The plate for a tile at the origin (10 mm tiles) is tried on rings of 10, 17.5, ... mm
    at 15, 45, ... degrees: an obstacle on the first try (15 degrees at 10 mm) moves it to the
    next angle of the same ring (45 degrees), not to a farther ring."""
    obstacle = shapely.box(8, 1, 11, 4)
    _, plate, leader = _free_spot((0.0, 0.0), "A1", [obstacle], shapely.box(-50, -50, 50, 50),
                                  10.0)
    centre = np.asarray(plate.centroid.coords[0])
    assert centre == pytest.approx(10 * np.array([np.cos(np.pi / 4), np.sin(np.pi / 4)]))
    assert not plate.intersects(obstacle) and not leader.intersects(obstacle)


def test_module_warning_counts_names_per_print_and_on_the_model():
    """The module layout leaves names off the one print of the module, which is printed k
    times: the warning gives both counts, and the model's count is k times the print's (every
    copy has the same crossings), the number of callouts the crossing pages carry."""
    book = pentagon_module_book()
    per_print = sum(len(p.left_out) for _, p in book.pieces)
    on_model = sum(len(crossing_callouts(sheet)[3]) for sheet in book.drawing.sheets
                   if any(layer.name == "crossings" for layer in sheet.layers))
    assert per_print > 0 and on_model == book.plan.k * per_print
    assert any(w.startswith(f"{per_print} under-crossing names are left off each print's "
                            f"strips ({on_model} on the model)") for w in book.warnings)


def test_page_1_names_a_short_strand_once():
    """The pentagon flower at 23 cm: a strand of ``ALONG`` own tiles or fewer (its two ends in
    view of one ID) is named once on page 1, not by two boxes side by side; the boxes that
    saves go first to strands page 1 names nowhere else (at the preset's turn, 177 IDs for 133
    strands became 150 for 139). Planted: a box at every end that has no room names 44
    strands twice."""
    from collections import Counter
    from weavecut.papermodel.assembly import ALONG
    book = pentagon_book()
    ws = list(weaves("pentagon-flower", 3))
    ids = Counter(t.text for layer in book.drawing.sheets[0].layers if layer.name == "ids"
                  for t in layer.shapes)
    short = {book.plan.labels[s] for s in range(ws[-1].n_strands)
             if int(ws[-1].strand(s)[1].sum()) <= ALONG}
    assert short and all(ids[label] <= 1 for label in short)
