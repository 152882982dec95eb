"""Quad weaves: colourings, two strands per tile, alternation, Catmull-Clark's parallel strands."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from weavecut.errors import MeshError
from weavecut.subdivision import catmull_clark
from weavecut.weave.quad import quad_weave
from weavecut.weave.two_colouring import (
    catmull_clark_colouring,
    check_two_colouring,
    disc_two_colouring,
)

from ..subdivision.classic_meshes import any_meshes, jittered_quad_grids, quad_grid, tri_grid


def assert_crossings(w):
    """Every tile is visited exactly twice, by two different strands, one on top."""
    np.testing.assert_array_equal(np.bincount(w.strand_visits, minlength=w.n_tiles), 2)
    assert (w.tile_over >= 0).all() and (w.tile_under >= 0).all()
    assert (w.tile_over != w.tile_under).all()


@settings(max_examples=30, deadline=None)
@given(mesh=jittered_quad_grids())
def test_disc_colouring_and_crossings(mesh):
    c1 = disc_two_colouring(mesh)
    check_two_colouring(mesh, c1)
    assert_crossings(quad_weave(mesh, c1))


def test_over_under_alternates_on_a_grid():
    m = quad_grid(5, 4)
    w = quad_weave(m, disc_two_colouring(m))
    assert w.n_strands == 9
    for s in range(w.n_strands):
        tiles, over = w.strand(s)
        assert len(tiles) in (4, 5)
        assert (over[1:] != over[:-1]).all()


def test_entering_with_c1_on_the_left_is_on_top():
    """Two unit quads side by side, c1 = (0,0), (2,0), (1,1). Walking right, the horizontal
    strand enters quad 0 with (0,1) (c2) on its left: below; quad 1 with (1,1) (c1): on top."""
    m = quad_grid(2, 1)  # vertex (i, j) has id 3 j + i; quad 0 is the left one
    c1 = np.array([True, False, True, False, True, False])
    w = quad_weave(m, c1)
    long = [s for s in range(w.n_strands) if len(w.strand(s)[0]) == 2]
    assert len(long) == 1
    tiles, over = w.strand(long[0])
    by_tile = dict(zip(tiles.tolist(), over.tolist()))
    assert by_tile == {0: False, 1: True}
    # each vertical strand is on top exactly where the horizontal one is below
    for s in range(w.n_strands):
        if s != long[0]:
            t, o = w.strand(s)
            assert len(t) == 1 and o[0] == (not by_tile[int(t[0])])


def test_odd_cycles_are_refused():
    with pytest.raises(MeshError, match="two-colourable"):
        disc_two_colouring(tri_grid(1, 1))


@settings(max_examples=30, deadline=None)
@given(mesh=any_meshes())
def test_catmull_clark_colouring_works_on_any_mesh(mesh):
    level = catmull_clark.step(mesh)
    c1 = catmull_clark_colouring(level)
    check_two_colouring(level.mesh, c1)
    assert_crossings(quad_weave(level.mesh, c1))


@pytest.mark.parametrize("n,m", [(3, 2), (4, 4)])
def test_catmull_clark_splits_every_strand_into_two_parallel_strands(n, m):
    mesh = quad_grid(n, m, jitter=0.1)
    parent = quad_weave(mesh, disc_two_colouring(mesh))
    level = catmull_clark.step(mesh)
    child = quad_weave(level.mesh, catmull_clark_colouring(level))
    assert child.n_strands == 2 * parent.n_strands
    parent_sets = {frozenset(parent.strand(s)[0].tolist()): s for s in range(parent.n_strands)}
    followers = {s: [] for s in range(parent.n_strands)}
    for s in range(child.n_strands):
        tiles = child.strand(s)[0]
        key = frozenset(level.parent_face[tiles].tolist())
        assert key in parent_sets                      # it follows one parent strand
        followers[parent_sets[key]].append(set(tiles.tolist()))
    for pair in followers.values():
        assert len(pair) == 2 and not pair[0] & pair[1]  # two strands side by side
