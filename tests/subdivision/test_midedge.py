"""Mid-edge: counts, midpoints, kept face degrees, and two steps = one Doo-Sabin step."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings

from weavecut.subdivision import doo_sabin, midedge

from .classic_meshes import any_meshes, fan, mixed


def _canonical(faces, below=None):
    out = set()
    for f in faces:
        if below is not None and max(f) >= below:
            continue
        k = f.index(min(f))
        out.add(tuple(f[k:] + f[:k]))
    return out


@settings(max_examples=30, deadline=None)
@given(mesh=any_meshes())
def test_two_steps_match_doo_sabin_combinatorially(mesh):
    ds = doo_sabin.step(mesh).mesh
    twice = midedge.step(midedge.step(mesh).mesh).mesh
    # vertex h of the second mid-edge step is the midpoint of corner edge h = Doo-Sabin corner h
    assert _canonical(ds.faces()) == _canonical(twice.faces(), below=mesh.n_corners)


def test_faces_keep_their_degree_and_vertices_are_midpoints():
    m = mixed()
    level = midedge.step(m)
    c = level.mesh
    np.testing.assert_array_equal(c.face_sizes[:m.n_faces], m.face_sizes)
    e = m.topology.edges
    np.testing.assert_allclose(c.vertices[:len(e)], m.vertices[e].mean(axis=1))
    assert (c.n_vertices, c.topology.n_edges, c.n_faces) == midedge.exact_counts(
        len(e), m.n_faces, m.n_corners, 1, 4)  # corners 0 and 2 are cut off


def test_inner_vertex_of_valence_k_gives_a_k_gon():
    c = midedge.step(fan(7)).mesh
    assert 7 in c.face_sizes[7:].tolist()
