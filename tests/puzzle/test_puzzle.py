"""The jigsaw puzzle: pieces tile the frame's hole, counts match the weave, cuts are single and
continuous, kerf grows pieces by perimeter x kerf/2, colours follow the lineage, files load."""

from __future__ import annotations

import json
from xml.etree import ElementTree

import ezdxf
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
import shapely
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.layout.lasersetup import laser
from weavecut.puzzle import files as pf
from weavecut.puzzle.colouring import UNPAINTED, colour_puzzle
from weavecut.puzzle.guides import guide, piece_halves
from weavecut.puzzle.pieces import ENNEAGON, OCTAGON
from weavecut.weave.colour import palette

from tests.built_puzzles import pentagon_puzzle


@pytest.fixture(scope="module")
def puzzle():
    """The level-3 pentagon, built once per process (tests/built_puzzles.py); the tests that
    guard the pieces themselves build theirs (test_puzzle_oracles.py)."""
    return pentagon_puzzle(3)


def test_pieces_tile_the_hole_without_overlaps(puzzle):
    pieces = puzzle.pieces
    assert all(p.is_valid and len(p.interiors) == 0 for p in pieces)  # simple polygons
    total = shapely.area(pieces).sum()
    assert total == pytest.approx(puzzle.hole.area, rel=1e-9)
    tree = shapely.STRtree(pieces)
    a, b = tree.query(pieces, predicate="intersects")
    keep = a < b
    overlap = shapely.area(shapely.intersection(pieces[a[keep]], pieces[b[keep]]))
    assert overlap.max() < 1e-6
    # the hole holds the whole level-t mesh, and the frame is outer minus hole
    level = puzzle.hierarchy[-1].mesh
    faces = shapely.polygons(puzzle.to_mm(level.vertices[level.dense_faces()]))
    assert shapely.area(shapely.difference(shapely.union_all(faces), puzzle.hole)) < 1e-6
    assert puzzle.frame.area + puzzle.hole.area == pytest.approx(puzzle.outer.area, rel=1e-9)


def test_piece_counts_match_the_weave(puzzle):
    parent = puzzle.hierarchy[-2].mesh.topology
    n_inner = int((~parent.boundary_edges).sum())
    assert int((puzzle.kinds == OCTAGON).sum()) == n_inner
    assert int((puzzle.kinds == ENNEAGON).sum()) == int(parent.boundary_edges.sum())
    assert sorted(puzzle.piece_tiles.tolist()) == list(range(puzzle.weaves[-1].n_tiles))
    enneagons = puzzle.pieces[puzzle.kinds == ENNEAGON]
    assert set(shapely.get_num_coordinates(enneagons) - 1) == {9}


def _segments(paths):
    segs = []
    for p in paths:
        p = np.round(np.asarray(p), 6)
        for a, b in zip(p[:-1], p[1:]):
            segs.append(tuple(sorted([tuple(a), tuple(b)])))
    return segs


def test_shared_cut_cuts_every_edge_once_and_totals_the_union(puzzle):
    result = pf.shared_cut(puzzle, laser())
    sheet = result.drawing.sheets[0]
    lines = [ln for layer in sheet.layers if layer.role == "cut" for shape in layer.shapes
             for ln in shape.lines()]
    segs = _segments(lines)
    assert len(segs) == len(set(segs))  # no segment cut twice
    width, height, shift = pf.placement(puzzle)
    outlines = shapely.union_all(np.concatenate([
        shapely.boundary(shapely.transform(puzzle.pieces, lambda xy: xy + shift)),
        [shapely.transform(puzzle.outer.exterior, lambda xy: xy + shift)]]))
    assert result.cut_length == pytest.approx(outlines.length, rel=1e-6)
    # joined into long paths: far fewer paths than piece edges
    assert result.n_paths < len(segs) / 5
    # inner cuts come before the frame's outer outline
    names = [layer.name for layer in sheet.layers if layer.role == "cut"]
    assert names == sorted(names) and names[-1].endswith("outer")


@pytest.mark.parametrize("kerf", [0.1, 0.3])
def test_separate_pieces_grow_by_perimeter_times_half_kerf(puzzle, kerf):
    grown = shapely.buffer(puzzle.pieces, kerf / 2, join_style="mitre")
    from weavecut.layout.nesting import offset
    ours = offset(puzzle.pieces, kerf)
    gain = shapely.area(ours) - shapely.area(puzzle.pieces)
    first_order = shapely.length(puzzle.pieces) * kerf / 2
    np.testing.assert_allclose(gain, first_order, rtol=0.05)
    np.testing.assert_allclose(shapely.area(ours), shapely.area(grown), rtol=1e-9)


def test_separate_sheets_do_not_overlap(puzzle):
    kerf = 0.2
    result = pf.separate_cut(puzzle, laser(), kerf, (600.0, 450.0))
    assert result.n_sheets >= 1
    for parts in pf.nested_parts(result):
        outlines = np.array([shapely.Polygon(p.exterior) for p in parts], dtype=object)
        tree = shapely.STRtree(outlines)
        a, b = tree.query(outlines, predicate="dwithin", distance=kerf * 0.99)
        pairs = [(i, j) for i, j in zip(a, b) if i < j]
        # only the frame's hole may contain pieces; no two outlines come closer than a kerf
        for i, j in pairs:
            inside = outlines[i].contains(outlines[j]) or outlines[j].contains(outlines[i])
            assert inside
        bounds = shapely.total_bounds(outlines)
        assert bounds[0] >= 0 and bounds[1] >= 0 and bounds[2] <= 600 and bounds[3] <= 450


def test_front_halves_split_along_the_parent_edge(puzzle):
    halves = piece_halves(puzzle)
    octagons = puzzle.kinds == OCTAGON
    merged = shapely.union(halves[octagons, 0], halves[octagons, 1])
    np.testing.assert_allclose(shapely.area(merged), shapely.area(puzzle.pieces[octagons]),
                               rtol=1e-9)
    # the shared border of the two halves is one straight segment between parent vertices
    border = shapely.intersection(shapely.boundary(halves[octagons, 0]),
                                  shapely.boundary(halves[octagons, 1]))
    # (the parent's vertices keep their ids; the pieces use their level-t positions)
    n_parent = puzzle.hierarchy[-2].mesh.n_vertices
    parent_vertices = puzzle.to_mm(puzzle.hierarchy[-1].mesh.vertices[:n_parent])
    ends = shapely.get_coordinates(shapely.line_merge(border))
    tree = shapely.STRtree(shapely.points(parent_vertices))
    d = tree.query_nearest(shapely.points(ends), return_distance=True)[1]
    assert d.max() < 1e-6


def test_front_and_back_colours_follow_the_lineage(puzzle):
    colouring = colour_puzzle(puzzle, palette("puzzle"))
    child, parent = puzzle.weaves[-1], puzzle.weaves[-2]
    ps = child.parent_strand
    # a back strand wears exactly its parent's front colour (colouring.py: "a level t strand
    # wears its parent's front colour"), an orphan none; not a sibling's, not a tint
    assert (ps >= 0).sum() > len(ps) // 2
    for s, p in enumerate(ps.tolist()):
        assert colouring.back_strands[s] == (colouring.front_strands[p] if p >= 0
                                             else UNPAINTED), s
    # front halves: each wears a parent strand's colour, and every parent colour is worn
    worn = set(colouring.front.ravel()) - {UNPAINTED}
    assert worn == set(colouring.front_strands) - {UNPAINTED}
    assert len(colouring.front_strands) == parent.n_strands


def test_cli_writes_a_complete_set_that_loads(tmp_path):
    out = tmp_path / "puzzle"
    result = CliRunner().invoke(cli, ["puzzle", "-o", str(out), "--levels", "3", "--size",
                                      "30cm", "--numbers", "--json", "--sheet", "600x450mm"])
    assert result.exit_code == 0, result.output
    info = json.loads(result.output)
    assert info["pieces"] == sum(info["pieces_by_type"].values())
    for name in info["files"]:
        assert (out / name).stat().st_size > 0
    doc = ezdxf.readfile(out / "puzzle-shared-cut.dxf")
    assert not doc.audit().has_errors
    assert doc.header["$INSUNITS"] == 4
    layers = {layer.dxf.name for layer in doc.layers}
    assert {"cut-1-inner", "cut-2-hole", "cut-3-outer"} <= layers
    assert len(doc.modelspace().query("LWPOLYLINE")) > 0
    # the sheet is in millimetres, one user unit a millimetre, and the outline drawn on it is
    # the asked 30 cm across its corners (--size measures the diagonal), seen on the path
    root = ElementTree.parse(out / "puzzle-shared-cut.svg").getroot()
    assert root.get("width").endswith("mm") and root.get("height").endswith("mm")
    width, height = (float(root.get(k)[:-2]) for k in ("width", "height"))
    assert [float(v) for v in root.get("viewBox").split()] == [0, 0, width, height]
    ns = "{http://www.w3.org/2000/svg}"
    (outer,) = [g for g in root.iter(f"{ns}g") if g.get("id") == "cut-cut-3-outer"]
    xy = np.array([float(v) for path in outer.iter(f"{ns}path")
                   for v in path.get("d").replace("M", " ").replace("Z", " ")
                   .replace(",", " ").split()]).reshape(-1, 2)
    assert np.hypot(*(xy[:, None] - xy[None]).transpose(2, 0, 1)).max() == \
        pytest.approx(300.0, abs=0.01)
    assert np.ptp(xy[:, 0]) < width <= np.ptp(xy[:, 0]) + 50
    assert not list(out.glob(".*part"))


def test_front_guide_paints_every_piece_once(puzzle):
    """Each painted half appears once: the same ring twice in one even-odd path cancels out
    (which once left every border piece blank)."""
    colouring = colour_puzzle(puzzle, palette("puzzle"))
    drawing = guide(puzzle, colouring, "front")
    paint = next(layer for layer in drawing.sheets[0].layers if layer.name == "paint")
    polys = paint.shapes[0].to_shapely()
    keys = {tuple(np.round(shapely.normalize(p).exterior.coords, 6).ravel()) for p in polys}
    assert len(keys) == len(polys)
    # painted area = the level-t mesh (pieces without their hexagons)
    hexes = puzzle.hexagons[puzzle.hexagons != None]  # noqa: E711
    expected = shapely.area(puzzle.pieces).sum() - shapely.area(hexes).sum()
    assert shapely.area(polys).sum() == pytest.approx(expected, rel=1e-9)
    assert all(f != "#ffffff" for f in paint.shapes[0].fills)


def test_separate_sheet_dxf_has_one_closed_polyline_per_outline(tmp_path, puzzle):
    from weavecut import export
    result = pf.separate_cut(puzzle, laser("ponoko"), 0.15, (700.0, 700.0),
                             numbers=pf.piece_numbers(puzzle))
    n_outlines = 0
    for n, one in enumerate(pf.split_sheets(result.drawing)):
        path = tmp_path / f"sheet-{n}.dxf"
        export.write(one, path)
        doc = ezdxf.readfile(path)
        assert not doc.audit().has_errors
        assert doc.header["$INSUNITS"] == 4
        polys = [p for p in doc.modelspace().query("LWPOLYLINE")
                 if p.dxf.layer.startswith("cut")]
        assert all(p.closed for p in polys)
        assert {p.dxf.layer for p in polys} <= {"cut-1-inner", "cut-2-outer"}
        n_outlines += len(polys)
        assert not doc.modelspace().query("TEXT MTEXT")  # numbers are strokes
        strokes = doc.modelspace().query("LWPOLYLINE LINE")
        assert {e.dxf.layer for e in strokes} <= {"cut-1-inner", "cut-2-outer",
                                                  "engrave-numbers"}
    assert n_outlines == puzzle.n_pieces + 2  # pieces, the frame's hole and its outline
    # ponoko cuts in blue
    cut = result.drawing.sheets[0].layers[0].shapes[0].style
    assert cut.stroke == "#0000ff"


def test_guides_are_registered_to_the_cut_sheet(puzzle):
    colouring = colour_puzzle(puzzle, palette("puzzle"))
    cut = pf.shared_cut(puzzle, laser()).drawing.sheets[0]
    front = guide(puzzle, colouring, "front").sheets[0]
    back = guide(puzzle, colouring, "back").sheets[0]
    assert (front.width, front.height) == (cut.width, cut.height) == (back.width, back.height)
    outer_cut = cut.layers[2].shapes[0].coords
    frame_front = next(layer for layer in front.layers if layer.name == "frame").shapes[0]
    frame_back = next(layer for layer in back.layers if layer.name == "frame").shapes[0]
    assert shapely.Polygon(frame_front.rings()[0]).equals_exact(
        shapely.Polygon(outer_cut[:-1]), 1e-6) or shapely.Polygon(
        frame_front.rings()[0]).normalize().equals_exact(
        shapely.Polygon(outer_cut[:-1]).normalize(), 1e-6)
    mirrored = frame_back.coords * [-1, 1] + [back.width, 0]
    np.testing.assert_allclose(np.sort(mirrored, axis=0), np.sort(frame_front.coords, axis=0),
                               atol=1e-9)


@settings(max_examples=25, deadline=None)
@given(st.lists(st.tuples(st.floats(5, 80), st.floats(5, 80), st.floats(0, 180)),
                min_size=1, max_size=40), st.floats(0.1, 2.0))
def test_nesting_keeps_parts_apart_and_on_the_sheet(boxes, spacing):
    from shapely import affinity
    from weavecut.layout.nesting import nest
    parts = np.array([affinity.rotate(shapely.box(0, 0, w, h), a) for w, h, a in boxes],
                     dtype=object)
    placement = nest(parts, (200.0, 150.0), spacing, margin=5.0)
    placed = placement.apply(parts)
    np.testing.assert_allclose(shapely.area(placed), shapely.area(parts), rtol=1e-9)
    for s in range(placement.n_sheets):
        on = placed[placement.sheet == s]
        assert len(on) > 0
        lo, hi = shapely.total_bounds(on)[:2], shapely.total_bounds(on)[2:]
        assert lo.min() >= 5.0 - 1e-6 and hi[0] <= 195.0 + 1e-6 and hi[1] <= 145.0 + 1e-6
        tree = shapely.STRtree(on)
        a, b = tree.query(on, predicate="dwithin", distance=spacing * 0.999)
        assert not (a < b).any()
