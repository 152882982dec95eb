"""The finished puzzle in 3-D (puzzle-3d.glb), read back by trimesh: the front paints lie on
top of the board (z = thickness) facing up, the back paints under it facing down, each
colour's area what its painting guide paints (the guides' polygons measured by shapely), the
top and the bottom each cover the whole board once (no holes, no overlap), and the cut edges
stand the material's thickness tall, facing out of the wood."""

from __future__ import annotations

import io

import numpy as np
import pytest
import shapely

from weavecut.export.gltf import glb_bytes, linear
from weavecut.puzzle.guides import painted
from weavecut.puzzle.model3d import WOOD, painted_union, puzzle_model

from tests.built_puzzles import pentagon_paint, pentagon_puzzle

trimesh = pytest.importorskip("trimesh")
THICKNESS = 3.0


@pytest.fixture(scope="module")
def parts():
    puzzle, colouring = pentagon_puzzle(2), pentagon_paint(2)
    scene = trimesh.load(io.BytesIO(glb_bytes(puzzle_model(puzzle, colouring, THICKNESS))),
                         file_type="glb")
    out = []
    for g in scene.geometry.values():  # in the file's order, metres y-up -> mm z-up
        z_up = lambda p: np.column_stack([p[:, 0], -p[:, 2], p[:, 1]])  # noqa: E731
        out.append((tuple(g.visual.material.baseColorFactor.tolist()), z_up(g.vertices) * 1000,
                    g.faces, z_up(g.vertex_normals)))
    return puzzle, colouring, out


def areas(v, f):
    """Per triangle: its area and the z of its normal's direction (unit normal z)."""
    c = v[f]
    n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    size = np.linalg.norm(n, axis=1)
    return size / 2, n[:, 2] / np.maximum(size, 1e-300), c[:, :, 2]


def rgba(colour):
    return tuple(round(255 * x) for x in linear(colour))


@pytest.mark.parametrize("side, z, up", [("front", THICKNESS, 1.0), ("back", 0.0, -1.0)])
def test_each_paint_covers_what_its_guide_paints(parts, side, z, up):
    puzzle, colouring, read = parts
    paint = painted(puzzle, colouring, side)
    want = {rgba(c): a for c, a in paint.areas().items()}
    got: dict = {}
    for colour, v, f, _ in read:
        area, nz, zs = areas(v, f)
        flat = np.abs(nz) > 0.5
        on_side = flat & (np.abs(zs - z) < 1e-6).all(axis=1)
        if colour != rgba(WOOD) and on_side.any():
            assert np.allclose(nz[on_side], up)
            got[colour] = got.get(colour, 0.0) + area[on_side].sum()
    assert set(got) == set(want)
    for colour, a in want.items():
        assert got[colour] == pytest.approx(a, rel=1e-6)  # float32 coordinates


def test_top_and_bottom_cover_the_board_once_and_the_edges_face_out(parts):
    puzzle, colouring, read = parts
    board = shapely.Polygon(puzzle.outer.exterior).area
    for z, up in ((THICKNESS, 1.0), (0.0, -1.0)):
        total = 0.0
        for _, v, f, _ in read:
            area, nz, zs = areas(v, f)
            side = (np.abs(nz) > 0.5) & (np.abs(zs - z) < 1e-6).all(axis=1)
            assert np.allclose(nz[side], up)
            total += area[side].sum()
        assert total == pytest.approx(board, rel=1e-6)
    colour, v, f, vn = read[-1]
    assert colour == rgba(WOOD)
    area, nz, zs = areas(v, f)
    walls = np.abs(nz) < 1e-6
    c = v[f[walls]]
    assert np.ptp(c[:, :, 2], axis=1).max() == pytest.approx(THICKNESS, rel=1e-6)
    # a point just outside a wall (along its normal) is out of the piece or frame it bounds
    n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    # the normals the file gives for shading are the walls' own
    assert ((vn[f[walls]] * n[:, None]).sum(axis=2) > 0.999).all()
    probe = c.mean(axis=1)[:, :2] + 0.05 * n[:, :2]
    inside = c.mean(axis=1)[:, :2] - 0.05 * n[:, :2]
    solids = np.concatenate([puzzle.pieces, [puzzle.frame]])
    tree = shapely.STRtree(solids)
    hits_in = tree.query(shapely.points(inside), predicate="within")
    hits_out = tree.query(shapely.points(probe), predicate="within")
    # every wall has material behind it; in front of it, material of another solid or none
    assert len(np.unique(hits_in[0])) == len(c)
    same = set(zip(hits_in[0].tolist(), hits_in[1].tolist())) & set(
        zip(hits_out[0].tolist(), hits_out[1].tolist()))
    assert not same


@pytest.mark.parametrize("side", ["front", "back"])
def test_the_painted_union_is_union_all_s(side):
    # the paints meet edge to edge: GEOS's coverage union makes union_all's union
    paint = painted(pentagon_puzzle(2), pentagon_paint(2), side).polygons
    union = painted_union(paint)
    assert shapely.is_valid(union)
    assert shapely.equals(union, shapely.union_all(paint))


@pytest.mark.parametrize("polygons", [
    [shapely.box(0, 0, 1, 1), shapely.box(0.5, 0, 1.5, 1)],  # overlapping
    [shapely.Polygon([(0, 0), (1, 0), (1, 0.5), (1, 1), (0, 1)]), shapely.box(1, 0, 2, 1)],
    # a corner on one side of a shared edge only
], ids=["overlap", "corner on one side"])
def test_polygons_that_do_not_meet_edge_to_edge_are_united_by_union_all(polygons):
    union = painted_union(np.array(polygons, dtype=object))
    assert shapely.is_valid(union) and union.geom_type == "Polygon"
    assert shapely.equals(union, shapely.union_all(polygons))
