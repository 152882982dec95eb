"""Lineage and colour order against loop-written oracles on small meshes.

The lineage rule (``weave.snub_weave.lineage``): every pentagon of a child strand's own tiles
votes for the parent strands on top of and below the parent tile its parent face lies in; most
votes win, ties go to the smaller parent strand. Here the votes are recounted with plain loops
over strands and faces, straight from that sentence.
"""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest
from hypothesis import given, settings

from tests.strategies import examples, valid_meshes
from weavecut import inputs
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette, shade, strand_colours
from weavecut.weave.snub_weave import lineage, snub_weave, snub_weaves



def lineage_by_loops(parent, child, parent_face) -> list[int]:
    out = []
    for s in range(child.n_strands):
        tiles, over = child.strand(s)
        votes: Counter[int] = Counter()
        for t in tiles[over].tolist():
            for f in child.tile_faces[child.tile_offsets[t]:child.tile_offsets[t + 1]].tolist():
                ptile = parent.face_tile[parent_face[f]]
                for candidate in (parent.tile_over[ptile], parent.tile_under[ptile]):
                    if candidate >= 0:
                        votes[int(candidate)] += 1
        if not votes:
            out.append(-1)
            continue
        best = max(votes.values())
        out.append(min(p for p, v in votes.items() if v == best))
    return out


@pytest.mark.parametrize("name, levels", [("pentagon", 4), ("square-grid:3x3", 3),
                                          ("tiling-8-4:2x2", 3), ("triangulated-ngon:7", 3)])
def test_lineage_equals_recounted_votes(name, levels):
    hierarchy = subdivide(inputs.get(name), levels)
    weaves = snub_weaves(hierarchy)
    for depth in range(1, len(weaves)):
        expected = lineage_by_loops(weaves[depth - 1], weaves[depth],
                                    hierarchy[depth + 1].parent_face)
        assert weaves[depth].parent_strand.tolist() == expected


def own_lengths(weave) -> np.ndarray:
    return np.bincount(weave.visit_strand[weave.visit_over], minlength=weave.n_strands)


def luminance(colour: str) -> float:
    r, g, b = (int(colour[i:i + 2], 16) for i in (1, 3, 5))
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


@pytest.mark.parametrize("name", ["pentagon", "square-grid:3x3"])
def test_siblings_take_shades_longest_first(name):
    """Children of one strand, longest first (ties: smaller id), take the family's shades in
    order at the first split, then alternately darker and lighter shades of the parent."""
    weaves = snub_weaves(subdivide(inputs.get(name), 4))
    pal = palette("maritime-12")
    for depth in (1, 2):
        parents = strand_colours(weaves[:depth], pal)
        children = strand_colours(weaves[:depth + 1], pal)
        weave = weaves[depth]
        lengths = own_lengths(weave)
        ps = weave.parent_strand.tolist()
        checked = 0
        for p in sorted(set(ps) - {-1}):
            kids = sorted((k for k, q in enumerate(ps) if q == p), key=lambda k: (-lengths[k], k))
            family = next(f for f in pal.families if parents[p] == f[0]) if depth == 1 else None
            for rank, k in enumerate(kids):
                if depth == 1:
                    assert children[k] == family[rank % len(family)]
                else:
                    assert children[k] == shade(parents[p], rank)
                checked += 1
            if depth > 1 and len(kids) >= 2:
                # the longest child is the darker shade, the second the lighter
                assert luminance(children[kids[0]]) < luminance(parents[p]) < luminance(
                    children[kids[1]])
        assert checked >= 5


@settings(max_examples=examples(30), deadline=None)
@given(valid_meshes)
def test_lineage_of_a_random_mesh_equals_recounted_votes(mesh):
    """Irregular patches have many lone boundary tiles (passed under by no strand): their
    empty votes must count for nobody."""
    hierarchy = subdivide(mesh, 3)
    parent, child = snub_weave(hierarchy[2].mesh), snub_weave(hierarchy[3].mesh)
    got = lineage(parent, child, hierarchy[3].parent_face)
    assert got.tolist() == lineage_by_loops(parent, child, hierarchy[3].parent_face)
