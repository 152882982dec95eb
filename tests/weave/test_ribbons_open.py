"""Ribbons of open strands (a surface with boundary in space) end at their last visit.

The oracle is each strand's centre line built here from the weave alone: the tile centres
it visits (lifted along the tile normal over, lowered under) and the midpoints between
consecutive visits; the ribbon's quads must join exactly its consecutive points.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from weavecut import inputs
from weavecut.mesh import Mesh
from weavecut.subdivision import subdivide
from weavecut.weave.ribbons import ribbons, tile_normals
from weavecut.weave.snub_weave import snub_weaves


def bowl() -> Mesh:
    """The pentagon lifted onto the paraboloid z = (x² + y²) / 10: a surface with boundary."""
    flat = inputs.get("pentagon")
    v = flat.vertices
    return Mesh(np.column_stack([v, 0.1 * (v ** 2).sum(axis=1)]), flat.face_offsets,
                flat.face_indices)


def test_open_strands_end_at_their_last_visit():
    weave = snub_weaves(subdivide(bowl(), 2))[-1]
    assert weave.mesh.dim == 3 and not weave.strand_closed.any()
    width, lift = 0.05, 0.01
    model = ribbons(weave, width, lift)
    normals = tile_normals(weave)
    centre = (model.vertices[0::2] + model.vertices[1::2]) / 2  # per centre-line point
    half = len(model.triangles) // 2  # each quad: (right a, right b, left b), (right a, ...)
    a, b = model.triangles[:half, 0] // 2, model.triangles[:half, 1] // 2
    strand = model.strand[:half]
    assert np.array_equal(model.strand[half:], strand)
    for s in range(weave.n_strands):
        tiles, over = weave.strand(s)
        lifted = (weave.tile_centres[tiles]
                  + np.where(over, lift, -lift)[:, None] * normals[tiles])
        line = np.empty((2 * len(tiles) - 1, 3))
        line[0::2] = lifted
        line[1::2] = (weave.tile_centres[tiles[:-1]] + weave.tile_centres[tiles[1:]]) / 2
        mine = strand == s
        assert mine.sum() == len(line) - 1  # one quad per step, none past the last visit
        got = np.stack([centre[a[mine]], centre[b[mine]]], axis=1)
        expected = np.stack([line[:-1], line[1:]], axis=1)
        order = np.lexsort(got[:, 0].T[::-1])
        assert got[order] == pytest.approx(expected[np.lexsort(expected[:, 0].T[::-1])],
                                           abs=1e-12)
    # the ribbon is `width` wide everywhere, across its centre line
    across = model.vertices[0::2] - model.vertices[1::2]
    np.testing.assert_allclose(np.linalg.norm(across, axis=1), width, rtol=1e-12)
    tangent = centre[b] - centre[a]
    dots = np.einsum("ij,ij->i", across[a], tangent) / np.linalg.norm(tangent, axis=1)
    assert np.abs(dots).max() < 0.5 * width  # across, not along (turns bend it a little)


def test_a_flat_weave_has_no_ribbons():
    weave = snub_weaves(subdivide(inputs.get("pentagon"), 1))[-1]
    with pytest.raises(ValueError, match="^ribbons need a weave on a surface in space$"):
        ribbons(weave, 0.05, 0.01)


def test_a_loop_has_no_start():
    """A ball's strands are loops: starting every loop at another visit draws the same
    ribbons (the same triangles, as sets of corner points). The ball is dented at random, so
    that no strand runs straight through a tile (where a one-sided direction would agree)."""
    weave = snub_weaves(subdivide(inputs.get("dodecahedron"), 1, project="sphere"))[-1]
    assert weave.strand_closed.all()
    mesh = weave.mesh
    dents = np.random.default_rng(5).uniform(0.9, 1.1, size=(mesh.n_vertices, 1))
    weave = dataclasses.replace(weave, mesh=Mesh(mesh.vertices * dents, mesh.face_offsets,
                                                 mesh.face_indices))
    offsets = weave.strand_offsets
    start = np.repeat(offsets[:-1], np.diff(offsets))
    size = np.repeat(np.diff(offsets), np.diff(offsets))
    turned = start + (np.arange(len(start)) - start + 2) % size  # every loop from its 3rd
    other = dataclasses.replace(weave, strand_visits=weave.strand_visits[turned],
                                visit_over=weave.visit_over[turned])

    def triangles(model):
        corners = np.round(model.vertices[model.triangles], 9)
        return sorted(map(tuple, corners.reshape(len(corners), -1).tolist()))

    assert triangles(ribbons(weave, 0.05, 0.01)) == triangles(ribbons(other, 0.05, 0.01))
