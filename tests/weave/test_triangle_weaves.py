"""Triangle weaves (Loop, butterfly, sqrt(3)) and the general face-split weave."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from weavecut.mesh import Mesh
from weavecut.subdivision import butterfly, loop, sqrt3
from weavecut.weave.face_split import face_split_mesh, face_split_weave
from weavecut.weave.triangles import sqrt3_weave, triangle_weave
from weavecut.weave.two_colouring import (
    check_triangle_colouring,
    disc_two_colouring,
    triangle_colouring_step,
)

from ..subdivision.classic_meshes import any_meshes, jittered_tri_grids, quad_grid
from .test_quad_weave import assert_crossings


def split_quads(n, m):
    """A two-coloured quad grid cut along its c2-c2 diagonals: one c1 per triangle."""
    q = quad_grid(n, m, jitter=0.1)
    c1 = disc_two_colouring(q)
    f = q.face_indices.reshape(-1, 4)
    shift = np.where(c1[f[:, 0]], 1, 0)               # start the quad at a c2 corner
    f = np.take_along_axis(f, (np.arange(4) + shift[:, None]) % 4, axis=1)
    tris = np.concatenate([f[:, [0, 1, 2]], f[:, [0, 2, 3]]], axis=1).reshape(-1)
    return Mesh(q.vertices, np.arange(0, len(tris) + 1, 3), tris), c1


@pytest.mark.parametrize("scheme", [loop, butterfly])
def test_colour_propagates_through_two_steps(scheme):
    mesh, c1 = split_quads(3, 2)
    w = triangle_weave(mesh, c1)
    assert w.n_tiles == mesh.n_faces // 2
    for _ in range(2):
        c1 = triangle_colouring_step(mesh, c1)
        mesh = scheme.step(mesh).mesh
        check_triangle_colouring(mesh, c1)
        w = triangle_weave(mesh, c1)
        assert_crossings(w)
        np.testing.assert_array_equal(np.diff(w.tile_offsets), 2)


@settings(max_examples=30, deadline=None)
@given(mesh=jittered_tri_grids())
def test_sqrt3_weave_quads_have_two_old_vertices_diagonally(mesh):
    level = sqrt3.step(mesh)
    w = sqrt3_weave(level, mesh.n_vertices)
    assert w.n_tiles == int((~mesh.topology.boundary_edges).sum())
    assert_crossings(w)
    faces = level.mesh.face_indices.reshape(-1, 3)
    pair = w.tile_faces.reshape(-1, 2)
    a, b = faces[pair[:, 0]], faces[pair[:, 1]]
    assert ((a < mesh.n_vertices).sum(axis=1) == 1).all()   # one old vertex per triangle
    assert ((b < mesh.n_vertices).sum(axis=1) == 1).all()
    assert (a.min(axis=1) != b.min(axis=1)).all()           # two different old vertices
    # the two centres are shared: the glued edge is the diagonal between them
    np.testing.assert_array_equal(np.sort(a, axis=1)[:, 1:], np.sort(b, axis=1)[:, 1:])


@settings(max_examples=30, deadline=None)
@given(mesh=any_meshes())
def test_face_split_weave_crosses_on_every_inner_edge(mesh):
    w = face_split_weave(mesh)
    assert w.n_tiles == int((~mesh.topology.boundary_edges).sum())
    if w.n_tiles:
        assert_crossings(w)
        q = face_split_mesh(mesh).face_indices.reshape(-1, 4)
        assert (q[:, [0, 2]] < mesh.n_vertices).all() and (q[:, [1, 3]] >= mesh.n_vertices).all()


def test_face_split_strands_alternate_on_a_quad_grid():
    w = face_split_weave(quad_grid(4, 4))
    for s in range(w.n_strands):
        over = w.strand(s)[1]
        assert (over[1:] != over[:-1]).all()
