"""The snub weave: octagons, strands, crossings and lineage, checked against the paper and
against an independent zig-zag walk on the parent mesh."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given

from benchmarks.zigzag import zigzag_strands  # the loop-based oracle, also a benchmark peer
from tests.strategies import valid_meshes
from weavecut import inputs
from weavecut.errors import MeshError
from weavecut.mesh import outer_vertices
from weavecut.subdivision import subdivide
from weavecut.weave.colour import crossing_pairs, palette, strand_colours, strand_families
from weavecut.weave.snub_weave import snub_weave, snub_weaves

NAMES = ["square-grid:3x3", "pentagon", "pentagon-flower", "tiling-8-4:2x2", "hex-grid:2x2",
         "triangulated-ngon:7"]


def weave_strands(weave):
    out = {}
    for s in range(weave.n_strands):
        tiles, over = weave.strand(s)
        out[frozenset(tiles[over].tolist())] = frozenset(tiles.tolist())
    return out


def check_weave(weave, self_crossings=False):
    mesh = weave.mesh
    sizes = np.diff(weave.tile_offsets)
    assert set(np.unique(sizes).tolist()) <= {1, 2}
    # every octagon is two pentagons sharing a middle edge (local edge 1, run both ways)
    pair = weave.tile_faces[weave.tile_offsets[:-1][sizes == 2, None] + [0, 1]]
    faces = mesh.dense_faces()
    assert (faces[pair[:, 0], 1] == faces[pair[:, 1], 2]).all()
    assert (faces[pair[:, 0], 2] == faces[pair[:, 1], 1]).all()
    # a lone tile's middle edge lies on the boundary
    lone = weave.tile_faces[weave.tile_offsets[:-1][sizes == 1]]
    outer = outer_vertices(mesh)
    assert (outer[faces[lone, 1]] & outer[faces[lone, 2]]).all()
    # every tile is the own tile of exactly one strand, passed under by at most one
    assert (np.bincount(weave.strand_visits[weave.visit_over], minlength=weave.n_tiles) == 1).all()
    assert np.bincount(weave.strand_visits[~weave.visit_over], minlength=weave.n_tiles).max() <= 1
    # every inner octagon is crossed by exactly one strand, other than its own on regular
    # inputs; on irregular meshes a zig-zag walk can pass under its own tile
    assert (weave.tile_under[sizes == 2] >= 0).all()
    if not self_crossings:
        assert (weave.tile_under[sizes == 2] != weave.tile_over[sizes == 2]).all()
    # over and under alternate along every strand (also across the seam of closed ones)
    same_strand = weave.visit_strand[1:] == weave.visit_strand[:-1]
    assert (weave.visit_over[1:] != weave.visit_over[:-1])[same_strand].all()
    # every tile has at most two strand neighbours
    nb = [set() for _ in range(weave.n_tiles)]
    for s in range(weave.n_strands):
        tiles, over = weave.strand(s)
        own = tiles[over].tolist()
        for a, b in zip(own, own[1:]):
            nb[a].add(b)
            nb[b].add(a)
        if weave.strand_closed[s]:
            nb[own[0]].add(own[-1])
            nb[own[-1]].add(own[0])
    assert max(len(n) for n in nb) <= 2


@pytest.mark.parametrize("name", NAMES)
def test_weave_facts_and_zigzag_agree(name):
    hierarchy = subdivide(inputs.get(name), 3)
    for parent, level in zip(hierarchy, hierarchy[1:]):
        weave = snub_weave(level.mesh)
        check_weave(weave)
        assert weave.n_tiles == parent.mesh.topology.n_edges
        assert weave_strands(weave) == zigzag_strands(parent.mesh)


@given(valid_meshes)
def test_weave_facts_on_random_meshes(mesh):
    hierarchy = subdivide(mesh, 2)
    for parent, level in zip(hierarchy, hierarchy[1:]):
        weave = snub_weave(level.mesh)
        check_weave(weave, self_crossings=True)
        assert weave_strands(weave) == zigzag_strands(parent.mesh)


def test_right_chirality_weaves_too():
    hierarchy = subdivide(inputs.get("square-grid:3x3"), 2, chirality="right")
    for level in hierarchy[1:]:
        check_weave(snub_weave(level.mesh))


def test_square_grid_strands_run_along_diagonals():
    level = subdivide(inputs.get("square-grid:6x6"), 1)[1]
    weave = snub_weave(level.mesh)
    v = level.mesh.vertices
    centres = np.array([v[level.mesh.dense_faces()[weave.tile_faces[a:b]]].reshape(-1, 2)
                        .mean(axis=0) for a, b in zip(weave.tile_offsets[:-1],
                                                      weave.tile_offsets[1:])])
    long = 0
    for s in range(weave.n_strands):
        tiles, over = weave.strand(s)
        own = tiles[over]
        if len(own) < 3:
            continue
        long += 1
        steps = np.diff(centres[own], axis=0)
        steps /= np.hypot(*steps.T)[:, None]
        diag = np.abs(steps @ np.array([1, 1]) / np.sqrt(2))
        anti = np.abs(steps @ np.array([1, -1]) / np.sqrt(2))
        assert (diag > 0.97).all() or (anti > 0.97).all()
    assert long >= 10


@pytest.mark.parametrize("name", ["square-grid:4x4", "pentagon", "pentagon-flower"])
def test_lineage_is_total_and_children_follow_their_parent(name):
    weaves = snub_weaves(subdivide(inputs.get(name), 4))
    for weave in weaves[1:]:
        sizes = np.diff(weave.tile_offsets)
        has_octagon = np.bincount(weave.visit_strand[weave.visit_over & (sizes[
            weave.strand_visits] == 2)], minlength=weave.n_strands) > 0
        assert (weave.parent_strand[has_octagon] >= 0).all()
    # most parents with long strands have two long children (the paper's split into two)
    weave, parent = weaves[-1], weaves[-2]
    lengths = np.bincount(weave.visit_strand[weave.visit_over], minlength=weave.n_strands)
    long_children = np.bincount(weave.parent_strand[lengths >= 4], minlength=parent.n_strands)
    parent_len = np.bincount(parent.visit_strand[parent.visit_over], minlength=parent.n_strands)
    assert np.median(long_children[parent_len >= 4]) == 2


@pytest.mark.parametrize("name, levels", [("okabe-ito", 3), ("maritime-4", 1)])
def test_crossing_strands_get_different_colours(name, levels):
    weaves = snub_weaves(subdivide(inputs.get("square-grid:3x3"), levels))
    colours = strand_colours(weaves[-1:], palette(name))
    pairs = crossing_pairs(weaves[-1])
    assert len(pairs) and all(colours[a] != colours[b] for a, b in pairs.tolist())


def test_lineages_keep_one_hue_and_siblings_differ():
    weaves = snub_weaves(subdivide(inputs.get("square-grid:3x3"), 3))
    pal = palette("maritime-12")
    colours = strand_colours(weaves, pal)
    families = strand_families(weaves, pal)
    assert len(colours) == weaves[-1].n_strands
    ps = weaves[-1].parent_strand
    for p in np.unique(ps[ps >= 0]).tolist():
        kids = np.flatnonzero(ps == p)
        assert len(set(families[kids].tolist())) == 1
        assert len({colours[k] for k in kids}) == len(kids)
    # the first split uses the family's own two shades
    two = strand_colours(weaves[:2], pal)
    fam2 = strand_families(weaves[:2], pal)
    assert all(c in pal.families[f] for c, f in zip(two, fam2.tolist()))
    assert strand_colours(weaves, pal) == colours  # deterministic


def test_not_a_snub_level():
    with pytest.raises(MeshError, match="snub"):
        snub_weave(inputs.get("square-grid:2x2"))


def test_weave_arrays_have_the_documented_dtypes():
    """Weave's contract (weave/model.py): tile and strand ids int32, offsets int64."""
    for weave in snub_weaves(subdivide(inputs.get("pentagon"), 3))[1:]:
        assert weave.parent_strand.dtype == np.int32
        assert weave.tile_faces.dtype == weave.strand_visits.dtype == np.int32
        assert weave.tile_offsets.dtype == weave.strand_offsets.dtype == np.int64
