"""Meshed outlines keep the outline's topology and area: holes stay holes, no gaps open
between faces, separate outlines stay apart, every face convex and counter-clockwise.

The oracles are Euler's formula (V - E + F = outlines - holes for a mesh without gaps), the
union of the faces as shapely polygons, and each face's own corners.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from weavecut.errors import MeshError
from weavecut.mesh_geometry import corner_turns, signed_areas
from weavecut.readers import outline_mesh, pieces, tessellations
from weavecut.readers.pieces import convex_pieces, merged_small
from weavecut.validation import validate

KINDS = ("hex", "quad", "voronoi", "tri")
FRAME = shapely.box(0, 0, 60, 40).difference(shapely.box(20, 15, 35, 25))  # 2250 mm², a hole
TWO = shapely.MultiPolygon([shapely.box(0, 0, 30, 30), shapely.box(50, 0, 80, 30)])
L_SHAPE = shapely.Polygon([(0, 0), (50, 0), (50, 20), (20, 20), (20, 50), (0, 50)])


def faces_of(mesh):
    return shapely.polygons(shapely.linearrings(mesh.vertices[mesh.face_indices],
                                                indices=mesh.half_edge_face))


def euler(mesh) -> int:
    return mesh.n_vertices - mesh.topology.n_edges + mesh.n_faces


@pytest.mark.parametrize("region, expected_euler", [(FRAME, 0), (TWO, 2), (L_SHAPE, 1)])
@pytest.mark.parametrize("kind", KINDS)
def test_meshes_keep_the_outlines_topology_and_area(region, expected_euler, kind):
    """No gap opens between the faces (a gap is a hole the outline does not have), the faces
    are convex and counter-clockwise, and they cover the outline but for slivers along it."""
    cell = 8.0
    mesh = validate(outline_mesh.mesh_outline(region, kind, cell))
    assert euler(mesh) == expected_euler
    union = shapely.union_all(faces_of(mesh))
    assert shapely.symmetric_difference(union, region).area <= 0.2 * region.boundary.length
    assert signed_areas(mesh).min() > 0
    p = mesh.vertices[mesh.face_indices]
    edges = np.hypot(*(p[mesh.next_half_edge] - p).T)
    assert (corner_turns(mesh) / (edges * edges[mesh.prev_half_edge])).min() > -1e-9
    if kind == "tri":
        assert (mesh.face_sizes == 3).all()


@pytest.mark.parametrize("kind", ["hex", "quad", "voronoi", "tri", "pent"])
def test_refusals_are_one_line(kind):
    square = shapely.box(0, 0, 10, 10)
    if kind == "pent":
        with pytest.raises(MeshError, match=r"^unknown mesh kind 'pent'; choose one of hex, "
                                            r"quad, tri, voronoi$"):
            outline_mesh.mesh_outline(square, kind, 1.0)
        return
    with pytest.raises(MeshError, match=r"^the outline \(100 mm²\) is smaller than one cell "
                                        r"\(14.2 mm across\); give a smaller --cell$"):
        outline_mesh.mesh_outline(square, kind, 14.2)
    with pytest.raises(MeshError, match=r"^--cell 0.009 mm would give about 1,234,568 faces "
                                        r"\(100 mm²\) and [\d,]+ outline points; at most "
                                        r"10,000 in all: give a larger --cell$"):
        outline_mesh.mesh_outline(square, kind, 0.009)


def test_a_region_of_half_a_cell_is_one_face():
    """The smallest outline meshed (half a cell in area) is one convex face: itself."""
    square = shapely.box(0, 0, 10, 10)
    mesh = outline_mesh.mesh_outline(square, "hex", 14.1)  # 100 mm² >= 99.4 mm²
    assert mesh.n_faces == 1 and signed_areas(mesh)[0] == pytest.approx(100.0)


def test_quality_reports_angles_and_sizes_of_the_faces():
    """A 30 x 20 mm rectangle in 10 mm squares: six squares, every angle 90 degrees, every
    size one cell; with cell 5 the same squares are two cells across."""
    mesh = outline_mesh.mesh_outline(shapely.box(0, 0, 30, 20), "quad", 10.0)
    assert outline_mesh.quality(mesh, 10.0) == pytest.approx(
        {"faces": 6, "min_angle": 90.0, "max_angle": 90.0, "min_size": 1.0,
         "median_size": 1.0, "max_size": 1.0})
    assert outline_mesh.quality(mesh, 5.0)["median_size"] == pytest.approx(2.0)


def test_quality_of_mixed_faces():
    """A square and a right triangle (legs 10): angles 45-90, sizes 10 and sqrt(50)."""
    from weavecut.mesh import Mesh
    mesh = Mesh(np.array([(0, 0), (10, 0), (10, 10), (0, 10), (20, 0)], float),
                np.array([0, 4, 7]), np.array([0, 1, 2, 3, 1, 4, 2]))
    q = outline_mesh.quality(mesh, 10.0)
    assert q == pytest.approx({"faces": 2, "min_angle": 45.0, "max_angle": 90.0,
                               "min_size": math.sqrt(50) / 10, "median_size":
                               (1 + math.sqrt(50) / 10) / 2, "max_size": 1.0})


def test_even_runs_keep_corners_and_cut_sides_equally():
    """A 10 mm square with runs of at most 3 mm: each side in 4 runs of 2.5 mm, corners
    kept; a 40 x 10 rectangle: long sides in 14 runs, short ones in 4."""
    square = np.array([(0, 0), (10, 0), (10, 10), (0, 10)], float)
    runs = outline_mesh._even_runs(square, 3.0)
    assert len(runs) == 16
    assert np.hypot(*(np.roll(runs, -1, 0) - runs).T) == pytest.approx(2.5)
    assert runs[::4].tolist() == square.tolist()
    rect = np.array([(0, 0), (40, 0), (40, 10), (0, 10)], float)
    runs = outline_mesh._even_runs(rect, 3.0)
    lengths = np.hypot(*(np.roll(runs, -1, 0) - runs).T)
    assert len(runs) == 2 * 14 + 2 * 4
    assert sorted(set(np.round(lengths, 9))) == pytest.approx([2.5, 40 / 14])


def test_even_runs_round_a_curve_without_corners():
    """A circle flattened into 200 chords (no turn above 30 degrees): runs of one length all
    round, no longer than the side, each ending on the drawn outline."""
    t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    circle = 20 * np.column_stack([np.cos(t), np.sin(t)])
    runs = outline_mesh._even_runs(circle, 5.0)
    along = np.hypot(*(np.roll(circle, -1, 0) - circle).T).sum()
    assert len(runs) == math.ceil(along / 5.0)
    assert shapely.distance(shapely.LinearRing(circle), shapely.points(runs)).max() < 1e-9
    assert runs[0] == pytest.approx(circle[0])
    # equal runs measured along the outline: the chords are equal to within the curvature
    chords = np.hypot(*(np.roll(runs, -1, 0) - runs).T)
    assert np.ptp(chords) < 1e-3 and chords.max() <= 5.0


@pytest.mark.parametrize("bend, corners", [(20.0, 3), (40.0, 4)])
def test_even_runs_corner_is_a_turn_above_thirty_degrees(bend, corners):
    """A triangle with one side bent in its middle: the bend is a corner (a run ends there)
    only when it turns by more than 30 degrees."""
    half = 20 * math.tan(math.radians(bend / 2))
    ring = np.array([(0, 0), (20, -half), (40, 0), (20, 30)], float)
    runs = outline_mesh._even_runs(ring, 100.0)  # runs longer than any side: corners only
    assert len(runs) == corners


def test_runs_give_the_outline_equal_boundary_runs():
    """A 60 x 40 rectangle meshed with runs: every boundary edge of the mesh is a whole
    number of the sides' run lengths (a straight side's points that one face uses alone are
    dropped), and the mesh still covers the rectangle exactly."""
    cell = 10.0
    mesh = outline_mesh.mesh_outline(shapely.box(0, 0, 60, 40), "hex", cell, runs=True)
    assert signed_areas(mesh).sum() == pytest.approx(2400.0)
    side = outline_mesh.EDGE["hex"] * cell
    runs = {60.0: 60 / math.ceil(60 / side), 40.0: 40 / math.ceil(40 / side)}
    p = mesh.vertices
    u, w = mesh.face_indices, mesh.face_indices[mesh.next_half_edge]
    key = np.minimum(u, w) * len(p) + np.maximum(u, w)
    boundary = np.flatnonzero(np.bincount(np.unique(key, return_inverse=True)[1]) == 1)
    edge = np.unique(key, return_index=True)[1][boundary]
    d = p[w[edge]] - p[u[edge]]
    horizontal = np.abs(d[:, 1]) < 1e-9
    assert (np.abs(d[horizontal, 0]) / runs[60.0]) == pytest.approx(
        np.round(np.abs(d[horizontal, 0]) / runs[60.0]))
    assert (np.abs(d[~horizontal, 1]) / runs[40.0]) == pytest.approx(
        np.round(np.abs(d[~horizontal, 1]) / runs[40.0]))


def test_a_reflex_corner_is_cut_not_smoothed():
    """The L's inner corner (20, 20) stays a vertex of the mesh at every kind: the outline is
    kept to the tolerance, no face bridges the notch."""
    for kind in KINDS:
        mesh = outline_mesh.mesh_outline(L_SHAPE, kind, 8.0)
        assert np.hypot(*(mesh.vertices - (20, 20)).T).min() < 1e-9
        union = shapely.union_all(faces_of(mesh))
        assert union.area == pytest.approx(L_SHAPE.area, abs=0.2 * L_SHAPE.length)


def test_a_missing_boundary_segment_is_split_at_its_middle():
    """The conforming triangulation's step: every flagged edge of a ring gets its midpoint
    inserted between its two ends, in order; the others stay whole."""
    ring = np.array([(0, 0), (4, 0), (4, 2), (0, 2)], float)
    split = tessellations._with_midpoints(ring, np.array([True, False, True, True]))
    assert split.tolist() == [[0, 0], [2, 0], [4, 0], [4, 2], [2, 2], [0, 2], [0, 1]]
    assert tessellations._with_midpoints(ring, np.zeros(4, bool)).tolist() == ring.tolist()


def test_a_short_inner_edge_near_the_outline_collapses_to_its_middle():
    """Four cells of a 4 mm square meet along the inner edge (1.95, 0.2)-(2.05, 0.2), 0.1 mm
    long and 0.2 mm from the outline: with short edges of 0.3 mm its two ends meet at their
    mean (2, 0.2) in every cell, however near the outline they lie; the outline's corners
    stay where they are."""
    region = shapely.box(0, 0, 4, 4)
    p, q = (1.95, 0.2), (2.05, 0.2)
    cells = [np.array(c, float) for c in ([(1, 0), (3, 0), q, p], [(0, 0), (1, 0), p, (0, 4)],
                                          [(3, 0), (4, 0), (4, 4), q], [p, q, (4, 4), (0, 4)])]
    merged = outline_mesh._short_inner_edges_merged(cells, region, 0.3)
    inner = shapely.distance(region.boundary, shapely.points(np.concatenate(cells))) > 0
    moved = np.concatenate(merged)
    assert moved[inner] == pytest.approx(np.tile([2, 0.2], (inner.sum(), 1)))
    assert moved[~inner].tolist() == np.concatenate(cells)[~inner].tolist()
    assert [len(c) for c in merged] == [4, 4, 4, 4]


def test_a_gentle_bend_is_dropped_and_a_reflex_corner_cut_in_one_cell():
    """The L with its bottom side bent in 0.1 mm at (25, 0.1) (a reflex turn of 0.46 degrees,
    shallower than the 0.2 mm tolerance) drawn before its reflex corner (20, 20): the bend is
    dropped, the pieces are convex, cover the L without the bend, and the corner is cut (a
    vertex of two pieces)."""
    corners = np.array(L_SHAPE.exterior.coords)[:-1]
    bent = shapely.Polygon(np.insert(corners, 1, (25, 0.1), axis=0))
    pieces = convex_pieces(bent, 0.2)
    rings = [np.array(shapely.orient_polygons(p).exterior.coords)[:-1] for p in pieces]
    assert not any(np.hypot(*(r - (25, 0.1)).T).min() < 1e-9 for r in rings)
    assert sum(np.hypot(*(r - (20, 20)).T).min() < 1e-9 for r in rings) == 2
    for r in rings:
        before, after = r - np.roll(r, 1, axis=0), np.roll(r, -1, axis=0) - r
        assert (before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0]).min() > -1e-9
    assert shapely.union_all(pieces).symmetric_difference(L_SHAPE).area < 1e-9


@pytest.mark.parametrize("scale, shift", [(1.0, 0.0), (1e-3, 0.0), (1e5, 0.0), (1.0, (1e5, -1e5))])
def test_triangles_along_a_long_straight_side_all_have_area(scale, shift):
    """The triangle (23, 9) (-29, 27) (-30, 14) meshed in triangles of cell 4: its sides, cut
    into equal parts, are runs of points collinear but for rounding, where Qhull's Delaunay
    triangulation also returns flat triangles whose centre may round to inside. No face may
    be flat (validate refuses zero area), and the faces cover the triangle exactly, at any
    scale (cell and tolerance scaled with the outline) and far from the origin."""
    region = shapely.Polygon(np.array([(23, 9), (-29, 27), (-30, 14)]) * scale + shift)
    mesh = validate(outline_mesh.mesh_outline(region, "tri", 4.0 * scale, 0.2 * scale))
    assert signed_areas(mesh).min() > 0.1 * scale ** 2
    union = shapely.union_all(faces_of(mesh))
    assert union.symmetric_difference(region).area < 1e-9 * region.area


@pytest.mark.parametrize("kind", ["quad", "hex"])
def test_a_rectangle_of_two_cells_is_two_faces(kind):
    """A 20 x 10 mm rectangle at cell 10 holds two lattice seeds: its Voronoi cells are the
    two 10 mm squares (the smallest outline that is cut at all)."""
    mesh = outline_mesh.mesh_outline(shapely.box(0, 0, 20, 10), kind, 10.0)
    assert signed_areas(mesh).tolist() == [100.0, 100.0]


@pytest.mark.parametrize("side, pieces", [(3.0, 2), (2.9, 1)])
def test_pieces_under_the_minimum_size_merge_and_at_it_stay(side, pieces):
    """At cell 5 the smallest piece kept is a square of 0.6 * 5 = 3 mm: a 3 mm square beside
    a larger piece stays, a 2.9 mm one merges with it (their union is convex)."""
    small, large = shapely.box(0, 0, side, 3), shapely.box(side, 0, 10, 3)
    merged = merged_small([small, large], 5.0)
    assert len(merged) == pieces
    assert shapely.union_all(merged).equals(shapely.box(0, 0, 10, 3))


def test_a_small_piece_is_cut_anew_with_one_neighbour_never_joined_with_two():
    """A 2 mm square in the corner of a 10 mm square whose rest is cut along the diagonal
    from its inner corner: its union with either neighbour has a reflex corner, so it is cut
    anew with one of them (the smallest of the two new pieces, 20 mm², is over 1.2 x 4 mm²).
    Its union with both is the whole square, convex, one piece: a recut that left one piece
    would make a face of two neighbours and more, so the three pieces stay three."""
    small = shapely.box(0, 0, 2, 2)
    right = shapely.Polygon([(2, 0), (10, 0), (10, 10), (2, 2)])
    top = shapely.Polygon([(0, 2), (2, 2), (10, 10), (0, 10)])
    merged = merged_small([small, right, top], 5.0)
    assert len(merged) == 3
    areas = shapely.area(merged)
    assert areas.min() > 1.2 * small.area and areas.max() <= top.area + small.area + 1e-9
    assert shapely.union_all(merged).symmetric_difference(shapely.box(0, 0, 10, 10)).area < 1e-9
    assert (shapely.area(shapely.convex_hull(merged)) - areas < 1e-9).all()


def test_snapping_onto_the_outline_never_shrinks_a_cell_under_the_smallest():
    """A 20 x 10 rectangle cut at x = 3, the cut's top end (3, 10) an outline vertex: its
    bottom end (3, 0) lies 3 mm from the outline vertex (0, 0) beside it, within the reach of
    5 mm, and snapping it there halves the left cell (30 to 15 mm²). Allowed down to 10 mm²,
    the move is made; with the smallest face at 25 mm² (half of a 10 mm cell) it is not."""
    region = shapely.Polygon([(0, 0), (20, 0), (20, 10), (3, 10), (0, 10)])
    cells = [np.array(c, float) for c in ([(0, 0), (3, 0), (3, 10), (0, 10)],
                                          [(3, 0), (20, 0), (20, 10), (3, 10)])]
    snapped = outline_mesh._snapped(cells, region, 5.0, 10.0)
    assert [c.tolist() for c in snapped] == [[[0, 0], [0, 0], [3, 10], [0, 10]],
                                            [[0, 0], [20, 0], [20, 10], [3, 10]]]
    kept = outline_mesh._snapped(cells, region, 5.0, 25.0)
    assert [c.tolist() for c in kept] == [c.tolist() for c in cells]


def test_a_short_edge_is_not_collapsed_where_it_would_shrink_a_cell_under_the_smallest():
    """The 0.2 mm inner edge (4, 5)-(4.2, 5) collapses to the mean of its five corners (three
    cells meet at (4, 5), two at (4.2, 5)): (4.08, 5), which cuts the triangle (4, 0)
    (4.08, 5) (4, 5), 0.2 mm², off each 30 mm² right cell: made when the smallest face is
    29.7 mm², not when it is 29.9 mm² (then every corner stays where it was)."""
    region = shapely.box(0, 0, 10, 10)
    p, q = (4, 5), (4.2, 5)
    cells = [np.array(c, float) for c in ([(0, 0), (4, 0), p, (4, 10), (0, 10)],
                                          [(4, 0), (10, 0), (10, 5), q, p],
                                          [p, q, (10, 5), (10, 10), (4, 10)])]
    lower = [shapely.Polygon(c).area
             for c in outline_mesh._short_inner_edges_merged(cells, region, 0.3, 29.7)]
    assert lower == pytest.approx([40.4, 29.8, 29.8])
    kept = outline_mesh._short_inner_edges_merged(cells, region, 0.3, 29.9)
    assert [c.tolist() for c in kept] == [c.tolist() for c in cells]


def test_a_spike_or_crack_of_no_width_is_dropped_from_a_ring():
    """A 10 mm square whose bottom side runs out to (15, 0) and back (a spike, as a union of
    pieces at a T-junction collinear only to within rounding leaves) and whose top side runs
    in to (5, 6) and back a hair to the right (a crack): both tips go, and so do the crack's
    ends (the top side steps back by 1e-13 mm between them); the corners stay in order."""
    ring = np.array([(0, 0), (10, 0), (15, 1e-13), (10, 1e-13), (10, 10), (5, 10),
                     (5, 6), (5 + 1e-13, 10), (0, 10)])
    assert pieces._without_spikes(ring).tolist() == [
        [0, 0], [10, 0], [10, 1e-13], [10, 10], [0, 10]]
    square = np.array([(0, 0), (10, 0), (10, 10), (0, 10)], float)
    assert pieces._without_spikes(square).tolist() == square.tolist()


GEAR_ANGLES = np.linspace(0, 2 * np.pi, 80, endpoint=False)
GEAR = shapely.Polygon(np.where(np.arange(80) % 2, 100.0, 80.0)[:, None]
                       * np.column_stack([np.cos(GEAR_ANGLES), np.sin(GEAR_ANGLES)]))


@pytest.mark.parametrize("kind, smallest", [("voronoi", 0.0), ("quad", 0.5)])
def test_a_gear_with_teeth_about_a_cell_wide(kind, smallest):
    """A gear of 40 teeth (radii 80 and 100 mm) in 12 mm cells. In Voronoi cells some small
    pieces' unions with their neighbours have a reflex corner that no cut leaves convex: such a
    group is passed over (the mesher once stopped there with "could not cut a cell"). In
    squares a piece nothing helped is helped once a neighbour has changed: every face ends
    over half a cell (0.60; skipping the piece for good left one of 0.35). Either mesh is
    valid, convex and covers the gear."""
    mesh = validate(outline_mesh.mesh_outline(GEAR, kind, 12.0))
    union = shapely.union_all(faces_of(mesh))
    assert shapely.symmetric_difference(union, GEAR).area <= 0.2 * GEAR.boundary.length
    p = mesh.vertices[mesh.face_indices]
    edges = np.hypot(*(p[mesh.next_half_edge] - p).T)
    assert (corner_turns(mesh) / (edges * edges[mesh.prev_half_edge])).min() > -1e-9
    assert np.sqrt(signed_areas(mesh)).min() / 12.0 >= smallest
