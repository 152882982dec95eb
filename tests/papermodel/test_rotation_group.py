"""The rotation group of a weave checked by turning it: every tile centre lands on its image,
the strands on top and below follow, the powers are the generator applied again and again,
and the orbits are what walking the permutation finds (loops, apart from the vectorised
code)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from tests.meshes import hexagon
from weavecut import inputs
from weavecut.mesh import Mesh
from weavecut.papermodel.symmetry import rotate, rotation_group, strand_orbits, tile_centres
from weavecut.subdivision import subdivide
from weavecut.weave.snub_weave import snub_weaves


@lru_cache(maxsize=None)
def weave(spec: str, levels: int):
    """The snub weave of an input or of the six-triangle hexagon (the weave package is not
    mutated with this one, so its result may be shared)."""
    return snub_weaves(subdivide(hexagon() if spec == "hexagon" else inputs.get(spec),
                                 levels))[-1]


CASES = {("square-grid:2x2", 2): 4, ("pentagon", 2): 5, ("hexagon", 2): 6,
         ("square-grid:3x2", 2): 2, ("pentagon-flower", 3): 5}


def test_rotate_turns_counter_clockwise_about_the_centre():
    pts = np.array([[2.0, 1.0], [1.0, 1.0], [1.0, 3.0]])
    np.testing.assert_allclose(rotate(pts, np.pi / 2, (1.0, 1.0)),
                               [[1.0, 2.0], [1.0, 1.0], [-1.0, 1.0]], atol=1e-12)
    np.testing.assert_allclose(rotate(pts, np.pi, np.array([0.0, 0.0])), -pts, atol=1e-12)


def test_tile_centres_are_the_mean_of_their_faces_corners():
    w = weave("square-grid:2x2", 2)
    centres = tile_centres(w)
    faces = w.mesh.dense_faces()
    for t in range(w.n_tiles):
        corners = [w.mesh.vertices[v] for f in w.tile_faces[w.tile_offsets[t]:w.tile_offsets[t + 1]]
                   for v in faces[f] if v >= 0]
        np.testing.assert_allclose(centres[t], np.mean(corners, axis=0), atol=1e-12)


@pytest.mark.parametrize("case", CASES)
def test_the_generator_maps_the_weave_onto_itself(case):
    w = weave(*case)
    sym = rotation_group(w)
    assert sym.order == CASES[case] and sym.angle == pytest.approx(2 * np.pi / sym.order)
    np.testing.assert_allclose(sym.centre, w.mesh.vertices.mean(axis=0), atol=1e-12)
    centres = tile_centres(w)
    turned = rotate(centres, sym.angle, sym.centre)
    np.testing.assert_allclose(turned, centres[sym.tile_perm], atol=1e-6)
    assert sorted(sym.tile_perm.tolist()) == list(range(w.n_tiles))
    assert sorted(sym.strand_perm.tolist()) == list(range(w.n_strands))
    for t in range(w.n_tiles):  # the strands on top and below go where the tile goes
        for top in (w.tile_over, w.tile_under):
            s = int(top[t])
            if s >= 0:
                assert top[sym.tile_perm[t]] == sym.strand_perm[s]
    # a strand's image walks its image tiles, one for one
    for s in range(w.n_strands):
        visits, _ = w.strand(s)
        image, _ = w.strand(int(sym.strand_perm[s]))
        assert sorted(sym.tile_perm[visits].tolist()) == sorted(image.tolist())


@pytest.mark.parametrize("case", CASES)
def test_powers_repeat_the_generator_and_orbits_walk_it(case):
    w = weave(*case)
    sym = rotation_group(w)
    k = sym.order
    strands, tiles = sym.strand_powers(), sym.tile_powers()
    assert strands.shape == (k, w.n_strands) and tiles.shape == (k, w.n_tiles)
    s_now, t_now = np.arange(w.n_strands), np.arange(w.n_tiles)
    for j in range(k):
        assert strands[j].tolist() == s_now.tolist() and tiles[j].tolist() == t_now.tolist()
        s_now, t_now = sym.strand_perm[s_now], sym.tile_perm[t_now]
    assert s_now.tolist() == list(range(w.n_strands))  # k turns are the identity
    orbit, size = strand_orbits(sym)
    for s in range(w.n_strands):
        seen, x = {s}, int(sym.strand_perm[s])
        while x != s:
            seen.add(x)
            x = int(sym.strand_perm[x])
        assert orbit[s] == min(seen) and size[s] == len(seen)


def test_a_weave_turned_off_its_grid_keeps_no_rotation():
    """The centre vertex moved: no turn maps the vertices onto themselves."""
    mesh = inputs.get("square-grid:2x2")
    v = mesh.vertices.copy()
    v[np.argmin(np.hypot(*(v - v.mean(axis=0)).T))] += (0.12, 0.05)
    w = snub_weaves(subdivide(Mesh(v, mesh.face_offsets, mesh.face_indices), 2))[-1]
    sym = rotation_group(w)
    assert sym.order == 1 and sym.strand_powers().shape == (1, w.n_strands)
    assert sym.tile_perm.tolist() == list(range(w.n_tiles))
    assert strand_orbits(sym)[1].tolist() == [1] * w.n_strands
