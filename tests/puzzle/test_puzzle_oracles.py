"""The puzzle's geometry against oracles computed apart from ``build_puzzle``: areas from the
level-t mesh faces and regular hexagons, the frame band measured with shapely, the halves
against their faces' centroids. Every test builds its own puzzle (a level-3 pentagon builds in a
quarter of a second): mutmut credits a shared fixture's work to the first test only."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import shapely

from weavecut import inputs
from weavecut.errors import WeaveCutError
from weavecut.puzzle.frame_size import diameter, extent, frame_scale
from weavecut.puzzle.guides import piece_halves, split_ends
from weavecut.puzzle.pieces import OCTAGON, build_puzzle
from weavecut.subdivision import subdivide

HEXAGON_AREA = 3.0 * np.sqrt(3.0) / 2.0  # x side squared


def _build(spec="pentagon", levels=3, size=300.0, frame_width=20.0, measure="diagonal"):
    return build_puzzle(subdivide(inputs.get(spec), levels), size, frame_width, measure)


def _faces_mm(puzzle):
    """The level-t pentagons (mm) and every piece's first and last face."""
    weave = puzzle.weaves[-1]
    mesh = weave.mesh
    polygons = shapely.polygons(puzzle.to_mm(mesh.vertices[mesh.dense_faces()]))
    tiles = puzzle.piece_tiles
    return (polygons, weave.tile_faces[weave.tile_offsets[tiles]],
            weave.tile_faces[weave.tile_offsets[tiles + 1] - 1])


@pytest.mark.parametrize("spec, levels, measure", [("pentagon", 3, "diagonal"),
                                                   ("square-grid:2x2", 2, "width")])
def test_pieces_are_the_faces_and_hexagons_and_tile_the_hole(spec, levels, measure):
    """Every octagon is its tile's two pentagons, every enneagon its pentagon plus a regular
    hexagon on the pentagon's middle edge, outside the mesh; together they cover the hole once:
    the area of their union is the sum of their areas, with no gap inside."""
    puzzle = _build(spec, levels, measure=measure)
    faces, f0, f1 = _faces_mm(puzzle)
    pieces = puzzle.pieces
    assert shapely.is_valid(pieces).all()
    assert (shapely.get_num_interior_rings(pieces) == 0).all()
    octagon = puzzle.kinds == OCTAGON
    assert (f0[octagon] != f1[octagon]).all() and (f0[~octagon] == f1[~octagon]).all()
    np.testing.assert_allclose(shapely.area(pieces[octagon]),
                               shapely.area(faces[f0[octagon]])
                               + shapely.area(faces[f1[octagon]]), rtol=1e-9)
    assert (shapely.get_num_coordinates(pieces[octagon]) - 1 == 8).all()
    assert (shapely.get_num_coordinates(pieces[~octagon]) - 1 == 9).all()
    # an enneagon less its pentagon is its hexagon: regular, on the pentagon's middle edge
    hexes = puzzle.hexagons[~octagon].astype(object)
    rest = shapely.difference(pieces[~octagon], faces[f0[~octagon]])
    assert shapely.area(shapely.symmetric_difference(rest, hexes)).max() < 1e-6
    xy = shapely.get_coordinates(hexes).reshape(len(hexes), 7, 2)[:, :6]
    side = np.hypot(*(np.roll(xy, -1, axis=1) - xy).transpose(2, 0, 1))
    np.testing.assert_allclose(side, np.repeat(side[:, :1], 6, axis=1), rtol=1e-6)
    np.testing.assert_allclose(shapely.area(hexes), HEXAGON_AREA * side[:, 0] ** 2, rtol=1e-6)
    shared = shapely.length(shapely.intersection(shapely.boundary(hexes), shapely.buffer(
        shapely.boundary(faces[f0[~octagon]]), 1e-6)))
    np.testing.assert_allclose(shared, side[:, 0], rtol=1e-5)
    mesh_area = shapely.area(faces).sum()
    assert shapely.area(shapely.intersection(hexes, shapely.union_all(faces))).max() < 1e-6
    # one cover: union area = sum of areas = mesh + hexagons, and no hole inside
    union = shapely.union_all(pieces)
    assert union.geom_type == "Polygon" and not union.interiors
    total = shapely.area(pieces).sum()
    assert total == pytest.approx(mesh_area + shapely.area(hexes).sum(), rel=1e-9)
    assert union.area == pytest.approx(total, rel=1e-9)
    assert sorted(puzzle.piece_tiles.tolist()) == list(range(puzzle.weaves[-1].n_tiles))
    # the frame is the outer outline less exactly that union, and a valid board
    frame = puzzle.frame
    assert frame.is_valid and len(frame.interiors) == 1
    assert shapely.symmetric_difference(shapely.union(frame, union), puzzle.outer).area < 1e-6
    assert shapely.intersection(frame, union).area < 1e-6
    assert puzzle.hole.area == pytest.approx(total, rel=1e-9)


def test_ring_hexagons_are_regular_outside_the_mesh_and_apart():
    """The unclaimed ring cells: regular, each sharing a whole side with the pieces' outline,
    overlapping neither a piece nor each other, and none the same cell as an enneagon's."""
    puzzle = _build()
    ring = puzzle.ring
    assert len(ring) == 25  # pentagon, level 3: 5 sides x 5 unclaimed cells
    xy = shapely.get_coordinates(ring).reshape(len(ring), 7, 2)[:, :6]
    side = np.hypot(*(np.roll(xy, -1, axis=1) - xy).transpose(2, 0, 1))
    np.testing.assert_allclose(side, np.repeat(side[:, :1], 6, axis=1), rtol=1e-6)
    np.testing.assert_allclose(shapely.area(ring), HEXAGON_AREA * side[:, 0] ** 2, rtol=1e-6)
    hole = shapely.union_all(puzzle.pieces)
    assert shapely.area(shapely.intersection(ring, hole)).max() < 1e-6
    touching = shapely.length(shapely.intersection(shapely.boundary(ring),
                                                   shapely.buffer(hole.boundary, 1e-6)))
    assert (touching >= side[:, 0] * (1 - 1e-6)).all()
    a, b = shapely.STRtree(ring).query(ring, predicate="intersects")
    overlap = shapely.area(shapely.intersection(ring[a[a < b]], ring[b[a < b]]))
    assert overlap.max(initial=0.0) < 1e-6


@pytest.mark.parametrize("frame_width", [10.0, 20.0, 35.0])
def test_the_pentagon_frame_is_frame_width_beyond_the_rings_outermost_point(frame_width):
    """The frame's outer outline keeps exactly ``frame_width`` mm to the nearest ring point
    (pieces and ring cells), its diagonal is the size, and its sides are parallel to the input
    pentagon's (an offset of the outline)."""
    puzzle = _build(frame_width=frame_width)
    ring = shapely.union_all(np.concatenate([puzzle.pieces, puzzle.ring]))
    assert shapely.distance(puzzle.outer.exterior, ring) == pytest.approx(frame_width, abs=1e-6)
    assert puzzle.outer.contains(ring)
    assert diameter(puzzle.outer) == pytest.approx(300.0, abs=0.01)
    corners = np.asarray(puzzle.outer.exterior.coords)[:-1]
    v0 = puzzle.to_mm(puzzle.hierarchy[0].mesh.vertices)
    assert len(corners) == 5
    # corners on the rays from the centre through the input's corners (a concentric offset)
    bearing = np.sort(np.arctan2(corners[:, 1], corners[:, 0]))
    expected = np.sort(np.arctan2(v0[:, 1], v0[:, 0]))
    np.testing.assert_allclose(bearing, expected, atol=1e-9)
    assert puzzle.frame_width == frame_width and puzzle.measure == "diagonal"


def test_a_wider_frame_scales_the_pieces_down_to_keep_the_size():
    narrow, wide = _build(frame_width=10.0), _build(frame_width=40.0)
    assert diameter(narrow.outer) == pytest.approx(diameter(wide.outer), abs=0.01)
    assert wide.scale < narrow.scale
    assert narrow.hole.area / wide.hole.area == pytest.approx(
        (narrow.scale / wide.scale) ** 2, rel=1e-9)


def test_a_square_frame_by_width_is_an_even_band_and_size_wide():
    puzzle = _build("square-grid:2x2", 2, size=250.0, frame_width=12.0, measure="width")
    assert extent(puzzle.outer, "width") == pytest.approx(250.0, abs=0.01)
    x0, _, x1, _ = puzzle.outer.bounds
    assert x1 - x0 == pytest.approx(250.0, abs=0.01)
    ring = shapely.union_all(np.concatenate([puzzle.pieces, puzzle.ring]))
    assert shapely.distance(puzzle.outer.exterior, ring) == pytest.approx(12.0, abs=0.05)
    assert puzzle.outer.contains(ring) and puzzle.frame.is_valid


def test_scale_and_centre_map_the_input_onto_the_mm_drawing():
    """The input's vertex mean sits at the origin; a mesh vertex at the model distance d from
    it lies d x scale mm from the origin."""
    puzzle = _build()
    v = puzzle.hierarchy[0].mesh.vertices
    np.testing.assert_allclose(puzzle.centre, v.mean(axis=0), atol=1e-12)
    mm = puzzle.to_mm(v)
    np.testing.assert_allclose(mm.mean(axis=0), 0.0, atol=1e-9)
    np.testing.assert_allclose(np.hypot(*mm.T),
                               np.hypot(*(v - v.mean(axis=0)).T) * puzzle.scale, rtol=1e-12)
    # the pieces are drawn in mm: the level-t mesh at that scale
    level = puzzle.weaves[-1].mesh
    assert shapely.area(shapely.polygons(puzzle.to_mm(level.vertices[level.dense_faces()]))
                        ).sum() < shapely.area(puzzle.pieces).sum()
    assert puzzle.levels == 3 and puzzle.n_pieces == 85
    assert puzzle.counts() == {"octagon": 40, "enneagon": 45, "ring hexagons in the frame": 25}


def test_each_half_holds_the_centroid_of_its_face():
    """Half k of a piece contains the centroid of the piece's face k (an octagon's halves are
    not swapped), the two halves tile the piece, and their shared border runs between the two
    level t-1 corners ``split_ends`` names."""
    puzzle = _build()
    faces, f0, f1 = _faces_mm(puzzle)
    halves = piece_halves(puzzle)
    assert shapely.contains(halves[:, 0], shapely.centroid(faces[f0])).all()
    assert shapely.contains(halves[:, 1], shapely.centroid(faces[f1])).all()
    octagon = puzzle.kinds == OCTAGON
    assert not shapely.contains(halves[octagon, 0], shapely.centroid(faces[f1[octagon]])).any()
    np.testing.assert_allclose(shapely.area(halves[octagon]).sum(axis=1),
                               shapely.area(puzzle.pieces[octagon]), rtol=1e-9)
    assert shapely.area(shapely.intersection(halves[octagon, 0], halves[octagon, 1])).max() < 1e-6
    # an enneagon's halves are its pentagon, twice
    assert shapely.equals(halves[~octagon, 0], faces[f0[~octagon]]).all()
    assert shapely.equals(halves[~octagon, 1], faces[f0[~octagon]]).all()
    u, w = split_ends(puzzle)
    border = shapely.intersection(shapely.boundary(halves[octagon, 0]),
                                  shapely.boundary(halves[octagon, 1]))
    chord = shapely.linestrings(np.stack([u[octagon], w[octagon]], axis=1))
    assert shapely.length(shapely.symmetric_difference(shapely.line_merge(border), chord)
                          ).max() < 1e-6
    # the chord's ends are corners of the piece that are level t-1 vertices
    n_parent = puzzle.hierarchy[-2].mesh.n_vertices
    parent = puzzle.to_mm(puzzle.weaves[-1].mesh.vertices[:n_parent])
    for ends in (u, w):
        d = np.min(np.hypot(*(ends[:, None] - parent[None]).transpose(2, 0, 1)), axis=1)
        assert d.max() < 1e-9
        assert (shapely.distance(shapely.points(ends), shapely.boundary(puzzle.pieces))
                < 1e-9).all()


def test_build_puzzle_refuses_what_it_cannot_make():
    hierarchy = subdivide(inputs.get("pentagon"), 2)
    with pytest.raises(WeaveCutError, match=r"^a puzzle needs --levels >= 2 \(front shows "
                                            r"level t-1\), got 1$"):
        build_puzzle(hierarchy[:2])
    for size, width in ((0.0, 20.0), (300.0, 0.0), (-1.0, 20.0), (300.0, -5.0)):
        with pytest.raises(WeaveCutError, match="^size and frame width must be positive$"):
            build_puzzle(hierarchy, size, width)
    with pytest.raises(WeaveCutError, match=r"^unknown size measure 'area'; choose one of "
                                            r"diagonal, width$"):
        build_puzzle(hierarchy, 300.0, 20.0, "area")
    with pytest.raises(WeaveCutError, match=r"^a frame of 30 mm diagonal leaves no room for "
                                            r"the pieces inside a 20 mm frame; use a larger "
                                            r"--size or a narrower --frame$"):
        build_puzzle(hierarchy, 30.0, 20.0)


def test_frame_scale_solves_the_size_to_a_hundredth():
    """``frame_scale`` finds the scale whose grown outline measures ``size``, for an outline
    that grows by a fixed band (a square of side s offset by 5 mm: diagonal (s + 10) sqrt 2,
    with square corners, so the scale is known in closed form)."""
    base = shapely.box(-1.0, -1.0, 1.0, 1.0)

    def grow(scale):
        return shapely.buffer(shapely.transform(base, lambda xy: xy * scale), 5.0,
                              join_style="mitre")

    scale = frame_scale(base, grow, 100.0, "diagonal", 5.0)
    assert scale == pytest.approx((100.0 / np.sqrt(2) - 10.0) / 2.0, rel=1e-9)
    assert frame_scale(base, grow, 100.0, "width", 5.0) == pytest.approx(45.0, rel=1e-9)
    with pytest.raises(WeaveCutError, match="^a frame of 9 mm width leaves no room for the pieces inside a 5 mm frame"):
        frame_scale(base, grow, 9.0, "width", 5.0)


def test_extent_and_diameter_measure_corners():
    triangle = shapely.Polygon([(0, 0), (4, 0), (1, 3)])
    assert diameter(triangle) == pytest.approx(np.hypot(3, 3))
    assert extent(triangle) == extent(triangle, "diagonal") == diameter(triangle)
    assert extent(triangle, "width") == 4.0


def test_pieces_do_not_depend_on_the_drawings_units():
    """The pentagon drawn a thousand times smaller (metres for millimetres) makes the same
    pieces at the same size: corners snap at a tolerance relative to the drawing."""
    mesh = inputs.get("pentagon")
    small = dataclasses.replace(mesh, vertices=mesh.vertices * 1e-3)
    a = build_puzzle(subdivide(mesh, 2), size=300.0)
    b = build_puzzle(subdivide(small, 2), size=300.0)
    assert a.n_pieces == b.n_pieces
    assert (shapely.get_num_coordinates(a.pieces) == shapely.get_num_coordinates(b.pieces)).all()
    assert shapely.hausdorff_distance(a.pieces, b.pieces).max() < 1e-9
