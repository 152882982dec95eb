"""The snub weave on closed surfaces: loops only, two passes per octagon, strict alternation,
lineage, and strand lengths (with a planar oracle for the length)."""

from __future__ import annotations

import numpy as np
import pytest

from weavecut import inputs
from weavecut.subdivision import subdivide
from weavecut.weave.report import weave_summaries
from weavecut.weave.snub_weave import snub_weaves

SOLIDS = ["tetrahedron", "cube", "octahedron", "dodecahedron", "icosahedron", "icosphere:1"]


@pytest.fixture(scope="module", params=SOLIDS)
def weaves(request):
    return snub_weaves(subdivide(inputs.get(request.param), 3, project="sphere"))


def test_every_strand_is_a_loop_and_every_tile_an_octagon(weaves):
    for weave in weaves:
        assert weave.strand_closed.all()
        sizes = np.diff(weave.tile_offsets)
        assert (sizes == 2).all()  # no boundary pentagons
        assert weave.n_tiles == weave.mesh.n_faces // 2  # every pentagon in one octagon


def test_each_octagon_is_passed_once_over_and_once_under(weaves):
    for weave in weaves:
        over = np.bincount(weave.strand_visits[weave.visit_over], minlength=weave.n_tiles)
        under = np.bincount(weave.strand_visits[~weave.visit_over], minlength=weave.n_tiles)
        assert (over == 1).all() and (under == 1).all()


def test_over_and_under_alternate_around_every_loop(weaves):
    for weave in weaves:
        for s in range(weave.n_strands):
            tiles, over = weave.strand(s)
            assert len(over) % 2 == 0
            assert (over != np.roll(over, 1)).all()  # the wrap too: a loop has no seam


def test_consecutive_visits_are_neighbouring_tiles(weaves):
    """Tiles a strand visits one after the other share a mesh edge (it walks, never jumps)."""
    for weave in weaves:
        mesh = weave.mesh
        topo = mesh.topology
        twin = topo.twin
        tile_of_face = weave.face_tile
        he_tile = tile_of_face[mesh.half_edge_face]
        pairs = {(a, b) for a, b in zip(he_tile.tolist(), he_tile[twin].tolist())}
        for s in range(weave.n_strands):
            tiles = weave.strand(s)[0].tolist()
            assert all((a, b) in pairs for a, b in zip(tiles, tiles[1:] + tiles[:1]))


def test_lineage_finds_a_parent_for_every_strand(weaves):
    summaries = weave_summaries(weaves)
    for weave, summary in zip(weaves[1:], summaries[1:]):
        assert (weave.parent_strand >= 0).all()
        assert summary["lineage"]["orphans"] == 0
        assert summary["lineage"]["parents_without_children"] == 0


def test_strand_lengths_are_reported_for_balls(weaves):
    for weave, summary in zip(weaves, weave_summaries(weaves)):
        lengths = summary["strand_lengths"]
        assert len(lengths) == weave.n_strands
        centres = weave.tile_centres
        for s, length in enumerate(lengths):  # the closed polyline, walked point by point
            p = centres[weave.strand(s)[0]]
            want = sum(np.linalg.norm(p[i] - p[i - 1]) for i in range(len(p)))
            assert length == pytest.approx(want, abs=1e-6)


def test_dodecahedron_level_1_has_six_loops_of_five_octagons():
    """One snub step of the dodecahedron: 30 octagons (one per edge), woven by six loops, one
    for each great decagon of the icosidodecahedron the edge midpoints form."""
    weave = snub_weaves(subdivide(inputs.get("dodecahedron"), 1))[0]
    assert weave.n_tiles == 30 and weave.n_strands == 6
    assert (np.diff(weave.strand_offsets) == 10).all()
