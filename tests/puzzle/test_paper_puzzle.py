"""The paper's puzzle checked as a maker would: size, front colours, back colours, stroke
numbers, frame parts, colour key. Oracles are computed apart from the code: distances between
corners, octagon centroids of the coarser level, a real DXF reader, shapely unions."""

from __future__ import annotations

import json
import re

import ezdxf
import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from weavecut.text import counted
from weavecut import export, inputs
from weavecut.cli import cli
from weavecut.layout.colour_difference import colour_difference, srgb_to_lab
from weavecut.layout.labels import text_box
from weavecut.layout.lasersetup import laser
from weavecut.puzzle import files as pf
from weavecut.puzzle.frame import fits, split_frame
from weavecut.puzzle.guides import colour_key, guide, painted, printed
from weavecut.puzzle.guide_numbers import guide_numbers
from weavecut.puzzle.pieces import OCTAGON, build_puzzle
from weavecut.subdivision import subdivide

from tests.built_puzzles import pentagon_paint, pentagon_puzzle

HUES = {"green": (100, 180), "blue": (200, 290), "pink": (320, 380)}  # CIELAB hue, degrees


@pytest.fixture(scope="module")
def paper():
    """The paper's puzzle: level 4 on a regular pentagon, 50 cm frame diagonal, and its paint,
    made once per process (tests/built_puzzles.py; the paint's own rules are recounted in
    test_colouring_recount.py, which colours in every test)."""
    return pentagon_puzzle(4, 500.0), pentagon_paint(4, 500.0)


@pytest.mark.parametrize("size", [500.0, 300.0, 733.3])
def test_frame_is_a_regular_pentagon_whose_diagonal_is_the_size(size):
    puzzle = build_puzzle(subdivide(inputs.get("pentagon"), 2), size=size)
    corners = np.asarray(puzzle.outer.exterior.coords)[:-1]
    assert len(corners) == 5
    d = np.linalg.norm(corners[:, None] - corners[None], axis=2)
    sides = np.diag(np.roll(d, 1, axis=1))
    diagonals = np.diag(np.roll(d, 2, axis=1))
    np.testing.assert_allclose(sides, sides[0], atol=1e-6)
    np.testing.assert_allclose(diagonals, size, atol=0.01)
    assert diagonals[0] / sides[0] == pytest.approx((1 + 5 ** 0.5) / 2, rel=1e-9)


def _hue_family(colour: str) -> str:
    _, a, b = srgb_to_lab(colour)
    hue = np.degrees(np.arctan2(b, a)) % 360
    hue = hue + 360 if hue < 20 else hue
    return next(name for name, (lo, hi) in HUES.items() if lo <= hue < hi)


def test_front_has_twenty_colours_in_three_families(paper):
    puzzle, colouring = paper
    colours = colouring.front_colours
    assert len(colours) == 20
    families = {c: _hue_family(c) for c in colours}
    assert set(families.values()) == {"green", "blue", "pink"}
    # siblings (children of one level-2 strand) share a family
    parent = puzzle.weaves[-2].parent_strand
    strands = np.array(colouring.front_strands, dtype=object)
    for p in np.unique(parent[parent >= 0]).tolist():
        kids = {families[c] for c in strands[parent == p] if c in families}
        assert len(kids) <= 1


def test_one_colour_per_level3_strand_with_an_octagon(paper):
    puzzle, colouring = paper
    w = puzzle.weaves[-2]
    octagon = np.diff(w.tile_offsets) == 2
    on_octagon = np.unique(w.tile_over[octagon & (w.tile_over >= 0)])
    assert len(on_octagon) == 20
    colours = [colouring.front_strands[s] for s in on_octagon.tolist()]
    assert len(set(colours)) == 20


def test_touching_different_colours_differ_by_delta_e_12(paper):
    puzzle, colouring = paper
    # an independent adjacency: painted halves that share a boundary segment
    paint = painted(puzzle, colouring, "front")
    tree = shapely.STRtree(paint.polygons)
    a, b = tree.query(paint.polygons, predicate="touches")
    keep = a < b
    a, b = a[keep], b[keep]
    shared = shapely.length(shapely.intersection(paint.polygons[a], paint.polygons[b]))
    a, b = a[shared > 1e-6], b[shared > 1e-6]
    differ = paint.colours[a] != paint.colours[b]
    de = colour_difference(paint.colours[a][differ].tolist(), paint.colours[b][differ].tolist())
    assert de.min() >= 12
    assert colouring.smallest_difference == pytest.approx(de.min(), abs=1e-9)


def test_single_coloured_pieces_are_the_forty_level3_octagon_centres(paper):
    puzzle, colouring = paper
    w3 = puzzle.weaves[-2]
    faces = w3.mesh.dense_faces()
    octs = np.flatnonzero(np.diff(w3.tile_offsets) == 2)
    first = w3.tile_faces[w3.tile_offsets[octs]]
    second = w3.tile_faces[w3.tile_offsets[octs] + 1]
    tiles = shapely.union(shapely.polygons(puzzle.to_mm(w3.mesh.vertices[faces[first]])),
                          shapely.polygons(puzzle.to_mm(w3.mesh.vertices[faces[second]])))
    centres = shapely.centroid(tiles)
    tree = shapely.STRtree(puzzle.pieces)
    _, hit = tree.query(centres, predicate="within")
    single = np.flatnonzero((colouring.front[:, 0] == colouring.front[:, 1])
                            & (puzzle.kinds == OCTAGON))
    assert len(single) == 40
    assert sorted(hit.tolist()) == single.tolist()


def test_back_strand_pairs_wear_the_front_colour_of_the_piece_they_enclose(paper):
    puzzle, colouring = paper
    w4 = puzzle.weaves[-1]
    # every back strand wears its parent's front colour, so a pair shares one colour
    for s, p in enumerate(w4.parent_strand.tolist()):
        if p >= 0:
            assert colouring.back_strands[s] == colouring.front_strands[p]
    # the pieces next to a single-coloured centre piece include, on the back, its front colour
    # on both sides (the enclosing pair), read from the geometry
    single = np.flatnonzero((colouring.front[:, 0] == colouring.front[:, 1])
                            & (puzzle.kinds == OCTAGON))
    tree = shapely.STRtree(puzzle.pieces)
    for k in single.tolist():
        near = tree.query(puzzle.pieces[k], predicate="touches")
        shared = shapely.length(shapely.intersection(puzzle.pieces[near], puzzle.pieces[k]))
        near = near[shared > 1e-6]
        assert (colouring.back[near] == colouring.front[k, 0]).sum() >= 2


def test_numbers_are_strokes_inside_their_pieces_with_half_a_millimetre(tmp_path, paper):
    puzzle, _ = paper
    numbers = pf.piece_numbers(puzzle)
    result = pf.shared_cut(puzzle, laser(), numbers)
    path = tmp_path / "cut.dxf"
    export.write(result.drawing, path)
    doc = ezdxf.readfile(path)
    assert not doc.modelspace().query("TEXT MTEXT")
    width, height, shift = pf.placement(puzzle)
    pieces = shapely.transform(puzzle.pieces, lambda xy: xy + shift)
    lines = [np.array(e.get_points("xy")) for e in doc.modelspace().query("LWPOLYLINE")
             if e.dxf.layer == "engrave-numbers"]
    strokes = shapely.linestrings(np.concatenate(lines), indices=np.repeat(
        np.arange(len(lines)), [len(x) for x in lines]))
    tree = shapely.STRtree(pieces)
    owner = tree.query(strokes, predicate="within")
    assert len(np.unique(owner[0])) == len(strokes)  # every stroke inside one piece
    gap = shapely.distance(strokes[owner[0]], shapely.boundary(pieces[owner[1]]))
    assert gap.min() >= 0.5
    # every piece has its number, read back: 1..P pieces each own strokes
    assert set(owner[1].tolist()) == set(range(puzzle.n_pieces))
    svg = (tmp_path / "cut.svg")
    export.write(result.drawing, svg)
    assert "<text" not in svg.read_text().split("engrave-numbers", 1)[1].split("</g>", 1)[0]


@pytest.mark.parametrize("sheet", [(600.0, 400.0), (350.0, 250.0)])
def test_split_frame_parts_tile_the_frame_and_fit_the_sheet(paper, sheet):
    puzzle, _ = paper
    parts = split_frame(puzzle.frame, puzzle.outer, sheet, 5.0, 0.15)
    assert len(parts) >= 2
    union = shapely.union_all(parts)
    assert shapely.symmetric_difference(union, puzzle.frame).area < 1e-6
    assert shapely.area(parts).sum() == pytest.approx(puzzle.frame.area, rel=1e-9)
    tree = shapely.STRtree(parts)
    a, b = tree.query(parts, predicate="intersects")
    overlap = shapely.area(shapely.intersection(parts[a[a < b]], parts[b[a < b]]))
    assert overlap.max(initial=0) < 1e-6
    assert fits(shapely.buffer(parts, 0.075, join_style="mitre"), sheet, 5.0).all()
    # each part is one piece of board, and joins its neighbours along more than a line:
    # a dovetail makes the shared border longer than the straight cut across the band
    assert all(p.geom_type == "Polygon" and not p.interiors for p in parts)


def test_cli_on_a_small_sheet_splits_the_frame_and_never_says_part_0(tmp_path):
    out = tmp_path / "p"
    result = CliRunner().invoke(cli, ["puzzle", "-o", str(out), "--levels", "2", "--sheet",
                                      "600x400mm", "--json"])
    assert result.exit_code == 0, result.output
    assert "part 0" not in result.output
    info = json.loads(result.stdout)  # warnings go to stderr
    readme = (out / "README.txt").read_text()
    assert "F1" in readme and info["frame_parts"] >= 2
    # the workshop README names every file written, the material, sheets, cut length and time
    for name in info["files"]:
        assert (out / name).is_file() and f"  {name}\n" in readme
    m = info["modes"]["separate"]
    assert info["material"] in readme and counted(m['sheets'], 'sheet') in readme
    assert f"{m['cut_length_m']:.1f} m of cutting" in readme and f"{m['time_min']:g} min" in readme
    assert f"{info['frame_diagonal_mm']:g} mm diagonal" in readme
    bad = CliRunner().invoke(cli, ["puzzle", "-o", str(tmp_path / "q"), "--levels", "2",
                                   "--sheet", "30x30mm", "--mode", "separate"])
    assert bad.exit_code == 1 and "part 0" not in bad.output
    assert "frame does not fit a 30 x 30 mm sheet" in bad.output


def test_colour_key_areas_add_up_to_the_painted_area(paper):
    puzzle, colouring = paper
    for side in ("front", "back"):
        key = colour_key(puzzle, colouring, side)
        text = " ".join(s.text for sheet in key.sheets for layer in sheet.layers
                        for s in layer.shapes if hasattr(s, "text"))
        listed = [float(x) for x in re.findall(r"#[0-9a-f]{6}   (\d+\.\d) cm²", text)]  # a paint's
        g = guide(puzzle, colouring, side)
        paint = next(layer for layer in g.sheets[0].layers if layer.name == "paint")
        painted_cm2 = shapely.area(paint.shapes[0].to_shapely()).sum() / 100
        assert sum(listed) == pytest.approx(painted_cm2, abs=0.05 * len(listed))
        names = [n for n in colouring.names.values()]
        assert sum(name in text for name in set(names)) == len(
            colouring.front_colours if side == "front" else colouring.back_colours)


def test_printed_guide_has_no_empty_pages(paper):
    puzzle, colouring = paper
    g = guide(puzzle, colouring, "front")
    pages = printed(g, colour_key(puzzle, colouring, "front"), (210.0, 297.0))
    for sheet in pages.sheets:
        assert any(layer.shapes for layer in sheet.layers if layer.role in ("paint", "label"))


def test_back_guide_numbers_read_left_to_right(paper):
    """The back is mirrored, its numbers are not: the strokes of "1" in piece 1's number lie
    where an unmirrored number puts them (the vertical of a 1 is at the right of its box)."""
    puzzle, colouring = paper
    placed = guide_numbers(puzzle, colouring, "back")
    numbers = placed.labels
    one = [k for k, t in enumerate(numbers.texts) if t == "1"][0]
    sheet = guide(puzzle, colouring, "back", placed).sheets[0]
    layer = next(layer for layer in sheet.layers if layer.name == "numbers")
    width = sheet.width
    _, _, shift = pf.placement(puzzle)
    centre = numbers.centres[one] + shift
    centre = np.array([width - centre[0], centre[1]])
    pts = np.concatenate([shape.coords for shape in layer.shapes if hasattr(shape, "offsets")])
    near = pts[np.hypot(*(pts - centre).T) < numbers.heights[one]]
    # the back turns labels by minus their angle a; turned back (by +a), the foot of the 1's
    # stem (its lowest point) is right of the centre, its flag reaches left
    a = np.radians(numbers.angles[one])
    local = (near - centre) @ np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
    assert local[np.argmin(local[:, 1]), 0] > 0


def test_number_warnings_name_small_pieces_and_unnumbered_ones():
    labels = pf.Labels(("1", "2", "3"), np.array([4.0, 2.0, 0.0]), np.zeros((3, 2)),
                       np.zeros(3))
    lines = pf.number_warnings(labels)
    assert lines[0].startswith("pieces 2 are too small for 3 mm digits")
    assert lines[1].startswith("pieces 3 are too small for 1.5 mm digits and get no number")
    coords, offsets = labels.strokes()
    assert len(offsets) > 1 and np.abs(coords).max() <= 4.0  # "3" drew nothing


def test_a_small_puzzle_warns_and_names_the_largest_good_level():
    from weavecut.puzzle import workshop
    puzzle = build_puzzle(subdivide(inputs.get("pentagon"), 4), size=300.0)
    lines = workshop.size_warnings(puzzle, 3.0)
    assert any("smaller than 15 mm across" in w for w in lines)
    assert lines[-1] == "at this size, --levels 3 keeps every piece above both limits"
    smaller = build_puzzle(subdivide(inputs.get("pentagon"), 3), size=300.0)
    across, width = workshop.piece_sizes(smaller)
    assert across.min() >= 15 and width.min() >= 9  # the named level really is fine
    # sizes across, one piece at a time: the largest distance between two corners
    corners = [np.asarray(p.exterior.coords) for p in smaller.pieces]
    np.testing.assert_allclose(across, [np.max(np.hypot(*(c[:, None] - c[None]).T))
                                        for c in corners], rtol=1e-12)


def test_the_two_long_children_of_a_strand_are_a_light_and_a_dark_shade(paper):
    """"the light and dark green strands originate from one strand": the two children of a
    level-2 strand that run over three octagons each share a family and differ in lightness."""
    puzzle, colouring = paper
    w3 = puzzle.weaves[-2]
    octagon = np.diff(w3.tile_offsets) == 2
    n_octagons = np.bincount(w3.tile_over[octagon], minlength=w3.n_strands)
    long = np.flatnonzero(n_octagons >= 3)
    parents = w3.parent_strand[long]
    assert len(long) == 10 and sorted(np.bincount(parents)[np.unique(parents)]) == [2] * 5
    for p in np.unique(parents).tolist():
        a, b = (colouring.front_strands[s] for s in long[parents == p].tolist())
        assert _hue_family(a) == _hue_family(b)
        assert abs(srgb_to_lab(a)[0] - srgb_to_lab(b)[0]) >= 20


def test_colour_key_text_stays_inside_the_page_margins(paper):
    puzzle, colouring = paper
    margin = 15.0
    for side in ("front", "back"):
        for sheet in colour_key(puzzle, colouring, side, margin=margin).sheets:
            inside = shapely.box(margin - 0.01, margin - 0.01, sheet.width - margin + 0.01,
                                 sheet.height - margin + 0.01)
            texts = [s for layer in sheet.layers for s in layer.shapes if hasattr(s, "text")]
            outside = [t.text for t in texts if not inside.contains(text_box(t))]
            assert not outside, outside[:3]
