"""The cut files read back with ezdxf and checked against the puzzle's geometry: the shared cut
covers every outline once in paths whose lengths and travel add up, the score lines are the
ring's free edges, separate pieces grow by perimeter x kerf/2 while the frame's hole shrinks
by it, and a kerf wider than a piece is refused. The puzzles are built once per process
(tests/built_puzzles.py); the cuts are made in every test."""

from __future__ import annotations

import ezdxf
import numpy as np
import pytest
import shapely

from weavecut import export
from weavecut.errors import WeaveCutError
from weavecut.layout.lasersetup import laser
from weavecut.puzzle import files as pf
from weavecut.puzzle.frame import split_frame

from tests.built_puzzles import pentagon_puzzle


def _puzzle(levels=3):
    return pentagon_puzzle(levels)


def _read(drawing, path):
    """(layer, (n, 2) points, closed) of every polyline of a one-sheet drawing, in file order."""
    export.write(drawing, path)
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors and doc.header["$INSUNITS"] == 4
    return [(e.dxf.layer, np.array(e.get_points("xy")), e.closed)
            for e in doc.modelspace().query("LWPOLYLINE")]


def _segments(points, closed):
    """(n, 2, 2) the segments of one polyline."""
    pts = np.concatenate([points, points[:1]]) if closed else points
    return np.stack([pts[:-1], pts[1:]], axis=1)


def test_shared_cut_read_back_cuts_every_outline_once_in_its_layer(tmp_path):
    puzzle = _puzzle()
    result = pf.shared_cut(puzzle, laser(), pf.piece_numbers(puzzle))
    width, height, shift = pf.placement(puzzle)
    sheet = result.drawing.sheets[0]
    assert (sheet.width, sheet.height) == (width, height)
    x0, y0, x1, y1 = puzzle.outer.bounds
    assert (width, height) == pytest.approx((x1 - x0 + 20.0, y1 - y0 + 20.0))
    np.testing.assert_allclose(shift, [10.0 - x0, 10.0 - y0])
    read = _read(result.drawing, tmp_path / "shared.dxf")
    cuts = [(layer, p, c) for layer, p, c in read if layer.startswith("cut")]
    assert [layer for layer, _, _ in cuts] == sorted(layer for layer, _, _ in cuts)
    assert len(cuts) == result.n_paths
    pieces = shapely.transform(puzzle.pieces, lambda xy: xy + shift)
    hole = shapely.transform(puzzle.hole, lambda xy: xy + shift)
    outer = shapely.transform(puzzle.outer, lambda xy: xy + shift)
    segs = np.concatenate([_segments(p, c) for _, p, c in cuts])
    layer_of = np.concatenate([[layer] * len(_segments(p, c)) for layer, p, c in cuts])
    lines = shapely.linestrings(segs)
    mid = shapely.points(segs.mean(axis=1))
    # no segment twice; the lengths add up to what the result says
    key = np.round(np.sort(segs.reshape(-1, 4).reshape(-1, 2, 2), axis=1), 6).reshape(-1, 4)
    assert len(np.unique(key, axis=0)) == len(segs)
    assert shapely.length(lines).sum() == pytest.approx(result.cut_length, rel=1e-9)
    # every piece's outline and the frame's outline are cut
    cut = shapely.buffer(shapely.union_all(lines), 1e-6)
    assert shapely.length(shapely.difference(shapely.boundary(pieces), cut)).max() < 1e-6
    assert shapely.difference(outer.exterior, cut).length < 1e-6
    # each in its layer: inner cuts between two pieces, the hole's outline, the outer last
    n_near = np.array([len(shapely.STRtree(shapely.boundary(pieces)).query(
        m, predicate="dwithin", distance=1e-6)) for m in mid])
    on_hole = shapely.distance(mid, hole.exterior) < 1e-6
    on_outer = shapely.distance(mid, outer.exterior) < 1e-6
    assert ((n_near == 2) & ~on_hole)[layer_of == "cut-1-inner"].all()
    assert ((n_near == 1) & on_hole)[layer_of == "cut-2-hole"].all()
    assert on_outer[layer_of == "cut-3-outer"].all()
    assert set(layer_of) == {"cut-1-inner", "cut-2-hole", "cut-3-outer"}
    # head travel: from the top-left corner to each path's start, from its end to the next
    here, travel = np.array([0.0, height]), 0.0
    for _, p, c in cuts:
        travel += np.hypot(*(p[0] - here))
        here = p[0] if c else p[-1]
    assert travel == pytest.approx(result.travel_length, rel=1e-9)
    assert result.n_sheets == 1


def test_score_lines_are_the_ring_cells_edges_off_the_hole(tmp_path):
    puzzle = _puzzle()
    result = pf.shared_cut(puzzle, laser())
    _, _, shift = pf.placement(puzzle)
    read = _read(result.drawing, tmp_path / "shared.dxf")
    score = [shapely.LineString(p) for layer, p, _ in read if layer == "score-ring"]
    assert score
    ring_edges = shapely.union_all(shapely.get_exterior_ring(
        shapely.transform(puzzle.ring, lambda xy: xy + shift)))
    hole = shapely.transform(puzzle.hole, lambda xy: xy + shift).exterior
    free = shapely.difference(ring_edges, shapely.buffer(hole, 1e-6))
    assert sum(s.length for s in score) == pytest.approx(free.length, rel=1e-6)
    pts = shapely.points(np.concatenate([np.asarray(s.coords) for s in score]))
    assert shapely.distance(pts, ring_edges).max() < 1e-6
    mids = shapely.line_interpolate_point(np.array(score, dtype=object), 0.5, normalized=True)
    assert shapely.distance(mids, hole).min() > 1e-3
    no_score = pf.shared_cut(puzzle, laser(), score_ring=False).drawing.sheets[0]
    assert "score-ring" not in [layer.name for layer in no_score.layers]


@pytest.mark.parametrize("kerf", [0.2, 0.4])
def test_separate_pieces_grow_and_the_hole_shrinks_by_perimeter_times_half_kerf(tmp_path, kerf):
    """Read back from every sheet's DXF: one closed outline per piece, grown by about
    perimeter x kerf/2 (exactly the mitred offset), the frame's outline grown and its hole
    shrunk by the same rule."""
    puzzle = _puzzle(2)
    sheet = (500.0, 400.0)
    result = pf.separate_cut(puzzle, laser(), kerf, sheet)
    sheets = pf.split_sheets(result.drawing)
    assert len(sheets) == result.n_sheets == len(result.drawing.sheets)
    rings, length, corners = [], 0.0, 0
    for n, one in enumerate(sheets):
        read = _read(one, tmp_path / f"sheet-{n}.dxf")
        cut = [p for layer, p, closed in read if layer.startswith("cut") and closed]
        assert len(cut) == len([1 for layer, _, _ in read if layer.startswith("cut")])
        polygons = [shapely.Polygon(p) for p in cut]
        length += sum(p.exterior.length for p in polygons)
        corners += sum(len(p.exterior.coords) for p in polygons)
        assert shapely.total_bounds(polygons)[2] <= sheet[0] + 1e-6
        rings += polygons
    assert len(rings) == result.n_paths == puzzle.n_pieces + 2
    # the DXF keeps 6 decimals: each segment's length moves by at most sqrt(2) x 1e-6
    assert length == pytest.approx(result.cut_length, rel=0, abs=1.5e-6 * corners)
    area = np.sort([p.area for p in rings])
    outer, hole, pieces = area[-1], area[-2], area[:-2]
    first = shapely.area(puzzle.pieces) + shapely.length(puzzle.pieces) * kerf / 2
    np.testing.assert_allclose(pieces, np.sort(first), rtol=0, atol=40 * kerf ** 2)
    # the DXF keeps 6 decimals (1 nm): an area moves by at most its perimeter x 1 nm
    mitred = shapely.buffer(puzzle.pieces, kerf / 2, join_style="mitre")
    order = np.argsort(shapely.area(mitred))
    assert (np.abs(pieces - shapely.area(mitred)[order])
            <= 1e-6 * shapely.length(mitred)[order]).all()
    assert hole == pytest.approx(puzzle.hole.area - puzzle.hole.length * kerf / 2,
                                 abs=400 * kerf ** 2)
    shrunk = shapely.buffer(puzzle.hole, -kerf / 2, join_style="mitre")
    assert hole == pytest.approx(shrunk.area, abs=1e-6 * shrunk.length)
    assert outer == pytest.approx(puzzle.outer.area + puzzle.outer.length * kerf / 2,
                                  abs=10 * kerf ** 2)


def test_a_split_frame_is_cut_in_its_parts_each_labelled(tmp_path):
    puzzle = _puzzle(2)
    sheet = (250.0, 200.0)
    parts = split_frame(puzzle.frame, puzzle.outer, sheet, 5.0, 0.2)
    assert len(parts) >= 2
    result = pf.separate_cut(puzzle, laser(), 0.2, sheet, frame_parts=parts)
    rings = [shapely.Polygon(r) for s in result.drawing.sheets for layer in s.layers
             if layer.role == "cut" for shape in layer.shapes for r in shape.rings()]
    assert len(rings) == puzzle.n_pieces + len(parts)  # split parts have no inner ring
    grown = np.sort(shapely.area(shapely.buffer(parts, 0.1, join_style="mitre")))
    np.testing.assert_allclose(np.sort([r.area for r in rings])[-len(parts):], grown,
                               rtol=1e-9)
    # every part carries its label's strokes inside it: F1 ... Fk, counted by sheet
    labelled = 0
    for s in result.drawing.sheets:
        cut = [shapely.Polygon(r) for layer in s.layers if layer.role == "cut"
               for shape in layer.shapes for r in shape.rings()]
        big = [p for p in cut if p.area > 0.5 * min(shapely.area(parts))]
        eng = [ln for layer in s.layers if layer.name == "engrave-numbers"
               for shape in layer.shapes for ln in shape.lines()]
        strokes = [shapely.LineString(ln) for ln in eng]
        for p in big:
            inside = [st for st in strokes if p.contains(st)]
            assert inside, "a frame part without its label"
            labelled += 1
    assert labelled == len(parts)
    assert pf.frame_labels(parts) == [f"F{k + 1}" for k in range(len(parts))]
    assert pf.frame_labels(parts[:1]) == [""]


def test_a_kerf_as_wide_as_the_smallest_pieces_inner_radius_is_refused():
    puzzle = _puzzle(2)
    inner = 2 * shapely.area(puzzle.pieces) / shapely.length(puzzle.pieces)
    k = int(np.argmin(inner))
    pf.check_kerf(puzzle, float(inner[k]) * (1 - 1e-9))
    with pytest.raises(WeaveCutError, match=rf"^a kerf of {inner[k]:g} mm is wider than piece "
                                            rf"{k + 1} \({inner[k]:.3g} mm inner radius\); use "
                                            r"a smaller --kerf or a larger --size$"):
        pf.check_kerf(puzzle, float(inner[k]))


def test_closed_rings_drop_their_repeated_last_point():
    square = np.array([(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)], dtype=float)
    open_line = np.array([(0, 0), (2, 0), (2, 2)], dtype=float)
    shape = pf._closed([square, open_line], laser().style("cut"))
    assert [len(r) for r in shape.rings()] == [4, 3]
    np.testing.assert_array_equal(shape.rings()[0], square[:-1])
    empty = pf._closed([], laser().style("cut"))
    assert len(empty.coords) == 0 and empty.ring_offsets.tolist() == [0]
