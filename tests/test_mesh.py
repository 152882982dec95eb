"""Mesh core: structure checks, topology, immutability."""

from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from tests import meshes
from tests.strategies import examples, jittered_grids
from weavecut.errors import MeshError, NonManifoldError
from weavecut.mesh import Mesh, Topology, edge_faces
from weavecut.mesh_geometry import face_centroids, signed_areas


def test_arrays_are_private_and_read_only():
    v = np.array([(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)])
    mesh = Mesh(v, [0, 3], [0, 1, 2])
    v[0] = (5, 5)
    assert mesh.vertices[0].tolist() == [0.0, 0.0]
    with pytest.raises(ValueError):
        mesh.vertices[0, 0] = 1.0


@pytest.mark.parametrize("vertices, faces, message", [
    ([(0, 0), (1, 0), (0, 1)], [[0, 1, 3]], "vertex 3, out of range"),
    ([(0, 0), (1, 0), (0, 1)], [[0, 1]], "face 0 has 2 corner"),
    ([(0, 0), (1, 0), (0, 1), (1, 1)], [[0, 1, 1, 2]], "face 0 visits vertex 1 more than once"),
    ([(0, 0), (1, float("nan")), (0, 1)], [[0, 1, 2]], "vertex 1 has a non-finite"),
    ([(0, 0), (1, float("inf")), (0, 1)], [[0, 1, 2]], "non-finite"),
    ([(0, 0), (1, 0), (0, 1)], [[0, 1, -1]], "out of range"),
])
def test_structure_errors_name_the_element(vertices, faces, message):
    with pytest.raises(MeshError, match=message):
        Mesh.from_faces(vertices, faces)


@st.composite
def faces_with_repeats(draw):
    """Faces of 3 to 20 distinct corners, some with one corner copied onto another."""
    degree = draw(st.sampled_from([None, 3, 5, 16, 17]))  # None: mixed degrees
    faces = []
    for _ in range(draw(st.integers(1, 6))):
        size = degree or draw(st.integers(3, 20))
        face = draw(st.lists(st.integers(0, 24), min_size=size, max_size=size, unique=True))
        if draw(st.booleans()):
            i, j = draw(st.lists(st.integers(0, size - 1), min_size=2, max_size=2, unique=True))
            face[j] = face[i]
        faces.append(face)
    return faces


@settings(max_examples=examples(200))
@given(faces_with_repeats())
@example([list(range(15)) + [3]])  # 16 corners, the largest face compared in a table
@example([list(range(16)) + [3]])  # 17, the smallest sorted
def test_the_first_face_with_a_repeated_vertex_is_named(faces):
    # tables by degree for faces of up to MAX_COMPARED (16) corners, a sort beyond
    repeating = [f for f, face in enumerate(faces) if len(set(face)) < len(face)]
    vertices = np.zeros((25, 2))
    if not repeating:
        Mesh.from_faces(vertices, faces)
        return
    face = faces[repeating[0]]
    twice = min(i for i in face if face.count(i) > 1)
    with pytest.raises(MeshError, match=f"^face {repeating[0]} visits vertex {twice} more than"):
        Mesh.from_faces(vertices, faces)


def test_edge_in_three_faces_is_non_manifold():
    v = [(0, 0), (1, 0), (0.5, 1), (0.5, -1), (1.5, 0.5)]
    with pytest.raises(NonManifoldError, match=r"edge \(0, 1\) is in 3 faces"):
        Mesh.from_faces(v, [[0, 1, 2], [1, 0, 3], [0, 1, 4]]).topology


def test_edge_twice_in_the_same_direction_is_an_error():
    v = [(0, 0), (1, 0), (0.5, 1), (0.5, -1)]
    with pytest.raises(NonManifoldError, match="runs the same way in face 0 and face 1"):
        Mesh.from_faces(v, [[0, 1, 2], [0, 1, 3]]).topology


def test_bow_tie_vertex_is_non_manifold():
    v = [(0, 0), (1, -1), (1, 1), (-1, 1), (-1, -1)]
    with pytest.raises(NonManifoldError, match="vertex 0 joins 2 separate fans"):
        Mesh.from_faces(v, [[0, 1, 2], [0, 3, 4]]).topology


@given(jittered_grids())
def test_topology_of_a_disc(mesh):
    topo = mesh.topology
    assert mesh.n_vertices - topo.n_edges + mesh.n_faces == 1
    inner = topo.twin >= 0
    assert (topo.twin[topo.twin[inner]] == np.flatnonzero(inner)).all()
    ef = edge_faces(mesh)
    assert ((ef >= 0).sum(axis=1) == np.where(topo.boundary_edges, 1, 2)).all()
    # each half-edge's face lies on the side its direction says
    assert (ef[topo.half_edge_edge, topo.half_edge_side] == mesh.half_edge_face).all()


def test_moved_shares_topology_and_reversed_flips_areas():
    mesh = meshes.mixed()
    topo = mesh.topology
    moved = mesh.moved(mesh.vertices * 2)
    assert moved.topology is topo
    np.testing.assert_allclose(signed_areas(moved), 4 * signed_areas(mesh))
    np.testing.assert_allclose(signed_areas(mesh.reversed()), -signed_areas(mesh))
    np.testing.assert_allclose(face_centroids(mesh)[0], [0.5, 0.5])


def test_topology_edges_are_sorted_and_deterministic():
    mesh = meshes.mixed()
    a, b = Topology.build(mesh), Topology.build(Mesh(mesh.vertices, mesh.face_offsets,
                                                     mesh.face_indices))
    np.testing.assert_array_equal(a.edges, b.edges)
    keys = a.edges[:, 0].astype(np.int64) * mesh.n_vertices + a.edges[:, 1]
    assert (np.diff(keys) > 0).all()


def _oracle_topology(faces):
    """Dict-based topology of a list of faces: (edges, half-edge edge, half-edge side), or the
    message of the first bad edge (by the sorted edge order) that Topology.build must give."""
    directed = [(f, u, face[(i + 1) % len(face)]) for f, face in enumerate(faces)
                for i, u in enumerate(face)]
    edges = sorted({(min(u, w), max(u, w)) for _, u, w in directed})
    index = {e: i for i, e in enumerate(edges)}
    he_edge = [index[(min(u, w), max(u, w))] for _, u, w in directed]
    side = [int(u > w) for _, u, w in directed]
    for e, (a, b) in enumerate(edges):
        if he_edge.count(e) > 2:
            return f"edge ({a}, {b}) is in {he_edge.count(e)} faces"
    for e, (a, b) in enumerate(edges):
        for s in (0, 1):
            on = [f for (f, _, _), h, t in zip(directed, he_edge, side) if h == e and t == s]
            if len(on) > 1:
                return f"edge ({a}, {b}) runs the same way in face {on[0]} and face {on[1]}"
    return edges, he_edge, side


@settings(max_examples=300)
@given(st.lists(st.permutations(range(7)).map(lambda p: list(p[:3])), min_size=1, max_size=6))
@example([[0, 1, 2], [2, 1, 3], [3, 1, 4], [4, 1, 5], [1, 2, 6]])
@example([[0, 1, 2], [1, 0, 3], [2, 1, 4], [4, 1, 5], [5, 6, 4], [6, 5, 2]])
def test_topology_against_a_dict_built_one(faces):
    """Topology.build on triangle soups against a dict oracle: the same edges, half-edge edges
    and sides, or the same first bad edge named in the error (bow-tie vertices aside)."""
    want = _oracle_topology(faces)
    mesh = Mesh.from_faces(np.zeros((7, 2)), faces)
    if isinstance(want, str):
        with pytest.raises(NonManifoldError, match="^" + re.escape(want)):
            Topology.build(mesh)
        return
    try:
        topo = Topology.build(mesh)
    except NonManifoldError as error:
        assert "separate fans" in str(error)
        return
    edges, he_edge, side = want
    assert topo.edges.tolist() == [list(e) for e in edges]
    assert topo.half_edge_edge.tolist() == he_edge
    assert topo.half_edge_side.tolist() == side


def test_vertex_count_beyond_int32_indexes_is_refused():
    """2**31 vertices (a zero-stride view, no memory) are one more than int32 indexes reach."""
    from types import SimpleNamespace
    from weavecut.mesh import check_structure
    many = SimpleNamespace(vertices=np.broadcast_to(np.zeros((1, 2)), (2**31, 2)),
                           face_offsets=np.zeros(1, np.int64), face_indices=np.zeros(0, np.int32))
    with pytest.raises(MeshError, match=r"^2147483648 vertices is more than weave-cut indexes "
                                        r"\(2147483647\)$"):
        check_structure(many)


def test_out_of_range_first_corner_names_its_own_face():
    """The out-of-range corner opening face 1 is blamed on face 1, not on the face before."""
    with pytest.raises(MeshError, match=r"^face 1 uses vertex 5, out of range 0\.\.2$"):
        Mesh.from_faces([(0, 0), (1, 0), (0, 1)], [[0, 1, 2], [5, 1, 2]])
