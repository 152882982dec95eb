"""Mesh files: what is written, what is read back, and the exact one-line message of every kind
of bad file (line numbers and the counts OBJ users see)."""

from __future__ import annotations

import json
import os
import re
from unittest.mock import patch

import numpy as np
import pytest

from tests import meshes, obj_reference
from weavecut import mesh_io, readers
from weavecut.readers import obj
from weavecut.errors import MeshError, MeshFileError
from weavecut.mesh import Mesh
from weavecut.mesh_geometry import signed_areas
from weavecut.mesh_io import json_text, obj_text, read_mesh, read_valid_mesh, write_mesh

TRIANGLE = "v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n"


def refused(tmp_path, name: str, data: bytes | str) -> str:
    """The message reading ``data`` as file ``name`` gives, without the path."""
    path = tmp_path / name
    path.write_bytes(data.encode() if isinstance(data, str) else data)
    with pytest.raises(MeshError) as error:  # MeshFileError, or the structure's MeshError
        read_mesh(path)
    prefix = f"{path}: "
    assert str(error.value).startswith(prefix), error.value
    return str(error.value)[len(prefix):]


# -- OBJ ------------------------------------------------------------------------------------

@pytest.mark.parametrize("text, message", [
    ("v 0 0\nv 1 0\nv 0 1\nf 0 1 2\n", "line 4: face index 0 refers to no vertex (3 defined so "
                                        "far)"),
    ("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\nf 3 2 -4\n", "line 5: face index -4 refers to no vertex (3 "
                                                 "defined so far)"),
    ("v 0 0\nv 1 0\nf -1 -2 -3\nv 0 1\nf 1 2 3\n", "line 3: face index -3 refers to no vertex "
                                                   "(2 defined so far)"),
    ("v 0 0\nv 1 0\nf 1 2 3\nv 0 1\n", "line 3: face index 3 refers to no vertex (2 defined so "
                                       "far)"),
    ("v 0 0\nv 1 0\nv 0 1\n\n# gap\nf 1 2 3\nf 1 2 4/4/4\n", "line 7: face index 4 refers to "
                                                             "no vertex (3 defined so far)"),
    ("v 0 0\nv 1 0 0 1 2\n", "line 2: a vertex needs x y [z], got 5 numbers"),
    ("v 0 0\nv 1\n", "line 2: a vertex needs x y [z], got 1 numbers"),
    ("v 0 0\nv\n", "line 2: a vertex needs x y [z], got 0 numbers"),
    ("v 0 0\nv 1 1e999\n", "line 2: vertex coordinate is not finite"),
    ("v 0 0\nv 1 -inf\n", "line 2: vertex coordinate is not finite"),
    ("v 0 0\nv 1 0\nv 0 1\nf 1 2 3.0\n", "line 4: face indices must be whole numbers"),
    ("v 0 0\nv 1 0\nv 0 1\nf 1 2 " + "9" * 20 + "\n",
     "line 4: face index " + "9" * 20 + " is too large"),
    ("v 0 0\nv 1 0\nv 0 1\nf 1 2 " + "0" * 16 + "1\n",  # more than 16 digits, by length
     "line 4: face index " + "0" * 16 + "1 is too large"),
    ("v 0 0\nv 1 0\nv 0 1\nf 1 2 " + "9" * 50 + "\n",
     "line 4: face index " + "9" * 37 + "... is too large"),
    ("v 0 0\nv 1 0\nv 0 1\nvx 1 2\n", "line 4: unknown OBJ statement 'vx'"),
    (TRIANGLE + "x" * 300 + "\n", "line 5: unknown OBJ statement '" + "x" * 169),  # 200 long
    ("v 0 0\nbogus\nv 1 x\n", "line 2: unknown OBJ statement 'bogus'"),
    ("v 1 x\nbogus\n", "line 1: vertex coordinates must be numbers"),
    ("v 0 0\r\nv 1 0\r\nv 0 1\r\nf 1 2 3\r\nf 1 2 0\r\n", "line 5: face index 0 refers"),
    ("v 0 0\rv 1 0\rv 0 1\rf 1 2 9\r", "line 4: face index 9 refers"),
    ("# only a comment\n\n", "no faces ('f' lines) found"),
])
def test_obj_messages(tmp_path, text, message):
    assert refused(tmp_path, "m.obj", text).startswith(message)
    with pytest.raises(obj_reference.Refused, match=f"^{re.escape(message)}"):  # the oracle
        obj_reference.read(text.encode())


def test_obj_negative_indices_count_back_from_the_vertices_read_so_far(tmp_path):
    path = tmp_path / "m.obj"
    path.write_text("v 0 0\nv 1 0\nv 0 1\nf -3 -2 -1\nv 1 1\nv 2 2\nf -4 -2 -3\nf 2 5 4\n")
    # -1 on line 4 is vertex 3; on line 7, after two more vertices, -2 is vertex 4
    assert read_mesh(path).faces() == [[0, 1, 2], [1, 3, 2], [1, 4, 3]]


@pytest.mark.parametrize("z, note", [
    (0.0, ""), (-0.0, ""), (1.0, "z = 1.0"), (-1.0, "z = -1.0"), (1e-300, "z = 1e-300")])
def test_a_flat_obj_off_the_ground_is_read_with_a_note(tmp_path, z, note):
    path = tmp_path / "m.obj"
    path.write_text(f"v 0 0 {z!r}\nv 1 0 {z!r}\nv 0 1 {z!r}\nf 1 2 3\n")
    notes = []
    mesh = read_mesh(path, note=notes.append)
    want = [f"{path}: all vertices have {note}; read in the xy-plane as (x, y)"] if note else []
    assert notes == want
    assert mesh.dim == 2 and mesh.vertices.tolist() == [[0, 0], [1, 0], [0, 1]]
    assert read_mesh(path).dim == 2  # no one to tell: no note, the same mesh


def test_planes_are_tried_z_first_then_y_then_x(tmp_path):
    path = tmp_path / "m.obj"
    # every vertex has y = 2 and x = 5: the xz-plane (y) wins over the yz-plane (x)
    path.write_text("v 5 2 0\nv 5 2 1\nv 5 2 3\nf 1 2 3\n")
    notes = []
    mesh = read_mesh(path, note=notes.append)
    assert notes == [f"{path}: all vertices have y = 2.0; read in the xz-plane as (x, -z), "
                     "seen from +y"]
    assert mesh.vertices.tolist() == [[5, 0], [5, -1], [5, -3]]
    path.write_text("v 5 0 0\nv 5 1 0\nv 5 0 1\nf 1 2 3\n")  # z differs: not the xy-plane
    notes.clear()
    assert read_mesh(path, note=notes.append).vertices.tolist() == [[0, 0], [1, 0], [0, 1]]
    assert notes == [f"{path}: all vertices have x = 5.0; read in the yz-plane as (y, z), "
                     "seen from +x"]


def test_more_faces_or_vertices_than_the_limit_are_refused(tmp_path):
    text = "v 0 0\nv 1 0\nv 0 1\nv 1 1\nf 1 2 3\nf 2 4 3\nf 1 2 4\n"
    with patch.object(readers, "MAX_FACES", 2):
        assert refused(tmp_path, "m.obj", text) == (
            "more than 2 faces or 33,554,432 vertices by line 7; weave-cut reads at most that")
        assert read_mesh_text(tmp_path, text[:-len("f 1 2 4\n")]).n_faces == 2
    with patch.object(readers, "MAX_VERTICES", 3):
        assert refused(tmp_path, "m.obj", text) == (
            "more than 16,777,216 faces or 3 vertices by line 7; weave-cut reads at most that")


def read_mesh_text(tmp_path, text: str, name: str = "ok.obj") -> Mesh:
    path = tmp_path / name
    path.write_text(text)
    return read_mesh(path)


def test_big_files_are_read_in_pieces_that_agree_with_the_whole(tmp_path):
    # a mesh of many lines read with pieces of 64 bytes: lines, vertices before a face and
    # the limit's line count cross the pieces' ends
    mesh = meshes.mixed()
    text = obj_text(mesh) + "# end\n"
    with patch.object(obj, "CHUNK", 64):
        back = read_mesh_text(tmp_path, text)
        assert back.faces() == mesh.faces() and back.vertices.tolist() == mesh.vertices.tolist()
        bad = text + "f 1 2 99\n"
        assert refused(tmp_path, "m.obj", bad) == (
            f"line {bad.count(chr(10))}: face index 99 refers to no vertex (7 defined so far)")
        with patch.object(readers, "MAX_FACES", 2):
            message = refused(tmp_path, "m.obj", text)
    first_faces = text.index("\nf ") + 1
    lines = text[:first_faces].count("\n")
    assert message.startswith("more than 2 faces or 33,554,432 vertices by line ")
    assert int(message.split("by line ")[1].split(";")[0]) > lines + 2


def test_coordinates_longer_than_the_window_are_read_whole(tmp_path):
    # numbers numpy converts (exponents, underscores) of more than 40 characters are read one
    # by one; their first 40 characters alone would be another number
    tokens = ["1." + "0" * 45 + "1e5", "-2_5." + "5" * 50, "3" + "0" * 45 + "e-45", "7e1"]
    text = "".join(f"v {t} 1 0\n" for t in tokens) + "f 1 2 3\nf 1 3 4\n"
    mesh = read_mesh_text(tmp_path, text)
    assert mesh.vertices[:, 0].tolist() == [float(t) for t in tokens]


def test_comments_and_text_that_is_not_ascii(tmp_path):
    text = "# café, naïve\nv 0 0 # ü\nv 1 0\nv 0 1\nf 1 2 3 # é\n"
    assert read_mesh_text(tmp_path, text).faces() == [[0, 1, 2]]
    assert refused(tmp_path, "m.obj", text.encode("latin-1")) == "not a text file (not UTF-8)"
    assert refused(tmp_path, "m.obj", TRIANGLE + "é 1\n") == "line 5: unknown OBJ statement 'é'"
    # a long statement of two-byte letters, the first 800 bytes of which end inside a letter
    long = "x" + "é" * 500
    message = refused(tmp_path, "m.obj", TRIANGLE + long + " 1\n")
    assert message == f"line 5: unknown OBJ statement {long!r}"[:200]


# -- what is written ------------------------------------------------------------------------

def test_obj_text_is_what_any_obj_reader_reads(tmp_path):
    mesh = Mesh.from_faces([(0.1, -2.5), (1e-20, 3.0), (7.0, 1 / 3)], [[0, 1, 2]])
    text = obj_text(mesh, {"generator": "weave-cut test", "command": "a\nb"})
    assert text.splitlines() == [
        "# weave-cut mesh", "# 3 vertices, 1 faces", "# generator: weave-cut test",
        "# command: a b", "v 0.1 -2.5 0", "v 1e-20 3.0 0", f"v 7.0 {1 / 3!r} 0", "f 1 2 3"]
    vertices, faces, remark = obj_reference.read(text.encode())
    assert vertices.tolist() == mesh.vertices.tolist() and faces == [[0, 1, 2]] and not remark
    surface = Mesh.from_faces([(0, 0, 0.5), (1, 0, 0), (0, 1, -2)], [[0, 1, 2]])
    assert obj_text(surface).splitlines()[2:] == ["v 0.0 0.0 0.5", "v 1.0 0.0 0.0",
                                                  "v 0.0 1.0 -2.0", "f 1 2 3"]


def test_json_text_carries_metadata_the_reader_ignores(tmp_path):
    mesh = meshes.mixed()
    doc = json.loads(json_text(mesh, {"generator": "weave-cut test"}))
    assert doc == {"format": "weave-cut-mesh", "version": 1, "generator": "weave-cut test",
                   "vertices": mesh.vertices.tolist(), "faces": mesh.faces()}
    path = tmp_path / "m.json"
    write_mesh(mesh, path, {"generator": "weave-cut test"})
    back = read_mesh(path)
    assert back.faces() == mesh.faces() and back.vertices.tolist() == mesh.vertices.tolist()


def test_write_mesh_keeps_the_metadata_and_writes_compact_json(tmp_path):
    mesh = meshes.mixed()
    write_mesh(mesh, tmp_path / "m.obj", {"generator": "weave-cut test"})
    assert "# generator: weave-cut test" in (tmp_path / "m.obj").read_text().splitlines()
    write_mesh(mesh, tmp_path / "m.json", {"generator": "weave-cut test"})
    text = (tmp_path / "m.json").read_text()
    assert json.loads(text)["generator"] == "weave-cut test"
    assert text.count("\n") == 1 and text.endswith("]]}\n")  # one line
    assert " " not in text.replace("weave-cut test", "")  # no space between items


@pytest.mark.parametrize("name", ["m.obj", "m.json", "M.OBJ", "m.Json"])
def test_surfaces_and_upper_case_suffixes_round_trip(tmp_path, name):
    rng = np.random.default_rng(3)
    surface = Mesh.from_faces(rng.normal(size=(4, 3)), [[0, 2, 1], [0, 1, 3], [0, 3, 2],
                                                       [1, 2, 3]])
    write_mesh(surface, tmp_path / name, {"command": "test"})
    back = read_mesh(tmp_path / name)
    assert back.vertices.tobytes() == surface.vertices.tobytes()
    assert back.faces() == surface.faces()


def test_unknown_suffixes_are_refused_on_writing_and_reading(tmp_path):
    path = tmp_path / "m.stl"
    with pytest.raises(MeshFileError, match=rf"^{path}: unknown mesh format '\.stl'; use \.obj "
                                            r"or \.json$"):
        write_mesh(meshes.square(), path)
    assert not path.exists()
    path.write_text("solid")
    with pytest.raises(MeshFileError, match=rf"^{path}: unknown mesh format '\.stl'; use \.obj "
                                            r"or \.json, or a drawing \(\.svg, \.dxf\)$"):
        read_mesh(path)


def test_missing_and_oversized_files(tmp_path):
    with pytest.raises(MeshFileError, match=rf"^cannot read {tmp_path}/no\.obj: No such file or "
                                            "directory$"):
        read_mesh(tmp_path / "no.obj")
    for suffix, limit in ((".obj", "1,024"), (".JSON", "512")):
        path = tmp_path / f"huge{suffix}"
        size = mesh_io.MAX_BYTES[suffix.lower()] + 1
        with open(path, "wb") as f:
            f.truncate(size)
        with pytest.raises(MeshFileError, match=rf"^{path}: {size:,} bytes is more than the "
                                                rf"{limit} MiB weave-cut reads from a "
                                                rf"{suffix.lower()} file$"):
            read_mesh(path)
    size = len(TRIANGLE)
    with patch.object(mesh_io, "MAX_BYTES", {".obj": size, ".json": size}):
        assert read_mesh_text(tmp_path, TRIANGLE).n_faces == 1  # at the limit: read
    with patch.object(mesh_io, "MAX_BYTES", {".obj": size - 1, ".json": size}):
        assert refused(tmp_path, "m.obj", TRIANGLE) == (
            f"{size} bytes is more than the 0 MiB weave-cut reads from a .obj file")


def test_read_valid_mesh_names_the_file_and_validates(tmp_path):
    path = tmp_path / "dent.json"
    write_mesh(Mesh.from_faces([(0, 0), (2, 0), (2, 2), (1, 0.5), (0, 2)], [[4, 3, 2, 1, 0]]),
               path)  # clockwise and not convex
    with pytest.raises(MeshError, match=rf"^{path}: face 0 is not convex at vertex 3"):
        read_valid_mesh(path)
    mesh = read_valid_mesh(path, allow_nonconvex=True)
    assert signed_areas(mesh)[0] > 0 and mesh.faces() == [[0, 1, 2, 3, 4]]
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0\nv 1 0\nv 0 1\nv 5 5\nf 1 2 3\n")
    with pytest.raises(MeshError, match=rf"^{bad}: vertex 4 is in no face$"):
        read_valid_mesh(bad)


def test_read_valid_mesh_passes_allow_nonconvex_to_a_drawing(tmp_path):
    path = tmp_path / "ell.svg"  # an L and the piece that fills it up to a rectangle
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
                    'viewBox="0 0 100 100"><polygon points="0,0 40,0 40,20 20,20 20,40 0,40"/>'
                    '<polygon points="40,0 60,0 60,40 20,40 20,20 40,20"/></svg>')
    with pytest.raises(MeshError, match=rf"^{path}: face 0 \(<polygon>\) is not convex at "):
        read_valid_mesh(path)
    mesh = read_valid_mesh(path, allow_nonconvex=True)
    assert sorted(signed_areas(mesh).round(9).tolist()) == [1200.0, 1200.0]


# -- JSON -----------------------------------------------------------------------------------

def doc(**fields) -> str:
    return json.dumps({"format": "weave-cut-mesh", "version": 1, "vertices": [[0, 0], [1, 0],
                                                                              [0, 1]],
                       "faces": [[0, 1, 2]], **fields})


@pytest.mark.parametrize("text, message", [
    ("{\n  \"a\": 1,\n}", "invalid JSON at line 3: Expecting property name enclosed in double "
                          "quotes"),
    ("[]", 'not a weave-cut mesh (expected "format": "weave-cut-mesh")'),
    ('{"format": "weave-cut-mesh"}', "unsupported version None; this reads version 1"),
    (doc(version="1"), "unsupported version '1'; this reads version 1"),
    (doc(vertices={}), '"vertices" and "faces" must be lists'),
    (doc(faces=None), '"vertices" and "faces" must be lists'),
    (doc(vertices=[[0]]), "vertex 0 must be [x, y] or [x, y, z], got [0]"),
    (doc(vertices=[[0, 0, 0, 0]]), "vertex 0 must be [x, y] or [x, y, z], got [0, 0, 0, 0]"),
    (doc(vertices=[0, 0]), "vertex 0 must be [x, y] or [x, y, z], got 0"),
    (doc(vertices=[[0, 0], [1, 0, 0]]), "vertex 1 must be [x, y] numbers like vertex 0, got "
                                        "[1, 0, 0]"),
    (doc(vertices=[[0, 0, 0], [1, 0]]), "vertex 1 must be [x, y, z] numbers like vertex 0, got "
                                        "[1, 0]"),
    (doc(vertices=[[0, 0], [1, True]]), "vertex 1 must be [x, y] numbers like vertex 0, got "
                                        "[1, True]"),
    (doc(vertices=[[0, 0], [1, "2"]]), "vertex 1 must be [x, y] numbers like vertex 0"),
    (doc(faces=[[0, 1, 2], [0, 1.0, 2]]), "face 1 must be a list of vertex indices, got "
                                          "[0, 1.0, 2]"),
    (doc(faces=[[0, False, 2]]), "face 0 must be a list of vertex indices, got [0, False, 2]"),
    (doc(faces=[7]), "face 0 must be a list of vertex indices, got 7"),
    (doc(faces=[]), "the mesh has no faces"),
    (doc(vertices=[], faces=[]), "the mesh has no faces"),
    (doc(faces=[[0, 1, 2, 1]]), "face 0 visits vertex 1 more than once"),
    (doc(faces=[[0, 1, 3]]), "face 0 uses vertex 3, out of range 0..2"),
])
def test_json_messages(tmp_path, text, message):
    assert refused(tmp_path, "m.json", text).startswith(message)


def test_json_messages_show_at_most_120_characters(tmp_path):
    vertex = refused(tmp_path, "m.json", doc(vertices=[[0, 0], [1, "x" * 300]]))
    face = refused(tmp_path, "m.json", doc(faces=[[0, 1, "y" * 300]]))
    assert vertex.startswith("vertex 1 must be [x, y] numbers like vertex 0, got [1, 'xxx")
    assert (len(vertex), len(face)) == (120, 120) and face.endswith("yyy")


def test_json_limits_and_surfaces(tmp_path):
    with patch.object(readers, "MAX_FACES", 1):
        assert refused(tmp_path, "m.json", doc(faces=[[0, 1, 2], [0, 2, 1]])) == (
            "2 faces and 3 vertices; weave-cut reads at most 1 faces and 33,554,432 vertices")
        assert read_mesh_text(tmp_path, doc(), "ok.json").n_faces == 1
    with patch.object(readers, "MAX_VERTICES", 2):
        assert refused(tmp_path, "m.json", doc()).startswith("1 faces and 3 vertices; ")
    with patch.object(readers, "MAX_VERTICES", 3):
        assert read_mesh_text(tmp_path, doc(), "ok.json").n_vertices == 3  # at the limit
    assert refused(tmp_path, "m.json", "[" * 100_000 + "]" * 100_000) == (
        "JSON nested too deeply (a mesh needs 3 levels)")
    assert refused(tmp_path, "m.json", doc().replace("[0, 1]]", "[0, 1" + "0" * 400 + "]]")) == (
        "a vertex coordinate is too large for a float")
    assert refused(tmp_path, "m.json", doc().replace("[[0, 1, 2]]", "[[0, 1, " + "9" * 5000 + "]]")) == (
        "a number in the JSON is too large (thousands of digits)")
    surface = read_mesh_text(tmp_path, doc(vertices=[[0, 0, 1], [1, 0, 2], [0, 1, 3.5]]),
                             "s.json")
    assert surface.vertices.tolist() == [[0, 0, 1], [1, 0, 2], [0, 1, 3.5]]
    assert read_mesh_text(tmp_path, doc(vertices=[[0, 0], [1, 0], [0, 1e3]]),
                          "i.json").vertices.dtype == np.float64
    assert refused(tmp_path, "m.json", b'{"a": "\xff"}') == "not a text file (not UTF-8)"


# -- files that are no regular files -----------------------------------------------------------

def test_a_fifo_is_refused_in_process_without_waiting_for_a_writer(tmp_path):
    # test_mesh_io's FIFO test runs weave-cut in a subprocess; this one reads in-process, in a
    # daemon thread so that a reader that blocks fails the test instead of hanging the suite
    import threading

    fifo = tmp_path / "pipe.json"
    os.mkfifo(fifo)
    errors = []

    def read():
        try:
            read_mesh(fifo)
        except MeshFileError as exc:
            errors.append(str(exc))

    thread = threading.Thread(target=read, daemon=True)
    thread.start()
    thread.join(60)
    assert errors == [f"{fifo}: is a FIFO (named pipe); mesh files must be regular files"]


@pytest.mark.skipif(not os.access("/dev/loop0", os.R_OK), reason="no block device to read")
def test_a_block_device_is_refused(tmp_path):
    path = tmp_path / "disk.obj"
    path.symlink_to("/dev/loop0")
    with pytest.raises(MeshFileError, match=rf"^{path}: is a block device; mesh files must be "
                                            "regular files$"):
        read_mesh(path)
