"""Mesh geometry and topology against independent oracles: shapely for areas, centroids and
perimeters, plain Python loops over faces and edges for the rest."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from tests import meshes
from tests.strategies import any_mesh, valid_meshes
from weavecut.errors import MeshError
from weavecut.mesh import Mesh, Numbering, Topology, edge_faces, outer_vertices, vertex_degrees
from weavecut.mesh_geometry import (area_centroids, corner_angles, corner_turns, edge_lengths,
                                    face_centroids, face_perimeters, mirrored, signed_areas)

# an L-shaped hexagon (one reflex corner), a skewed quad, a triangle, a pentagon: faces of
# several degrees, convex and not, that share edges
IRREGULAR = Mesh.from_faces(
    [(0, 0), (3, 0), (3, 1), (1, 1), (1, 3), (0, 3), (4, 0.5), (3.5, 2), (2, 4), (5, 3)],
    [[0, 1, 2, 3, 4, 5], [1, 6, 7, 2], [3, 2, 7, 8, 4], [6, 9, 7]])


@st.composite
def star_polygons(draw) -> Mesh:
    """One simple polygon, counter-clockwise, of 3 to 12 corners at random radii round the
    origin: often non-convex, so its area centroid is far from its vertex mean."""
    k = draw(st.integers(3, 12))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    t = (np.arange(k) + rng.uniform(0, 0.4, k)) * 2 * np.pi / k  # gaps under half a turn
    r = rng.uniform(0.2, 3.0, k)
    shift = rng.uniform(-5, 5, 2)
    ring = np.column_stack([r * np.cos(t), r * np.sin(t)]) + shift
    return Mesh.from_faces(ring, [list(range(k))])


meshes_and_polygons = st.one_of(valid_meshes, star_polygons(), st.just(IRREGULAR))


def polygons(mesh: Mesh) -> list[shapely.Polygon]:
    return [shapely.Polygon(mesh.vertices[f]) for f in mesh.faces()]


@given(meshes_and_polygons)
def test_areas_centroids_and_perimeters_agree_with_shapely(mesh):
    polys = polygons(mesh)
    np.testing.assert_allclose(signed_areas(mesh), [p.area for p in polys], rtol=1e-9)
    np.testing.assert_allclose(signed_areas(mesh.reversed()), [-p.area for p in polys],
                               rtol=1e-9)
    assert all(p.exterior.is_ccw for p in polys)
    np.testing.assert_allclose(area_centroids(mesh), [p.centroid.coords[0] for p in polys],
                               rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(area_centroids(mesh.reversed()), area_centroids(mesh),
                               rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(face_perimeters(mesh), [p.exterior.length for p in polys],
                               rtol=1e-12)


def test_area_centroid_of_the_l_shape_by_hand():
    # the L: a 3 x 1 bar and a 1 x 2 post, centroids (1.5, 0.5) and (0.5, 2), areas 3 and 2
    want = (np.array([1.5, 0.5]) * 3 + np.array([0.5, 2.0]) * 2) / 5
    np.testing.assert_allclose(area_centroids(IRREGULAR)[0], want, rtol=1e-12)
    assert signed_areas(IRREGULAR)[0] == 5.0
    assert face_perimeters(IRREGULAR)[0] == 12.0
    np.testing.assert_allclose(face_centroids(IRREGULAR)[0], [8 / 6, 8 / 6])


def interior_angles(mesh: Mesh) -> list[float]:
    """The angle at every corner by the law of cosines, made reflex where the corner turns
    right (the triangle prev, corner, next is clockwise)."""
    out = []
    for face in mesh.faces():
        for i, v in enumerate(face):
            p, c, n = (mesh.vertices[j] for j in (face[i - 1], v, face[(i + 1) % len(face)]))
            a, b, d = math.dist(c, p), math.dist(c, n), math.dist(p, n)
            angle = math.acos(max(-1.0, min(1.0, (a * a + b * b - d * d) / (2 * a * b))))
            right = shapely.Polygon([p, c, n]).exterior.is_ccw is False
            out.append(2 * math.pi - angle if right else angle)
    return out


@given(meshes_and_polygons)
def test_corner_angles_agree_with_the_law_of_cosines(mesh):
    angles = corner_angles(mesh)
    np.testing.assert_allclose(angles, interior_angles(mesh), atol=1e-6)
    # a simple counter-clockwise k-gon turns once: its angles add up to (k - 2) pi
    sums = np.add.reduceat(angles, mesh.face_offsets[:-1])
    np.testing.assert_allclose(sums, (mesh.face_sizes - 2) * np.pi, rtol=1e-9)
    # corner_turns is negative exactly at the reflex corners
    assert ((corner_turns(mesh) < 0) == (angles > np.pi)).all()


def test_corner_angles_of_the_l_shape_by_hand():
    degrees = np.degrees(corner_angles(IRREGULAR))[:6]
    np.testing.assert_allclose(degrees, [90, 90, 90, 270, 90, 90])
    turns = corner_turns(IRREGULAR)[:6]  # cross product of unit-length edges: +-1
    np.testing.assert_array_equal(turns, [3 * 3, 3 * 1, 1 * 2, -2 * 2, 2 * 1, 1 * 3])


def test_face_centroids_are_vertex_means_in_two_and_three_dimensions():
    for mesh in (IRREGULAR, meshes.hexagon(), meshes.two_squares()):
        want = [mesh.vertices[f].mean(axis=0) for f in mesh.faces()]
        np.testing.assert_allclose(face_centroids(mesh), want, rtol=1e-12, atol=1e-15)
    lifted = Mesh.from_faces([(0, 0, 0), (2, 0, 1), (2, 2, 2), (0, 2, 3), (4, 1, 5)],
                             [[0, 1, 2, 3], [1, 4, 2]])
    np.testing.assert_allclose(face_centroids(lifted), [[1, 1, 1.5], [8 / 3, 1, 8 / 3]])
    dense3 = Mesh.from_faces([(0, 0, 0), (3, 0, 3), (0, 3, 6), (3, 3, 0)], [[0, 1, 2], [1, 3, 2]])
    np.testing.assert_allclose(face_centroids(dense3), [[1, 1, 3], [2, 2, 3]])


def python_topology(mesh: Mesh):
    """Edges (sorted pairs), the faces left of each directed edge, and degrees, by loops."""
    left = {}
    for f, face in enumerate(mesh.faces()):
        for i, u in enumerate(face):
            left[(u, face[(i + 1) % len(face)])] = f
    edges = sorted({tuple(sorted(e)) for e in left})
    neighbours = [set() for _ in range(mesh.n_vertices)]
    for u, w in edges:
        neighbours[u].add(w)
        neighbours[w].add(u)
    return edges, left, [len(n) for n in neighbours]


@given(st.one_of(any_mesh, st.just(IRREGULAR)))
def test_topology_agrees_with_loops_over_the_faces(mesh):
    edges, left, degrees = python_topology(mesh)
    topo = mesh.topology
    assert topo.edges.tolist() == [list(e) for e in edges]
    assert vertex_degrees(mesh).tolist() == degrees
    assert edge_faces(mesh).dtype == np.int32
    assert edge_faces(mesh).tolist() == [[left.get((u, w), -1), left.get((w, u), -1)]
                                         for u, w in edges]
    boundary = [(u, w) in left and (w, u) not in left or (w, u) in left and (u, w) not in left
                for u, w in edges]
    assert topo.boundary_edges.tolist() == boundary
    outer = {v for e, b in zip(edges, boundary) if b for v in e}
    assert outer_vertices(mesh).tolist() == [v in outer for v in range(mesh.n_vertices)]
    corners = [(u, f[(i + 1) % len(f)]) for f in mesh.faces() for i, u in enumerate(f)]
    index = {c: h for h, c in enumerate(corners)}
    assert topo.twin.tolist() == [index.get((w, u), -1) for u, w in corners]
    assert topo.half_edge_side.tolist() == [int(u > w) for u, w in corners]
    assert [edges[e] for e in topo.half_edge_edge] == [tuple(sorted(c)) for c in corners]
    np.testing.assert_allclose(edge_lengths(mesh), [math.dist(mesh.vertices[u], mesh.vertices[w])
                                                    for u, w in edges], rtol=1e-12)
    nxt = [h + 1 if h + 1 < b else a for a, b in zip(mesh.face_offsets[:-1], mesh.face_offsets[1:])
           for h in range(a, b)]
    assert mesh.next_half_edge.tolist() == nxt
    assert mesh.prev_half_edge[nxt].tolist() == list(range(mesh.n_corners))
    assert mesh.half_edge_face.tolist() == [f for f, face in enumerate(mesh.faces())
                                            for _ in face]


def test_edge_lengths_do_not_overflow_or_underflow_in_the_plane():
    for scale in (1e200, 1e-200):
        mesh = Mesh.from_faces(np.array([(0, 0), (1, 1), (0, 1)]) * scale, [[0, 1, 2]])
        assert edge_lengths(mesh).tolist() == [math.hypot(scale, scale), scale, scale]


def test_a_vertex_in_no_face_keeps_its_place_in_the_per_vertex_arrays():
    mesh = Mesh.from_faces(meshes.square().vertices.tolist() + [[5, 5]], [[0, 1, 2, 3]])
    assert vertex_degrees(mesh).tolist() == [2, 2, 2, 2, 0]
    assert outer_vertices(mesh).tolist() == [True] * 4 + [False]


def test_edge_lengths_of_a_surface_in_space():
    mesh = Mesh.from_faces([(0, 0, 0), (3, 4, 0), (0, 0, 12)], [[0, 1, 2]])
    assert edge_lengths(mesh).tolist() == [5.0, 12.0, 13.0]  # edges (0,1), (0,2), (1,2)


def test_sizes_degrees_and_dense_faces():
    assert IRREGULAR.face_sizes.tolist() == [6, 4, 5, 3]
    assert IRREGULAR.face_degree is None and IRREGULAR.dense_faces() is None
    assert (IRREGULAR.n_vertices, IRREGULAR.n_faces, IRREGULAR.n_corners, IRREGULAR.dim) == \
        (10, 4, 18, 2)
    two = meshes.two_squares()
    assert two.face_degree == 4
    assert two.dense_faces().tolist() == [[0, 1, 4, 5], [1, 2, 3, 4]]
    empty = Mesh.from_faces([], [])
    assert empty.face_degree is None and empty.n_faces == 0 and empty.vertices.shape == (0, 2)
    assert signed_areas(empty).shape == (0,) and empty.faces() == []
    assert Mesh.from_faces([(0, 0, 0), (1, 0, 0), (0, 1, 1)], [[0, 1, 2]]).dim == 3


def test_reversed_and_mirrored():
    rev = IRREGULAR.reversed()
    assert rev.faces() == [f[::-1] for f in IRREGULAR.faces()]
    np.testing.assert_array_equal(rev.vertices, IRREGULAR.vertices)
    image = mirrored(IRREGULAR)
    np.testing.assert_array_equal(image.vertices, IRREGULAR.vertices * [-1, 1])
    assert image.faces() == rev.faces()
    np.testing.assert_allclose(signed_areas(image), signed_areas(IRREGULAR))


def test_moved_checks_the_shape_and_keeps_the_derived_arrays():
    mesh = meshes.mixed()
    _ = mesh.topology, mesh.face_sizes, mesh.half_edge_face, mesh.next_half_edge
    moved = mesh.moved(mesh.vertices + 1)
    for name in ("topology", "face_sizes", "half_edge_face", "next_half_edge"):
        assert moved.__dict__[name] is mesh.__dict__[name]
    np.testing.assert_array_equal(moved.vertices, mesh.vertices + 1)
    assert not moved.vertices.flags.writeable
    with pytest.raises(MeshError, match=r"^moved\(\) needs \(7, 2\) vertices, got \(6, 2\)$"):
        mesh.moved(mesh.vertices[:6])
    whole = meshes.square().moved(np.array([[0, 0], [3, 0], [3, 3], [0, 3]]))  # integers
    assert whole.vertices.dtype == np.float64 and signed_areas(whole)[0] == 9.0
    fresh = meshes.square().moved(meshes.square().vertices * 3)  # nothing derived yet
    assert "topology" not in fresh.__dict__ and signed_areas(fresh)[0] == 9.0


def test_trusted_wraps_without_copying_and_keeps_a_given_topology():
    v = np.array([(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)])
    off, idx = np.array([0, 3]), np.array([0, 1, 2], dtype=np.int32)
    topo = Topology.build(Mesh(v, off, idx))
    mesh = Mesh.trusted(v, off, idx, topo)
    assert mesh.vertices is v and mesh.face_offsets is off and mesh.face_indices is idx
    assert mesh.topology is topo and not v.flags.writeable
    assert "topology" not in Mesh.trusted(v, off, idx).__dict__


def test_numbering_names_elements_as_the_source_counts():
    obj = Numbering(first=1, face_lines=np.array([7, 9, 12]))
    assert (obj.face(2), obj.vertex(0), obj.edge(3, 4), obj.number(np.int32(5))) == \
        ("face 3 (line 12)", "vertex 1", "edge (4, 5)", 6)
    zero = Numbering()
    assert (zero.face(2), zero.vertex(0), zero.edge(3, 4)) == ("face 2", "vertex 0", "edge (3, 4)")


@pytest.mark.parametrize("vertices, offsets, indices, message", [
    (np.zeros((3, 4)), [0, 3], [0, 1, 2], r"vertices must have shape \(V, 2\) or \(V, 3\), got "
                                          r"\(3, 4\)"),
    (np.zeros(6), [0, 3], [0, 1, 2], r"vertices must have shape .*, got \(6,\)"),
    ([(0, 0), (1, 0), (0, np.inf)], [0, 3], [0, 1, 2],
     r"vertex 2 has a non-finite coordinate \(0.0, inf\)"),
    ([(0, 0), (1, 0), (0, 1)], [1, 3], [0, 1, 2], "face offsets must start at 0 and end"),
    ([(0, 0), (1, 0), (0, 1)], [0, 2], [0, 1, 2], "face offsets must start at 0 and end"),
    ([(0, 0), (1, 0), (0, 1)], [], [], "face offsets must start at 0 and end"),
    ([(0, 0), (1, 0), (0, 1)], [[0, 3]], [0, 1, 2], "face offsets must start at 0 and end"),
    ([(0, 0), (1, 0), (0, 1), (1, 1)], [0, 3, 5, 8], [0, 1, 2, 1, 3, 3, 2, 1],
     "face 1 has 2 corner"),
    ([(0, 0), (1, 0), (0, 1), (1, 1)], [0, 3, 6], [0, 1, 2, 1, 3, 4],
     r"face 1 uses vertex 4, out of range 0\.\.3"),
    ([(0, 0), (1, 0), (0, 1), (1, 1)], [0, 3, 6], [0, 1, 2, 1, -1, 3],
     r"face 1 uses vertex -1, out of range 0\.\.3"),
])
def test_structure_messages(vertices, offsets, indices, message):
    with pytest.raises(MeshError, match=f"^{message}"):
        Mesh(vertices, offsets, indices)


def test_structure_messages_count_as_the_numbering_says():
    from weavecut.mesh import check_structure

    mesh = Mesh.trusted(np.zeros((3, 2)), np.array([0, 3, 6]),
                        np.array([0, 1, 2, 0, 1, 3], dtype=np.int32))
    with pytest.raises(MeshError, match=r"^face 2 \(line 8\) uses vertex 4, out of range 1\.\.3$"):
        check_structure(mesh, Numbering(first=1, face_lines=np.array([5, 8])))


def test_from_faces_refuses_indices_it_cannot_store():
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    with pytest.raises(MeshError, match="^face vertex indices must be integers in range$"):
        Mesh.from_faces(square, [[0, 1, "a"]])
    with pytest.raises(MeshError, match="^face vertex indices must be integers in range$"):
        Mesh.from_faces(square, [[0, 1, 2**70]])
    with pytest.raises(MeshError, match="^vertex index 2147483648 is out of range$"):
        Mesh.from_faces(square, [[0, 1, 2**31]])
    with pytest.raises(MeshError, match="^vertex index -2147483648 is out of range$"):
        Mesh.from_faces(square, [[0, -2**31, 1]])
    mesh = Mesh.from_faces(square, [(0, 1, 2), iter([0, 2, 3])])  # any iterables
    assert mesh.faces() == [[0, 1, 2], [0, 2, 3]]
    assert mesh.face_offsets.dtype == np.int64 and mesh.face_indices.dtype == np.int32
    assert mesh.vertices.dtype == np.float64


@pytest.mark.parametrize("faces, message", [
    ([[0, 1, 2], [1, 0, 3], [0, 1, 4]], r"^edge \(0, 1\) is in 3 faces; at most 2 allowed$"),
    ([[0, 1, 2], [1, 2, 3], [0, 1, 4]], r"^edge \(0, 1\) runs the same way in face 0 and face 2 "
                                        r"\(the two faces are inconsistently oriented\)$"),
])
def test_non_manifold_messages(faces, message):
    from weavecut.errors import NonManifoldError

    v = [(0, 0), (1, 0), (0.5, 1), (0.5, -1), (1.5, 0.5)]
    with pytest.raises(NonManifoldError, match=message):
        Topology.build(Mesh.from_faces(v, faces))


def test_bow_tie_message_counts_the_fans():
    from weavecut.errors import NonManifoldError

    ring = [(np.cos(a), np.sin(a)) for a in np.linspace(0, 2 * np.pi, 7)[:-1]]
    v = [(0.0, 0.0), *ring]  # three triangles round vertex 0 with gaps between them
    with pytest.raises(NonManifoldError, match="^vertex 0 joins 3 separate fans of faces "
                                               r"\(a bow-tie\)$"):
        Mesh.from_faces(v, [[0, 1, 2], [0, 3, 4], [0, 5, 6]]).topology
