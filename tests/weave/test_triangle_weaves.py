"""Triangle weaves (Loop, butterfly, sqrt(3)) and the general face-split weave."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from weavecut import inputs
from weavecut.errors import MeshError
from weavecut.mesh import Mesh
from weavecut.subdivision import butterfly, loop, sqrt3, subdivide
from weavecut.weave.face_split import face_split_mesh, face_split_weave
from weavecut.weave.schemes import scheme_weaves
from weavecut.weave.triangles import sqrt3_weave, triangle_weave
from weavecut.weave.two_colouring import (
    check_triangle_colouring,
    disc_two_colouring,
    triangle_colouring_step,
    triangle_three_colouring,
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


def _three_colouring_oracle(mesh: Mesh) -> np.ndarray:
    """c1 by hand: colour the first face's corners 0, 1, 2 (per connected part, its lowest
    face first), then give every vertex the colour its triangle still lacks, face by face,
    until nothing changes; c1 is colour 0. None if some triangle ends without three colours."""
    faces = mesh.faces()
    colour: dict[int, int] = {}
    for start in range(len(faces)):
        if any(v in colour for v in faces[start]):
            continue
        # only a face of a part not yet reached can start one
        colour.update(zip(faces[start], range(3)))
        changed = True
        while changed:
            changed = False
            for f in faces:
                known = [colour[v] for v in f if v in colour]
                if len(known) == 2:
                    (v,) = [v for v in f if v not in colour]
                    colour[v] = 3 - sum(known)
                    changed = True
    if any(sorted(colour.get(v, -1) for v in f) != [0, 1, 2] for f in faces):
        return None
    return np.array([colour[v] == 0 for v in range(mesh.n_vertices)])


def _two_parts(name: str) -> Mesh:
    one = inputs.get(name)
    far = one.vertices + [100.0, 0.0]
    return Mesh.from_faces(np.vstack([one.vertices, far]),
                           one.faces() + [[v + one.n_vertices for v in f] for f in one.faces()])


@pytest.mark.parametrize("make", [lambda: inputs.get("triangle-grid:3x2"),
                                  lambda: inputs.get("triangulated-ngon:6"),
                                  lambda: split_quads(3, 3)[0],
                                  lambda: _two_parts("triangle-grid:2x2")])
def test_triangle_three_colouring_agrees_with_a_face_by_face_oracle(make):
    mesh = make()
    c1 = triangle_three_colouring(mesh)
    assert c1.dtype == bool and c1.shape == (mesh.n_vertices,)
    check_triangle_colouring(mesh, c1)
    np.testing.assert_array_equal(c1, _three_colouring_oracle(mesh))


@pytest.mark.parametrize("name, message", [
    ("triangulated-ngon:5", "an inner vertex of odd degree"),
    ("triangulated-ngon:7", "an inner vertex of odd degree"),
    ("square-grid:2x2", "a mesh of triangles only"),
])
def test_triangle_three_colouring_refuses_what_has_none(name, message):
    mesh = inputs.get(name)
    assert mesh.face_degree != 3 or _three_colouring_oracle(mesh) is None
    with pytest.raises(MeshError, match=message):
        triangle_three_colouring(mesh)


@pytest.mark.parametrize("scheme, name, tile_sizes", [
    ("snub", "pentagon", {1, 2}),                  # boundary pentagons and octagons
    ("catmull-clark", "square-grid:2x2", {1}),     # every quad is a tile
    ("loop", "triangle-grid:2x2", {2}),            # glued triangle pairs
    ("butterfly", "triangle-grid:2x2", {2}),
    ("sqrt3", "triangle-grid:2x2", {2}),
    ("doo-sabin", "hex-grid:2x2", None),           # no weave of its own: face split
])
def test_scheme_weaves_one_per_level_of_the_schemes_kind(scheme, name, tile_sizes):
    hierarchy = subdivide(inputs.get(name), 2, scheme)
    weaves = scheme_weaves(hierarchy, scheme)
    levels = hierarchy[1:] if tile_sizes else hierarchy  # the face split weaves level 0 too
    assert len(weaves) == len(levels)
    for w, level in zip(weaves, levels):
        assert w.n_strands > 0 and w.n_tiles > 0
        if tile_sizes:  # tiles of the level's own faces
            assert w.tile_faces.max() < level.mesh.n_faces
            assert set(np.diff(w.tile_offsets).tolist()) <= tile_sizes
            # tiles are disjoint sets of faces
            assert len(np.unique(w.tile_faces)) == len(w.tile_faces)
    # the snub weave carries its lineage from the second woven level on
    assert (weaves[1].parent_strand is not None) == (scheme == "snub")
    split = scheme_weaves(hierarchy, scheme, face_split=True)
    assert len(split) == len(hierarchy)
    for w, level in zip(split, hierarchy):
        want = face_split_weave(level.mesh)
        assert np.array_equal(w.strand_visits, want.strand_visits)
        assert np.array_equal(w.tile_faces, want.tile_faces)


@pytest.mark.parametrize("dtype", [np.int64, np.float64])
def test_a_c1_marking_of_zeros_and_ones_weaves_like_the_boolean_one(dtype):
    """``triangle_weave`` reads its marking as booleans: 0/1 integers or floats (as a file
    gives them) weave the same as the boolean marking."""
    mesh, c1 = split_quads(3, 2)
    by_bool, by_number = triangle_weave(mesh, c1), triangle_weave(mesh, c1.astype(dtype))
    np.testing.assert_array_equal(by_number.tile_faces, by_bool.tile_faces)
    np.testing.assert_array_equal(by_number.strand_visits, by_bool.strand_visits)
    np.testing.assert_array_equal(by_number.visit_over, by_bool.visit_over)
