"""Puzzles of drawn stars, one fixed star per rule (the random stars of test_shape_puzzle draw
many; these are cheap enough to run for every mutant of the piece builder): where ring cells of
neighbouring runs overlap the later one stays in the frame and the pieces still tile the hole,
a ring that leaves a gap is refused naming it, and a level that turns over is refused naming
where (and fewer levels where there can be fewer)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from weavecut.errors import MeshError
from weavecut.puzzle.frame_size import extent
from weavecut.puzzle.guides import piece_halves, split_ends
from weavecut.puzzle.pieces import OCTAGON, _one_region, build_puzzle
from weavecut.readers.outline_mesh import mesh_outline
from weavecut.subdivision import subdivide


def _star(points, dent, wobble, seed, levels=2):
    """The star of test_shape_puzzle's random stars, meshed in 30 mm hexagons with runs."""
    rng = np.random.default_rng(seed)
    angle = np.linspace(0, 2 * np.pi, 4 * points, endpoint=False)
    radius = np.where(np.arange(4 * points) % 4 == 2, dent, 1.0)
    radius = 50.0 * radius * (1 + wobble * rng.uniform(-0.5, 0.5, len(angle)))
    region = shapely.Polygon(np.column_stack([radius * np.cos(angle), radius * np.sin(angle)]))
    return subdivide(mesh_outline(region, "hex", 30.0, runs=True), levels)


@pytest.mark.parametrize("star", [(4, 1.0, 0.0, 0), (5, 0.8, 0.0, 0)])
def test_overlapping_ring_cells_stay_apart_and_the_pieces_tile_the_hole(star):
    """These stars' corners make ring cells of neighbouring runs overlap: the kept cells
    overlap neither each other nor a piece, the pieces tile the hole without gaps, and the
    frame is 250 mm wide with an even 10 mm band beyond the ring."""
    puzzle = build_puzzle(_star(*star), 250.0, 10.0, "width")
    pieces = puzzle.pieces
    assert shapely.is_valid(pieces).all()
    union = shapely.union_all(pieces)
    assert union.geom_type == "Polygon" and not union.interiors
    assert union.area == pytest.approx(shapely.area(pieces).sum(), rel=1e-9)
    cells = np.concatenate([puzzle.ring, puzzle.hexagons[puzzle.hexagons != None]])  # noqa: E711
    cells = cells.astype(object)
    a, b = shapely.STRtree(cells).query(cells, predicate="intersects")
    overlap = shapely.area(shapely.intersection(cells[a[a < b]], cells[b[a < b]]))
    assert overlap.max(initial=0.0) < 1e-6
    assert shapely.area(shapely.intersection(puzzle.ring, union)).max(initial=0.0) < 1e-6
    # every ring cell once
    centres = np.round(shapely.get_coordinates(shapely.centroid(cells)), 3)
    assert len(np.unique(centres, axis=0)) == len(cells)
    assert extent(puzzle.outer, "width") == pytest.approx(250.0, abs=0.01)
    ring = shapely.union_all(np.concatenate([pieces, puzzle.ring]))
    assert shapely.distance(puzzle.outer.exterior, ring) == pytest.approx(10.0, abs=0.05)
    assert puzzle.outer.contains(ring) and puzzle.frame.is_valid
    # a cell is dropped only where it would overlap: the mesh's boundary edges all carry one,
    # bar the few the conflicts removed
    level = puzzle.weaves[-1].mesh
    assert len(cells) <= int((level.topology.twin < 0).sum())


@pytest.mark.parametrize("missing, message", [
    ([(2, 1)], "1 gap between them, one 10 mm from the centre"),
    ([(1, 1), (3, 1)], "2 gaps between them, one 14 mm from the centre"),
    ([(2, 0), (2, 1), (2, 2)], "separate parts"),
])
def test_pieces_that_leave_a_gap_are_refused_naming_it(missing, message):
    """A ring that does not close leaves holes among the pieces (the random star that once did
    so now meshes without one since the outline mesher keeps the result without gaps): 10 mm
    squares of a 5 x 3 grid centred on x = 0, y = 10, some left out, name the gaps and where
    the first is."""
    cells = [(i, j) for i in range(5) for j in range(3) if (i, j) not in missing]
    pieces = np.array([shapely.box(10 * i - 25, 10 * j - 5, 10 * i - 15, 10 * j + 5)
                       for i, j in cells], dtype=object)
    with pytest.raises(MeshError, match=rf"^the puzzle's pieces leave {message}: the hexagon "
                                        r"ring does not close around this mesh; mesh the "
                                        r"outline with another --cell$"):
        _one_region(pieces)
    whole = _one_region(np.array([shapely.box(10 * i - 25, 10 * j - 5, 10 * i - 15, 10 * j + 5)
                                  for i in range(5) for j in range(3)], dtype=object))
    assert whole.equals(shapely.box(-25, -5, 25, 25))


def test_pieces_that_overlap_are_refused_naming_where():
    """Two pieces over each other (slim faces at the ring did this to a random star, and GEOS's
    coverage union, used before, hid the gap they left elsewhere)."""
    pieces = np.array([shapely.box(0, 0, 10, 10), shapely.box(5, 0, 15, 10)], dtype=object)
    with pytest.raises(MeshError, match=r"^the puzzle's pieces overlap \(50 square units in all, "
                                        r"the first near \(7\.5, 5\.0\)\): the mesh has faces "
                                        r"too thin for the hexagon ring there; mesh the outline "
                                        r"with another --cell$"):
        _one_region(pieces)
    inside = np.array([shapely.box(0, 0, 10, 10), shapely.box(2, 2, 4, 4)], dtype=object)
    with pytest.raises(MeshError, match=r"^the puzzle's pieces overlap \(4 square units in all, "
                                        r"the first near \(3\.0, 3\.0\)\)"):
        _one_region(inside)  # a piece within another: no "overlaps" pair, still named


def test_a_piece_collapsed_to_a_line_is_refused_naming_where():
    pieces = np.array([shapely.box(0, 0, 10, 10),
                       shapely.Polygon([(10, 0), (10, 0), (10, 0), (12, 0)])], dtype=object)
    with pytest.raises(MeshError, match=r"^1 of the puzzle's pieces collapse to a line or a "
                                        r"point \(the first at \(10\.0, 0\.0\)\): the mesh has "
                                        r"faces too thin there; mesh the outline with another "
                                        r"--cell$"):
        _one_region(pieces)


def test_an_octagon_whose_chord_leaves_it_is_halved_into_its_pentagons():
    """A three-armed star with sharp, wobbly arms has octagons bent so hard that the straight
    line between their two level t-1 corners runs outside the piece: those are halved into
    their two pentagons (face 0, face 1), the others along the chord; either way the halves
    are polygons that tile the piece."""
    puzzle = build_puzzle(_star(3, 0.4, 0.3, 3), 250.0, 10.0, "width")
    weave, mesh = puzzle.weaves[-1], puzzle.weaves[-1].mesh
    faces = shapely.polygons(puzzle.to_mm(mesh.vertices[mesh.dense_faces()]))
    tiles = puzzle.piece_tiles
    f0 = weave.tile_faces[weave.tile_offsets[tiles]]
    f1 = weave.tile_faces[weave.tile_offsets[tiles + 1] - 1]
    u, w = split_ends(puzzle)
    chord = shapely.linestrings(np.stack([u, w], axis=1))
    octagon = puzzle.kinds == OCTAGON
    leaves = octagon & ~shapely.covers(shapely.buffer(puzzle.pieces, 1e-9), chord)
    assert 0 < leaves.sum() < octagon.sum()
    halves = piece_halves(puzzle)
    assert (shapely.get_type_id(halves) == 3).all() and shapely.is_valid(halves).all()
    assert shapely.equals(halves[leaves, 0], faces[f0[leaves]]).all()
    assert shapely.equals(halves[leaves, 1], faces[f1[leaves]]).all()
    np.testing.assert_allclose(shapely.area(halves[octagon]).sum(axis=1),
                               shapely.area(puzzle.pieces[octagon]), rtol=1e-9)
    assert shapely.area(shapely.intersection(halves[octagon, 0], halves[octagon, 1])
                        ).max() < 1e-6
    cut = octagon & ~leaves
    border = shapely.line_merge(shapely.intersection(shapely.boundary(halves[cut, 0]),
                                                     shapely.boundary(halves[cut, 1])))
    assert shapely.length(shapely.symmetric_difference(border, chord[cut])).max() < 1e-6
