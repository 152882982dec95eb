"""Closed outlines made into faces: orientation, holes, welding, T-junctions, lines that
enclose faces, and the one-line errors a drawing gets when it cannot be a mesh.

Expected values come from the drawn geometry (where two segments cross, which ring lies
inside which, Euler's formula), written out by hand.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import shapely

from weavecut.errors import MeshError, MeshFileError
from weavecut.mesh_geometry import signed_areas
from weavecut.readers import drawing
from weavecut.readers.drawing import read_drawing
from weavecut.readers.rings import (Ring, checked, close_groups, enclosed_faces, nesting,
                                    split_t_junctions, weld)
from weavecut.validation import validate


def square(x0, y0, side, clockwise=False) -> np.ndarray:
    p = np.array([(x0, y0), (x0 + side, y0), (x0 + side, y0 + side), (x0, y0 + side)], float)
    return p[::-1] if clockwise else p


def euler(mesh) -> int:
    return mesh.n_vertices - mesh.topology.n_edges + mesh.n_faces


def svg(tmp_path: Path, body: str) -> Path:
    path = tmp_path / "d.svg"
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="200mm" '
                    f'viewBox="0 0 200 200">{body}</svg>', encoding="utf-8")
    return path


# --- checked ------------------------------------------------------------------------------

def test_rings_come_out_counter_clockwise_without_repeated_points():
    cw = square(0, 0, 10, clockwise=True)
    twice = np.repeat(square(20, 0, 10), 2, axis=0)  # every corner drawn twice
    out = checked([Ring("cw", cw), Ring("twice", twice), Ring("ccw", square(40, 0, 10))], 0.2)
    assert [r.label for r in out] == ["cw", "twice", "ccw"]
    for ring in out:
        assert len(ring.points) == 4
        assert shapely.Polygon(ring.points).exterior.is_ccw
    assert out[0].points.tolist() == cw[::-1].tolist()
    assert out[1].points.tolist() == square(20, 0, 10).tolist()


@pytest.mark.parametrize("repeat", [0, 1, 2])
def test_a_triangle_with_a_corner_drawn_twice_is_the_triangle(repeat):
    """The smallest ring with a repeated point: three distinct corners, one of them twice (an
    SVG path that returns to its start before ``z``, a DXF polyline closed on its last point)."""
    triangle = np.array([(0, 0), (10, 0), (0, 10)], float)
    drawn = np.insert(triangle, repeat, triangle[repeat], axis=0)
    (out,) = checked([Ring("t", drawn)], 0.2)
    assert out.points.tolist() == triangle.tolist()


def test_a_ring_that_crosses_itself_names_where():
    """The bow (0, 0) (30, 10) (30, 0) (0, 20): y = x / 3 meets y = 20 - 2 x / 3 at (20, 20/3)."""
    bow = np.array([(0, 0), (30, 10), (30, 0), (0, 20)], float)
    with pytest.raises(MeshFileError) as error:
        checked([Ring("bow", bow)], 0.2)
    assert str(error.value) == ("bow crosses itself near (20, 6.667) mm (y up); a face must be "
                                "a simple closed outline")


@pytest.mark.parametrize("points", [
    [(0, 0), (10, 0)],                      # two points
    [(0, 0), (10, 0), (20, 0)],             # a line
    [(0, 0), (10, 0), (10, 0.003)],         # 0.015 mm² < 0.2² mm²
    [(0, 0), (1, 0), (0, 0.02), (1, 0.02)],  # a bow tie of 0.01 mm²
])
def test_a_ring_without_area_is_refused(points):
    with pytest.raises(MeshFileError, match="^flat encloses no area$"):
        checked([Ring("flat", np.array(points, float))], 0.2)


def test_a_small_ring_above_the_tolerance_is_kept():
    out = checked([Ring("small", square(0, 0, 0.25))], 0.2)  # 0.0625 mm² > 0.04 mm²
    assert len(out) == 1


# --- nesting ------------------------------------------------------------------------------

def test_holes_are_rings_inside_an_odd_number_of_others():
    """A 100 mm square, a hole in it, an island in the hole, a hole in the island; beside
    them a square that shares an edge with the big one (touching is not overlapping)."""
    rings = checked([Ring("outer", square(0, 0, 100)), Ring("island", square(20, 20, 60)),
                     Ring("hole", square(10, 10, 80)), Ring("pit", square(40, 40, 20)),
                     Ring("beside", square(100, 0, 30))], 0.2)
    assert nesting(rings, 0.2).tolist() == [-1, -1, 0, 1, -1]


def test_overlapping_rings_are_named_in_drawing_order():
    rings = checked([Ring("a", square(0, 0, 10)), Ring("b", square(50, 0, 10)),
                     Ring("c", square(5, 5, 10))], 0.2)
    with pytest.raises(MeshFileError, match="^a and c overlap; faces may share edges but not "
                                            "insides$"):
        nesting(rings, 0.2)


def test_rings_that_overlap_by_less_than_the_tolerance_are_neighbours():
    """Drawn by hand, two squares overlap by 0.1 mm along their shared side."""
    rings = checked([Ring("a", square(0, 0, 10)), Ring("b", square(9.9, 0, 10))], 0.2)
    assert nesting(rings, 0.2).tolist() == [-1, -1]


# --- weld, T-junctions --------------------------------------------------------------------

def test_weld_merges_near_points_onto_the_first():
    a = square(0, 0, 10)
    b = np.array([(10.1, 0.05), (20, 0), (20, 10), (10, 10.1)])
    mesh, merged = weld([a, b], 0.2)
    assert merged == 2
    assert (mesh.n_vertices, mesh.n_faces, euler(mesh)) == (6, 2, 1)
    assert mesh.vertices.tolist() == [[0, 0], [10, 0], [10, 10], [0, 10], [20, 0], [20, 10]]


def test_weld_refuses_a_face_that_collapses():
    tiny = np.array([(10, 0), (10.05, 0), (10.05, 0.05)])
    with pytest.raises(MeshFileError, match=r"^face 1 collapses to fewer than 3 corners when "
                                            r"points closer than 0.2 mm are merged$"):
        weld([square(0, 0, 10), tiny], 0.2)


def test_close_groups_chain_and_keep_fixed_points_alone():
    points = np.array([(0, 0), (0.15, 0), (0.3, 0), (5, 5), (5.1, 5)])
    assert close_groups(points, 0.2).tolist() == [0, 0, 0, 1, 1]
    fixed = close_groups(points, 0.2, movable=np.array([1, 0, 1, 1, 1], bool))
    assert len(set(fixed[:3].tolist())) == 3 and fixed[3] == fixed[4]


def test_an_edge_split_twice_on_one_side_becomes_three_shared_edges():
    """A 30 mm square beside three 10 mm squares stacked along its right side: the square's
    right edge is split at y = 10 and y = 20, in order. V = 4 + 4 = 8 + 2 (the split points
    are the small squares' corners), E = 4 + 3 + 3 + 3 ... Euler: one disc."""
    big = square(0, 0, 30)
    smalls = [square(30, y, 10) for y in (20, 0, 10)]  # drawn out of order
    mesh, _ = weld([big, *smalls], 0.2)
    split = validate(split_t_junctions(mesh, 0.2))
    assert (split.n_vertices, split.n_faces, euler(split)) == (10, 4, 1)
    assert split.face_sizes.tolist() == [6, 4, 4, 4]
    big_face = split.vertices[split.faces()[0]]
    assert big_face.tolist() == [[0, 0], [30, 0], [30, 10], [30, 20], [30, 30], [0, 30]]
    assert split_t_junctions(split, 0.2) is split  # nothing left to split


# --- lines that enclose faces -------------------------------------------------------------

def test_a_grid_of_lines_encloses_its_cells():
    """Three horizontal and four vertical lines, each drawn once: 2 x 3 cells of 10 mm."""
    lines = [Ring(f"h{k}", np.array([(0, 10 * k), (30, 10 * k)])) for k in range(3)]
    lines += [Ring(f"v{k}", np.array([(10 * k, 0), (10 * k, 20)])) for k in range(4)]
    faces = enclosed_faces([], lines, 0.2)
    assert len(faces) == 6
    assert [abs(shapely.Polygon(f.points).area) for f in faces] == pytest.approx([100.0] * 6)


def test_a_line_that_misses_by_less_than_the_tolerance_joins():
    """A triangle of lines whose ends miss each other by 0.1 mm, and a diagonal that starts
    0.1 mm from a square's corner: every end joins (the square splits in two)."""
    lines = [Ring("a", np.array([(0, 0), (10, 0)])), Ring("b", np.array([(10.1, 0), (0, 10)])),
             Ring("c", np.array([(0, 10.1), (0, 0.1)])),
             Ring("d", np.array([(20.1, 0.05), (30, 10)]))]  # across the square
    faces = enclosed_faces([Ring("sq", square(20, 0, 10))], lines, 0.2)
    assert sorted(round(abs(shapely.Polygon(f.points).area)) for f in faces) == [50, 50, 50]


def test_a_dangling_line_is_named_where_it_ends():
    """The tail starts on the triangle's hypotenuse and ends in the open at (40, 30)."""
    lines = [Ring("a", np.array([(0, 0), (10, 0)])), Ring("b", np.array([(10, 0), (0, 10)])),
             Ring("c", np.array([(0, 10), (0, 0)])), Ring("tail", np.array([(5, 5), (40, 30)]))]
    with pytest.raises(MeshFileError, match=r"^tail near \(40, 30\) mm has an open end; lines "
                                            r"and arcs must enclose faces$"):
        enclosed_faces([], lines, 0.2)



def _redrawn(rings, pieces, turn: int):
    """The same drawing drawn otherwise: every ring starting ``turn`` corners later (and the
    odd ones the other way round), every piece reversed, both lists in reverse order."""
    rings = [Ring(r.label, np.roll(r.points, -turn, axis=0)[::(-1) ** k])
             for k, r in enumerate(rings)]
    return rings[::-1], [Ring(p.label, p.points[::-1]) for p in pieces[::-1]]


def test_enclosed_faces_are_numbered_and_started_by_their_geometry():
    """An untouched pentagon, a square that a line cuts from its lower-left corner (two
    triangles sharing that corner) and a house of lines: each face runs counter-clockwise from
    its leftmost corner (the lowest of them), the faces are in the order of those corners
    (x, then y) and the two triangles counter-clockwise around theirs; the same drawing
    drawn from other corners, the other way round, in another order gives the same faces."""
    pentagon = np.array([(60, 0), (70, 0), (75, 8), (65, 14), (55, 8)], dtype=float)
    rings = [Ring("pentagon", pentagon), Ring("square", square(20, 0, 10))]
    pieces = [Ring("diagonal", np.array([(20, 0), (30, 10)])),
              Ring("walls", np.array([(0, 0), (0, 10), (5, 15), (10, 10), (10, 0)])),
              Ring("floor", np.array([(0, 0), (10, 0)])),
              Ring("ceiling", np.array([(0, 10), (10, 10)]))]
    faces = enclosed_faces(rings, pieces, 0.2)
    want = [[(0, 0), (10, 0), (10, 10), (0, 10)], [(0, 10), (10, 10), (5, 15)],
            [(20, 0), (30, 0), (30, 10)], [(20, 0), (30, 10), (20, 10)],
            [(55, 8), (60, 0), (70, 0), (75, 8), (65, 14)]]
    assert [f.points.tolist() for f in faces] == [np.array(w, float).tolist() for w in want]
    assert [f.label for f in faces] == [f"face {k} enclosed by lines" for k in range(1, 6)]
    for f in faces:
        assert shapely.Polygon(f.points).exterior.is_ccw
        assert tuple(f.points[0]) == min(map(tuple, f.points))
    for turn in (1, 2, 3):
        again = enclosed_faces(*_redrawn(rings, pieces, turn), 0.2)
        assert [f.points.tolist() for f in again] == [f.points.tolist() for f in faces], turn


# --- drawing.read: files and options ------------------------------------------------------

def test_missing_empty_and_oversized_files_are_one_line(tmp_path, monkeypatch):
    with pytest.raises(MeshFileError, match=r"^cannot read .*nope\.svg: no such file$"):
        read_drawing(tmp_path / "nope.svg")
    with pytest.raises(MeshFileError, match=r"d\.svg: no outlines found$"):
        read_drawing(svg(tmp_path, ""))
    path = svg(tmp_path, '<rect width="10" height="10"/>')
    monkeypatch.setattr(drawing, "MAX_BYTES", path.stat().st_size - 1)
    with pytest.raises(MeshFileError, match=r"d\.svg: 0 MiB is more than a drawing of faces "
                                            r"needs \(at most 0 MiB\)$"):
        read_drawing(path)
    monkeypatch.setattr(drawing, "MAX_BYTES", path.stat().st_size)
    assert read_drawing(path, mesh="none").n_faces == 1


def test_mesh_choices(tmp_path):
    """auto meshes one outline or a drawing with holes and keeps several faces as drawn;
    a kind meshes several; an unknown kind is refused naming the choices."""
    one = svg(tmp_path, '<rect id="a" width="60" height="40"/>')
    assert read_drawing(one, cell=10.0).n_faces > 1
    assert read_drawing(one, mesh="none").n_faces == 1
    two = tmp_path / "two.svg"
    two.write_text(svg(tmp_path, '<rect id="a" width="30" height="30"/>'
                   '<rect id="b" x="30" width="30" height="30"/>').read_text())
    assert read_drawing(two).n_faces == 2
    reports = []
    meshed = read_drawing(two, mesh="quad", cell=10.0, report=reports.append)
    assert meshed.n_faces == 18 and euler(meshed) == 1
    assert re.fullmatch(r"two\.svg: 2 outlines, 0 holes, 1800 mm², meshed quad with "
                        r"cell 10 mm: 18 faces, angles 90-90°, size 1\.00-1\.00 × cell",
                        reports[0]), reports[0]
    with pytest.raises(MeshError, match=r"unknown --mesh 'pent'; choose one of auto, none, hex, "
                                        r"quad, tri, voronoi$"):
        read_drawing(one, mesh="pent")


def test_separate_outlines_mesh_apart(tmp_path):
    """Two squares 20 mm apart, meshed: two discs (Euler 2), each covered whole."""
    path = svg(tmp_path, '<rect id="a" width="30" height="30"/>'
               '<rect id="b" x="50" width="30" height="30"/>')
    reports = []
    for kind in ("hex", "quad", "voronoi", "tri"):
        mesh = validate(read_drawing(path, mesh=kind, cell=6.0, report=reports.append))
        assert euler(mesh) == 2
        assert signed_areas(mesh).sum() == pytest.approx(1800.0, abs=2 * 240 * 0.2)
    assert reports[0].startswith("d.svg: 2 outlines, 0 holes, 1800 mm², meshed hex")


def test_each_outline_keeps_its_own_holes(tmp_path):
    """Two 40 mm squares, the left with one 10 mm hole, the right with two: meshed, the
    holes stay where they are drawn (Euler 2 - 3) and the area is 2 x 1600 - 3 x 100."""
    path = svg(tmp_path, '<rect id="a" width="40" height="40"/>'
               '<rect id="ha" x="15" y="15" width="10" height="10"/>'
               '<rect id="b" x="60" width="40" height="40"/>'
               '<rect id="hb1" x="65" y="5" width="10" height="10"/>'
               '<rect id="hb2" x="80" y="25" width="10" height="10"/>')
    reports = []
    mesh = validate(read_drawing(path, cell=5.0, report=reports.append))
    assert euler(mesh) == -1
    assert signed_areas(mesh).sum() == pytest.approx(2900.0, abs=0.2 * 440)
    assert reports[0].startswith("d.svg: 2 outlines, 3 holes, 2900 mm², meshed hex")
    centres = np.array([(20, -20), (70, -10), (85, -30)])  # y up
    faces = shapely.polygons(shapely.linearrings(mesh.vertices[mesh.face_indices],
                                                 indices=mesh.half_edge_face))
    assert not shapely.intersects(faces[:, None], shapely.points(centres)[None]).any()


def test_a_simple_ring_of_no_area_is_refused_though_its_hull_has_one():
    """A thin V, drawn out and back along almost the same line: simple (no crossing), its hull
    100 mm², but 0.01 mm² inside, below the flattening tolerance squared (0.04 mm²)."""
    from weavecut.readers.rings import Ring, checked

    v = np.array([(0.0, 0.0), (10.0, 10.0), (20.0, 0.0), (10.0, 10.001)])
    polygon = shapely.Polygon(v)
    assert polygon.is_valid and polygon.area < 0.2 ** 2 < polygon.convex_hull.area
    with pytest.raises(MeshFileError, match=r'^<path id="v"> encloses no area$'):
        checked([Ring('<path id="v">', v)], 0.2)
    dart = np.array([(0.0, 0.0), (10.0, 10.0), (20.0, 0.0), (10.0, 15.0)])  # 50 mm² inside
    assert len(checked([Ring("dart", dart)], 0.2)) == 1
