"""OBJ and JSON round trips and the errors bad files give."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given

from tests.strategies import any_mesh
from weavecut import inputs
from weavecut.errors import MeshFileError
from weavecut.mesh_io import read_mesh, write_mesh


@pytest.mark.parametrize("suffix", [".obj", ".json"])
@pytest.mark.parametrize("name", list(inputs.INPUTS))
def test_builtins_round_trip_exactly(tmp_path, suffix, name):
    mesh = inputs.get(name)
    path = tmp_path / f"m{suffix}"
    write_mesh(mesh, path)
    back = read_mesh(path)
    np.testing.assert_array_equal(back.vertices, mesh.vertices)
    assert back.faces() == mesh.faces()


@given(any_mesh)
def test_random_meshes_round_trip(tmp_path_factory, mesh):
    folder = tmp_path_factory.mktemp("rt")
    for suffix in (".obj", ".json"):
        write_mesh(mesh, folder / f"m{suffix}")
        back = read_mesh(folder / f"m{suffix}")
        assert back.vertices.tobytes() == mesh.vertices.tobytes()
        assert back.faces() == mesh.faces()


@pytest.mark.parametrize("text, message", [
    ("v 0 0 0\nv 1 0 0\nv 0 1 1\nf 1 2 3\n", "z = 1.0"),
    ("v 0 0\nv 1 0\nv 0 1\nf 1 2 4\n", "line 4: face index 4 refers to no vertex"),
    ("v 0 0\nv 1 x\n", "line 2: vertex coordinates must be numbers"),
    ("v 0 0\nv 1 0\nv 0 1\n", "no faces"),
    ("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\nbogus 1\n", "unknown OBJ statement 'bogus'"),
    ("", "no faces"),
])
def test_bad_obj_files(tmp_path, text, message):
    path = tmp_path / "bad.obj"
    path.write_text(text)
    with pytest.raises(MeshFileError, match=message):
        read_mesh(path)


def test_obj_negative_indices_and_slashes(tmp_path):
    path = tmp_path / "rel.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf -3/1 -2/1 -1/1\n")
    assert read_mesh(path).faces() == [[0, 1, 2]]


@pytest.mark.parametrize("text, message", [
    ("{", "invalid JSON"),
    ('{"format": "other"}', "not a weave-cut mesh"),
    ('{"format": "weave-cut-mesh", "version": 2}', "unsupported version 2"),
    ('{"format": "weave-cut-mesh", "version": 1, "vertices": [[0, 0]], "faces": [[0, "a", 1]]}',
     "face 0 must be a list of vertex indices"),
    ('{"format": "weave-cut-mesh", "version": 1, "vertices": [[0]], "faces": [[0, 1, 2]]}',
     "vertex 0 must be"),
])
def test_bad_json_files(tmp_path, text, message):
    path = tmp_path / "bad.json"
    path.write_text(text)
    with pytest.raises(MeshFileError, match=message):
        read_mesh(path)


def test_binary_garbage_and_unknown_suffix(tmp_path):
    path = tmp_path / "bad.obj"
    path.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(MeshFileError, match="not a text file"):
        read_mesh(path)
    with pytest.raises(MeshFileError, match="unknown mesh format"):
        read_mesh(tmp_path / "mesh.stl")
    with pytest.raises(MeshFileError, match="cannot read"):
        read_mesh(tmp_path / "missing.obj")
