"""Surfaces in: built-in solids, OBJ and JSON with z, validation of oriented 2-manifolds."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from scipy.spatial import ConvexHull

from weavecut import inputs
from weavecut.errors import MeshError, MeshFileError, NonManifoldError
from weavecut.mesh import Mesh
from weavecut.mesh_io import read_mesh, read_valid_mesh, write_mesh
from weavecut.surface import face_normals, signed_volume
from weavecut.validation import validate

# name: (V, E, F, face degree)
PLATONIC = {"tetrahedron": (4, 6, 4, 3), "cube": (8, 12, 6, 4), "octahedron": (6, 12, 8, 3),
            "dodecahedron": (20, 30, 12, 5), "icosahedron": (12, 30, 20, 3)}


@pytest.mark.parametrize("name", PLATONIC)
def test_platonic_solids_are_regular_outward_and_unit(name):
    mesh = inputs.get(name)
    v, e, f, k = PLATONIC[name]
    assert (mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces, mesh.face_degree) == (v, e, f, k)
    assert validate(mesh) is mesh  # already outwards
    np.testing.assert_allclose(np.linalg.norm(mesh.vertices, axis=1), 1.0, rtol=1e-14)
    lengths = np.linalg.norm(np.diff(mesh.vertices[mesh.topology.edges], axis=1), axis=2).ravel()
    np.testing.assert_allclose(lengths, lengths[0], rtol=1e-12)
    # faces are flat and their normals point away from the centre (scipy's hull as the oracle)
    hull = ConvexHull(mesh.vertices)
    np.testing.assert_allclose(signed_volume(mesh), hull.volume, rtol=1e-12)
    normals = face_normals(mesh)
    centres = mesh.vertices[mesh.dense_faces()].mean(axis=1)
    offsets = np.einsum("ij,fkj->fk", normals, mesh.vertices[mesh.dense_faces()])
    np.testing.assert_allclose(offsets, offsets[:, :1] * np.ones(k), atol=1e-12)
    assert (np.einsum("ij,ij->i", normals, centres) > 0).all()


@pytest.mark.parametrize("n", [0, 1, 2, 3])
def test_icosphere_counts_and_sphere(n):
    mesh = inputs.get(f"icosphere:{n}")
    assert mesh.n_faces == 20 * 4**n and mesh.n_vertices == 10 * 4**n + 2
    np.testing.assert_allclose(np.linalg.norm(mesh.vertices, axis=1), 1.0, rtol=1e-14)
    assert validate(mesh) is mesh
    assert signed_volume(mesh) > 0


def test_inside_out_closed_surface_is_turned_outwards():
    cube = inputs.get("cube")
    turned = validate(cube.reversed())
    np.testing.assert_array_equal(turned.face_indices, cube.face_indices)


def test_inconsistently_oriented_faces_are_named():
    cube = inputs.get("cube")
    faces = cube.faces()
    faces[2] = faces[2][::-1]
    mesh = Mesh.from_faces(cube.vertices, faces)
    with pytest.raises(NonManifoldError, match=r"runs the same way in face \d and face \d "
                                               r"\(the two faces are inconsistently oriented\)"):
        validate(mesh)


def test_non_manifold_edge_is_named():
    tet = inputs.get("tetrahedron")
    extra = np.vstack([tet.vertices, [[2.0, 2.0, 2.0]]])
    a, b = tet.faces()[0][:2]
    mesh = Mesh.from_faces(extra, tet.faces() + [[b, a, 4]])
    with pytest.raises(NonManifoldError, match=rf"edge \({min(a, b)}, {max(a, b)}\) is in 3 "
                                               "faces"):
        validate(mesh)


def test_zero_area_face_in_space():
    mesh = Mesh.from_faces([(0, 0, 0), (1, 1, 1), (2, 2, 2), (0, 0, 1)], [[0, 1, 2], [0, 2, 3]])
    with pytest.raises(MeshError, match="face 0 has zero area"):
        validate(mesh)


def test_open_surface_with_boundary_is_accepted():
    """Half an octahedron (a square pyramid without its base): a surface with boundary."""
    octa = inputs.get("octahedron")
    top = [f for f in octa.faces() if np.isin(f, np.flatnonzero(octa.vertices[:, 2] > 0.5)).any()]
    keep = np.flatnonzero(octa.vertices[:, 2] > -0.5)  # the bottom apex is in no face now
    number = {int(v): k for k, v in enumerate(keep)}
    mesh = validate(Mesh.from_faces(octa.vertices[keep], [[number[v] for v in f] for f in top]))
    assert mesh.topology.boundary_edges.sum() == 4
    with pytest.raises(MeshError, match="vertex 5 is in no face"):  # NaN once smoothed
        validate(Mesh.from_faces(octa.vertices, top))


@pytest.mark.parametrize("name, suffix", list(itertools.product(["dodecahedron", "icosphere:1"],
                                                                [".obj", ".json"])))
def test_surfaces_round_trip_through_files(tmp_path, name, suffix):
    mesh = inputs.get(name)
    path = tmp_path / f"solid{suffix}"
    write_mesh(mesh, path)
    back = read_valid_mesh(path)
    assert back.dim == 3
    np.testing.assert_array_equal(back.vertices, mesh.vertices)
    assert back.faces() == mesh.faces()


def test_obj_with_z_is_a_surface_and_flat_planes_stay_planar(tmp_path):
    path = tmp_path / "tilted.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 1\nf 1 2 3\n")
    assert read_mesh(path).dim == 3
    flat = tmp_path / "flat.obj"
    flat.write_text("v 0 5 0\nv 1 5 0\nv 0 5 1\nf 1 3 2\n")
    notes = []
    assert read_mesh(flat, note=notes.append).dim == 2
    assert "xz-plane" in notes[0]


@pytest.mark.parametrize("vertices, message", [
    ("[[0, 0, 0], [1, 0], [0, 1, 0]]", "vertex 1 must be \\[x, y, z\\] numbers like vertex 0"),
    ("[[0, 0, 0, 0], [1, 0, 0, 0], [0, 1, 0, 0]]", "vertex 0 must be \\[x, y\\] or \\[x, y, z\\]"),
])
def test_json_vertices_must_all_have_two_or_all_three_coordinates(tmp_path, vertices, message):
    path = tmp_path / "bad.json"
    path.write_text('{"format": "weave-cut-mesh", "version": 1, "vertices": ' + vertices
                    + ', "faces": [[0, 1, 2]]}')
    with pytest.raises(MeshFileError, match=message):
        read_mesh(path)
