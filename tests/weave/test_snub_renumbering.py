"""The snub weave does not depend on the order of the mesh's faces: renumbering the pentagons
(each keeping its own corner order, so middle edge and tip stay put) gives the same tiles, the
same strands and the same crossings. Tiles are numbered by middle edge and strands by their
smallest tile, both independent of face order; only a strand's walking direction and a loop's
first visit may follow the pentagon numbers, so walks are compared up to those.

Rolling the faces so that every pentagon in turn is face 0 checks every code path that treats
index 0 apart from the rest (partner, sibling and tip look-ups whose "none" is -1)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from tests.strategies import examples, valid_meshes
from weavecut import inputs
from weavecut.errors import MeshError
from weavecut.mesh import Mesh
from weavecut.subdivision import subdivide
from weavecut.weave.snub_weave import snub_weave


def _canonical(weave, face_ids):
    """Tiles as sets of original face ids, strands as walks up to direction (and a loop's
    start), and who is over and under at every tile."""
    tiles = [frozenset(face_ids[weave.tile_faces[a:b]].tolist())
             for a, b in zip(weave.tile_offsets[:-1], weave.tile_offsets[1:])]
    walks = []
    for s in range(weave.n_strands):
        visits, over = weave.strand(s)
        seq = list(zip(visits.tolist(), over.tolist()))
        starts = range(len(seq)) if weave.strand_closed[s] else [0]
        turns = [seq[i:] + seq[:i] for i in starts]
        walks.append(min(turns + [t[::-1] for t in turns]))
    return (tiles, walks, weave.tile_over.tolist(), weave.tile_under.tolist(),
            weave.strand_closed.tolist())


def _check_every_face_first(mesh):
    want = _canonical(snub_weave(mesh), np.arange(mesh.n_faces))
    faces = mesh.dense_faces()
    for first in range(mesh.n_faces):
        order = np.roll(np.arange(mesh.n_faces), -first)
        renumbered = snub_weave(Mesh.from_faces(mesh.vertices, faces[order]))
        assert _canonical(renumbered, order) == want, f"face {first} first"


@pytest.mark.parametrize("name", ["square-grid:3x3", "pentagon", "pentagon-flower",
                                  "hex-grid:2x2", "triangulated-ngon:7"])
def test_snub_weave_is_the_same_whichever_pentagon_is_first(name):
    for level in subdivide(inputs.get(name), 2)[1:]:
        _check_every_face_first(level.mesh)


@settings(max_examples=examples(15), deadline=None)
@given(valid_meshes)
def test_snub_weave_of_a_random_mesh_is_the_same_whichever_pentagon_is_first(mesh):
    _check_every_face_first(subdivide(mesh, 1)[1].mesh)


def test_every_octagon_lists_its_pentagons_in_increasing_order():
    for level in subdivide(inputs.get("hex-grid:4x4"), 2)[1:]:
        weave = snub_weave(level.mesh)
        pair = weave.tile_offsets[:-1][np.diff(weave.tile_offsets) == 2]
        assert len(pair) and (weave.tile_faces[pair] < weave.tile_faces[pair + 1]).all()
        assert np.array_equal(np.sort(weave.tile_faces), np.arange(level.mesh.n_faces))


def test_a_turned_pentagon_is_named_in_the_refusal():
    """Turning the last pentagon's corners by one moves its tip off every middle edge; the
    refusal names that pentagon, not one whose tip lies on tile 0's middle edge."""
    mesh = subdivide(inputs.get("square-grid:3x3"), 1)[1].mesh
    faces = mesh.dense_faces().copy()
    last = len(faces) - 1
    faces[last] = np.roll(faces[last], 1)
    with pytest.raises(MeshError, match=f"^pentagon {last} has no middle edge at its tip"):
        snub_weave(Mesh.from_faces(mesh.vertices, faces))


def _starts_at_its_lone_end(weave):
    lone = np.diff(weave.tile_offsets) == 1
    for s in np.flatnonzero(~weave.strand_closed):
        tiles, over = weave.strand(s)
        first, last = over[0] & lone[tiles[0]], over[-1] & lone[tiles[-1]]
        assert first or not last, f"strand {s} ends on its own lone tile but starts elsewhere"


@pytest.mark.parametrize("name", ["square-grid:3x3", "pentagon-flower", "hex-grid:2x2"])
def test_an_open_strand_starts_at_its_own_lone_end(name):
    """The walking direction kept is the one with more pentagons: a strand whose own boundary
    (lone) tile is at one end only is walked from there."""
    for level in subdivide(inputs.get(name), 2)[1:]:
        _starts_at_its_lone_end(snub_weave(level.mesh))
