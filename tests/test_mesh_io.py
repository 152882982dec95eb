"""OBJ and JSON round trips and the errors bad files give."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from unittest.mock import patch
from decimal import ROUND_CEILING, ROUND_FLOOR, Context, Decimal
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from tests import obj_reference
from tests.strategies import examples, any_mesh
from weavecut import inputs
from weavecut.readers import obj, obj_tokens
from weavecut.errors import MeshError, MeshFileError
from weavecut.mesh_geometry import signed_areas
from weavecut.mesh_io import MAX_BYTES, obj_text, read_mesh, read_valid_mesh, write_mesh


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


# -- the vectorised OBJ reader against a line-by-line oracle ---------------------------------

VERTICES = ["v 0 0", "v 1 0 0", "v 0 1", "v 1 1 0", "v 0.5 -0.25", "v 2 0 0 1", "v 1_0 2",
            "\tv\t2\t0", "v 0 0 # c", "v 3 1e-3"]
READABLE = VERTICES + [
    "f 1 2 3", "f -1 -2 -3", "f 1/1 2/2/2 3//3", "f 1 2 3 4", "f 3 2 1", "f -3/1 -1 -2",
    "f 0001 2 3", "f +1 2 3", "f 4 5 6", "f 2 -1 -3 1", "vt 0 0", "vn 0 0 1",
    "# comment", "", "   ", "o x", "s off", "g a b", "f 1 2 3 # tail", "l 1 2", "f 1 2 3\x0b4",
]
UNREADABLE = [
    "v 1", "v 1 2 3 4 5", "v x 1", "v nan 0", "v 1e400 0", "v 0 0 inf", "v 0 0 1", "v 2 5 1",
    "f 0 1 2", "f 1 2", "f", "f 1 2 a", "f 1 2 1.5", "f 99999999999999999999 1 2", "f /1 2 3",
    "f 1 1 2", "f 9 1 2", "f 00000000000000000001 2 3", "bogus 1", "v 0\x00 1", "\x01bad",
    "é 1", "f 1 2 " + "9" * 30, "f 1 " + "9" * 20 + "x 2", "f -" + "1" * 17 + " 1 2",
    "f 12345678901234 1 2", "f " + "7" * 50 + " 1 " + "8" * 25, "f 1 2 " + "9" * 24 + "/5",
    "v 0 1?", "v 0.:5 1", "f 1 2 :3", "f 1 2 3>",  # the bytes just after "9"
    "f 1 2 3-", "f 1-2 3", "f 1 +-2 3", "f 1 2 3+",
]


@settings(max_examples=examples(300), deadline=None)
@given(st.lists(st.sampled_from(VERTICES), min_size=3, max_size=6),
       st.lists(st.sampled_from(READABLE * 8 + UNREADABLE), max_size=12),
       st.lists(st.sampled_from(["\n", "\r\n", "\r"]), min_size=18, max_size=18))
def test_obj_reader_agrees_with_a_line_by_line_reading(tmp_path_factory, head, body, ends):
    agrees_with_the_oracle(tmp_path_factory, head + body, ends)


FACES = [line for line in READABLE + UNREADABLE if line.startswith("f")]


@settings(max_examples=examples(200), deadline=None)
@given(st.lists(st.sampled_from(FACES[:10] * 6 + FACES), min_size=1, max_size=6))
def test_runs_of_face_lines_agree_with_a_line_by_line_reading(tmp_path_factory, faces):
    # f lines one after another go to numpy's whole-number parser when they can
    agrees_with_the_oracle(tmp_path_factory, VERTICES[:6] + faces, ["\n"] * 12)


def agrees_with_the_oracle(tmp_path_factory, lines, ends):
    data = "".join(a + b for a, b in zip(lines, ends)).encode()
    path = tmp_path_factory.mktemp("obj") / "m.obj"
    path.write_bytes(data)
    notes = []
    try:
        want = obj_reference.read(data)
    except obj_reference.Refused as exc:
        with pytest.raises(MeshError) as got:
            read_mesh(path, note=notes.append)
        assert str(got.value) == f"{path}: {exc}"
        return None
    mesh = read_mesh(path, note=notes.append)
    assert mesh.vertices.tobytes() == want[0].tobytes()
    assert mesh.faces() == want[1]
    assert notes == ([f"{path}: {want[2]}"] if want[2] else [])
    return mesh


@settings(max_examples=examples(60), deadline=None)
@given(any_mesh, st.sampled_from([None, *UNREADABLE, "v 0 0", "f 1 2 3 4 5 6 7 8 9 10 11 12"]),
       st.integers(0, 10**6), st.sampled_from([64, 512, 2**18]))
def test_regular_and_irregular_layouts_read_alike(tmp_path_factory, mesh, stray, where, chunk):
    # the reader has fast paths for a regular file (no blank line or run of spaces, x y z on
    # every v line, face indices of vertices read before) and a general one; the same
    # statements laid out both ways read alike, and as the line-by-line oracle reads them,
    # with pieces ending anywhere
    lines = obj_text(mesh).splitlines()
    if stray is not None:
        lines.insert(where % (len(lines) + 1), stray)
    irregular = [" " + line.replace(" ", "  ") + "\n" for line in lines]
    with patch.object(obj, "CHUNK", chunk):
        read = [agrees_with_the_oracle(tmp_path_factory, lines, ["\n"] * len(lines)),
                agrees_with_the_oracle(tmp_path_factory, irregular, ["\n"] * len(lines))]
    if read[0] is not None:
        assert read[0].vertices.tobytes() == read[1].vertices.tobytes()
        assert read[0].faces() == read[1].faces()
        assert stray is not None or read[0].faces() == mesh.faces()


def test_obj_index_rules(tmp_path):
    path = tmp_path / "m.obj"
    # negative indices count back from the last vertex read so far, not from the end
    path.write_text("v 0 0\nv 1 0\nv 0 1\nf -3 -2 -1\nv 1 1\nf -3 -1 -2\nf 2 4 3\n")
    assert read_mesh(path).faces() == [[0, 1, 2], [1, 3, 2], [1, 3, 2]]
    path.write_text("v 0 0\nv 1 0\nv 0 1\nf 0 1 2\n")
    with pytest.raises(MeshFileError, match="line 4: face index 0 refers to no vertex"):
        read_mesh(path)
    path.write_text("v 0 0\nv 1 0\nf -1 -2 -3\nv 0 1\n")  # vertex 3 comes too late
    with pytest.raises(MeshFileError, match=r"line 3: face index -3 refers to no vertex \(2 "):
        read_mesh(path)
    path.write_text("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\nf 1 2 4\nv 1 1\n")
    with pytest.raises(MeshFileError, match="line 5: face index 4"):
        read_mesh(path)


def test_mixed_degrees_slashes_and_big_files_agree_with_the_oracle(tmp_path):
    rng = np.random.default_rng(7)
    mesh = inputs.get("tiling-8-4:30x30")  # octagons and squares
    text = obj_text(mesh)
    # the same mesh with texture/normal indices and stray whitespace, as exporters write it
    text = re.sub(r"^f (.*)$", lambda m: "f " + "  ".join(
        f"{i}/{i}/{int(rng.integers(1, 9))}" for i in m.group(1).split()), text, flags=re.M)
    path = tmp_path / "m.obj"
    path.write_text(text.replace("\nv ", "\nv\t"))
    back = read_mesh(path)
    assert back.faces() == mesh.faces() == obj_reference.read(path.read_bytes())[1]
    np.testing.assert_array_equal(back.vertices, mesh.vertices)


@st.composite
def decimals(draw):
    """Plain decimals as OBJ writers print them, and ones a hair from halfway between two
    doubles (where rounding twice, once to long double, would go wrong)."""
    if draw(st.booleans()):
        whole = draw(st.text("0123456789", max_size=25))
        part = draw(st.one_of(st.none(), st.text("0123456789", max_size=25)))
        sign = draw(st.sampled_from(["", "-", "+"]))
        return sign + whole + ("" if part is None else "." + part) or "."
    x = draw(st.integers(2**52, 2**53 - 1)) * 2.0 ** draw(st.integers(-60, 0))
    halfway = Fraction(x) + Fraction(float(np.spacing(x))) / 2
    digits = draw(st.integers(16, 19))
    near = Context(prec=digits, rounding=draw(st.sampled_from([ROUND_FLOOR, ROUND_CEILING])))
    exact = Decimal(halfway.numerator) / Decimal(halfway.denominator)
    return format(near.create_decimal(exact), "f")


def parses(token: str) -> bool:
    try:
        float(token)
        return True
    except ValueError:
        return False


@settings(max_examples=examples(200))
@given(st.lists(decimals(), min_size=3, max_size=40), st.sampled_from([8, 64, 2**18]),
       st.booleans())
@example(["1" * 25, "2" * 18 + ".5", "12345678.5", "1234567.5", "-0.0", "+.5", "5.", "-0",
          "9007199254740993", "0.30000000000000004", "123.4567890123456789"], 2**18, True)
def test_decimals_are_read_as_python_reads_them(tmp_path_factory, tokens, chunk, x87):
    # pieces of `chunk` bytes: lines and the vertices before a face cross the pieces' ends;
    # without x87 long doubles (as on ARM) numpy converts the decimals of over 2**53
    path = tmp_path_factory.mktemp("obj") / "m.obj"
    path.write_text("".join(f"v {t} 0 0\n" for t in tokens) + "f 1 2 3\nf -1 -2 -3\n")
    bad = [i for i, t in enumerate(tokens) if not parses(t)]
    with patch.object(obj, "CHUNK", chunk), patch.object(obj_tokens, "_X87", x87 and obj_tokens._X87):
        if bad:
            with pytest.raises(MeshFileError, match=f"line {bad[0] + 1}: vertex coordinates"):
                read_mesh(path)
            return
        mesh = read_mesh(path)
    assert mesh.vertices[:, 0].tolist() == [float(t) for t in tokens]
    assert [str(x) for x in mesh.vertices[:, 0]] == [repr(float(t)) for t in tokens]  # -0.0
    assert mesh.faces() == [[0, 1, 2], [len(tokens) - 1, len(tokens) - 2, len(tokens) - 3]]


# -- flat meshes in any axis-aligned plane ----------------------------------------------------

BLENDER_PLANE = """# Blender 4.2 OBJ File: ''
o Plane
v -1.000000 0.000000 1.000000
v 1.000000 0.000000 1.000000
v -1.000000 0.000000 -1.000000
v 1.000000 0.000000 -1.000000
vn -0.0000 1.0000 -0.0000
vt 0.000000 0.000000
vt 1.000000 0.000000
vt 1.000000 1.000000
vt 0.000000 1.000000
s 0
f 1/1/1 2/2/1 4/3/1 3/4/1
"""


def test_blender_plane_is_read_in_xz_seen_from_above(tmp_path):
    path = tmp_path / "plane.obj"
    path.write_text(BLENDER_PLANE)
    notes = []
    mesh = read_valid_mesh(path, note=notes.append)
    assert notes == [f"{path}: all vertices have y = 0.0; read in the xz-plane as (x, -z), "
                     "seen from +y"]
    # Blender's ground plane seen from above: (x, -z), counter-clockwise, not mirrored
    np.testing.assert_array_equal(mesh.vertices, [[-1, -1], [1, -1], [-1, 1], [1, 1]])
    assert mesh.faces() == [[0, 1, 3, 2]] and signed_areas(mesh)[0] == 4.0


@pytest.mark.parametrize("plane, note", [
    ("{a} {b} 0", ""),
    ("{a} {b} 2.5", "all vertices have z = 2.5; read in the xy-plane as (x, y)"),
    ("{a} -3 {c}", "all vertices have y = -3.0; read in the xz-plane as (x, -z), seen from +y"),
    ("7 {a} {b}", "all vertices have x = 7.0; read in the yz-plane as (y, z), seen from +x"),
])
def test_flat_meshes_in_every_axis_aligned_plane(tmp_path, plane, note):
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    text = "".join("v " + plane.format(a=a, b=b, c=-b) + "\n" for a, b in square)
    path = tmp_path / "sq.obj"
    path.write_text(text + "f 1 2 3 4\n")
    notes = []
    mesh = read_valid_mesh(path, note=notes.append)
    assert notes == ([f"{path}: {note}"] if note else [])
    assert mesh.n_faces == 1 and signed_areas(mesh)[0] == 1.0


def test_a_mesh_that_is_not_flat_is_read_as_a_surface(tmp_path):
    path = tmp_path / "tilted.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 1\nf 1 2 3\n")
    np.testing.assert_array_equal(read_mesh(path).vertices, [[0, 0, 0], [1, 0, 0], [0, 1, 1]])


# -- messages count as the file does -----------------------------------------------------------

@pytest.mark.parametrize("text, message", [
    ("v 0 0\nv 2 0\nv 2 2\nv 1 0.5\nv 0 2\n# a dent\nf 1 2 3 4 5\n",
     "face 1 (line 7) is not convex at vertex 4"),
    ("v 0 0\nv 1 0\nv 2 0\nv 2 1\nv 1 1\nv 0 1\nf 1 2 5 6\nf 2 5 4 3\n",
     "face 2 (line 8) is clockwise while others are counter-clockwise"),
    ("v 0 0\nv 1 0\nv 0 1\nf 1 2 2 3\n", "face 1 (line 4) visits vertex 2 more than once"),
    ("v 0 0\nv 1 0\nf 1 2\n", "face 1 (line 3) has 2 corner"),
    ("v 0 0\nv 1 0\nv 2 0\nf 1 2 3\n", "face 1 (line 4) has zero area"),
    ("v 0 0\nv 1 0\nv 0.5 1\nv 0.5 2\nf 1 2 3\nf 1 2 4\n",
     "edge (1, 2) runs the same way in face 1 (line 5) and face 2 (line 6)"),
    ("v 0 0\nv 1 -1\nv 1 1\nv -1 1\nv -1 -1\nf 1 2 3\nf 1 4 5\n",
     "vertex 1 joins 2 separate fans"),
    ("v 0 0\nv 4 0\nv 4 4\nv 0 4\nv 1 1\nv 2 1\nv 2 2\nv 1 2\nf 1 2 3 4\nf 5 6 7 8\n",
     "vertex 5 lies inside face 1 (line 9)"),
])
def test_obj_messages_are_one_based_with_lines_and_the_file(tmp_path, text, message):
    path = tmp_path / "in.obj"
    path.write_text(text)
    with pytest.raises(MeshError) as error:
        read_valid_mesh(path)
    assert str(error.value).startswith(f"{path}: {message}")


def test_json_messages_stay_zero_based_as_the_file_counts(tmp_path):
    path = tmp_path / "in.json"
    doc = {"format": "weave-cut-mesh", "version": 1,
           "vertices": [[0, 0], [2, 0], [2, 2], [1, 0.5], [0, 2]], "faces": [[0, 1, 2, 3, 4]]}
    path.write_text(json.dumps(doc))
    with pytest.raises(MeshError, match=f"^{re.escape(str(path))}: face 0 is not convex at "
                                        "vertex 3"):
        read_valid_mesh(path)


# -- bounded inputs ---------------------------------------------------------------------------

def test_fifo_is_refused_at_once(tmp_path):
    fifo = tmp_path / "pipe.obj"
    os.mkfifo(fifo)  # no writer: opening it for reading the usual way would block forever
    result = subprocess.run([sys.executable, "-m", "weavecut", "stats", str(fifo)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 1
    assert f"{fifo}: is a FIFO (named pipe); mesh files must be regular files" in result.stderr


def test_devices_and_directories_are_refused(tmp_path):
    zero = tmp_path / "zero.obj"
    zero.symlink_to("/dev/zero")  # read until memory runs out, before
    with pytest.raises(MeshFileError, match="is a character device"):
        read_mesh(zero)
    folder = tmp_path / "folder.json"
    folder.mkdir()
    with pytest.raises(MeshFileError, match="is a directory"):
        read_mesh(folder)


@pytest.mark.parametrize("suffix", [".obj", ".json"])
def test_huge_files_are_refused_before_reading(tmp_path, suffix):
    path = tmp_path / f"huge{suffix}"
    with open(path, "wb") as f:
        f.truncate(MAX_BYTES[suffix] + 1)  # sparse: takes no disk space
    with pytest.raises(MeshFileError, match=r"bytes is more than the [0-9,]+ MiB weave-cut reads"):
        read_mesh(path)


@pytest.mark.parametrize("text, message", [
    ("[" * 100_000 + "]" * 100_000, "nested too deeply"),
    ('{"format": "weave-cut-mesh", "version": 1, "vertices": [[0, 0], [1, 0], [0, 1]], '
     '"faces": [[0, 1, ' + "9" * 5000 + "]]}", "a number in the JSON is too large"),
    ('{"format": "weave-cut-mesh", "version": 1, "vertices": [[0, 0], [1, 0], [0, '
     + "9" * 400 + ']], "faces": [[0, 1, 2]]}', "too large for a float"),
    ('{"format": "weave-cut-mesh", "version": 1, "vertices": [[0, 0], [1, 0], [0, 1]], '
     '"faces": [[0, 1, ' + "9" * 40 + "]]}", "integers in range"),
    ('{"format": "weave-cut-mesh", "version": 1, "vertices": [[0, 0], [1, 0], [0, 1e999]], '
     '"faces": [[0, 1, 2]]}', "non-finite"),
])
def test_json_depth_and_number_sizes_are_bounded(tmp_path, text, message):
    path = tmp_path / "m.json"
    path.write_text(text)
    with pytest.raises(MeshError, match=message):
        read_mesh(path)


def test_control_characters_are_no_numbers(tmp_path):
    path = tmp_path / "m.obj"
    path.write_bytes(b"v 0 0\nv 1\x00 0\nv 0 1\nf 1 2 3\n")
    with pytest.raises(MeshFileError, match="line 2: vertex coordinates must be numbers"):
        read_mesh(path)
    path.write_bytes(b"v 0 0\nv 1 0\nv 0 1\nf 1 2 3\x01\n")
    with pytest.raises(MeshFileError, match="line 4: face indices must be whole numbers"):
        read_mesh(path)


def test_hostile_files_fail_in_one_line_in_the_cli(tmp_path):
    from click.testing import CliRunner

    from weavecut.cli import cli

    (tmp_path / "zero.obj").symlink_to("/dev/zero")
    (tmp_path / "folder.obj").mkdir()
    with open(tmp_path / "huge.json", "wb") as f:
        f.truncate(MAX_BYTES[".json"] + 1)
    (tmp_path / "deep.json").write_text("[" * 50_000)
    (tmp_path / "digits.json").write_text('{"a": ' + "1" * 10_000 + "}")
    (tmp_path / "bytes.obj").write_bytes(b"v 0 0\nv 1 0\nv 0 1\nf 1 2 3\x00\n")
    for name in ("zero.obj", "folder.obj", "huge.json", "deep.json", "digits.json",
                 "bytes.obj"):
        result = CliRunner().invoke(cli, ["stats", str(tmp_path / name)])
        assert result.exit_code == 1, (name, result.output)
        assert result.output.startswith(f"Error: {tmp_path / name}: "), result.output
        assert len(result.output.strip().splitlines()) == 1 and "internal" not in result.output


@given(st.lists(st.binary(min_size=8, max_size=8), min_size=1, max_size=40),
       st.sampled_from([ord("."), ord(" "), 0, 0x80, 0xFF]))
def test_first_byte_finds_the_lowest_byte_equal_to_the_one_sought(chunks, byte):
    """The SWAR search against a byte-by-byte look (little-endian: position 0 is the word's
    lowest byte); 8 where no byte of the word is the one sought."""
    from weavecut.readers.obj_tokens import _first_byte
    words = np.frombuffer(b"".join(chunks), dtype="<u8").copy()
    want = [next((i for i, b in enumerate(c) if b == byte), 8) for c in chunks]
    assert _first_byte(words, byte).tolist() == want


@given(st.lists(st.tuples(st.sampled_from(["", "-", "+"]), st.integers(0, 9_999_999),
                          st.text("0123456789", max_size=8)), min_size=1, max_size=30))
def test_plain_decimals_are_converted_by_the_fast_path_exactly(numbers):
    """Plain decimals (a sign, 1-7 digits before the point, up to 8 after: at most 15 digits,
    under 2**53) are all converted by the fast path, each to the double Python's float gives:
    the digit path is the reader's speed, so falling back to numpy for them is a fault too."""
    from weavecut.readers.obj_tokens import Tokens
    texts = [f"{s}{w}.{f}" if f else f"{s}{w}" for s, w, f in numbers]
    tokens = Tokens(" ".join(texts).encode())
    values, plain = tokens._decimals(tokens.start, tokens.end)
    assert plain.all(), [t for t, p in zip(texts, plain) if not p]
    assert values.tolist() == [float(t) for t in texts]


def _oracle_tokens(data: bytes, lines_before: int, comments: bool):
    """A plain-Python split of an OBJ text: (tokens, first token of each kept line, its line
    number, tokens on it, line ends), with Tokens' rules spelt out byte by byte."""
    text = bytearray(data if data.endswith(b"\n") else data + b"\n")
    for i, b in enumerate(text):
        if b == 13:
            text[i] = 32 if text[i + 1] == 10 else 10
        elif b in (9, 11, 12):
            text[i] = 32
        elif b < 32 and b != 10:
            text[i] = 127
    lines = bytes(text).split(b"\n")[:-1]
    tokens, first, number, count = [], [], [], []
    for n, line in enumerate(lines):
        if comments:
            line = line.split(b"#")[0]
        words = [w for w in line.split(b" ") if w]
        if words:
            first.append(len(tokens))
            number.append(n + 1 + lines_before)
            count.append(len(words))
            tokens += words
    return tokens, first, number, count, len(lines) - (not data.endswith(b"\n"))


@settings(max_examples=300)
@given(st.lists(st.sampled_from([b"v", b"1", b"-2.5", b"#", b" ", b"  ", b"\t", b"\n", b"\r",
                                 b"\r\n", b"\x01", b"\x0b", b"\x0c", b"\x7f"]), max_size=40),
       st.integers(0, 3), st.booleans())
@example([b"v", b" ", b"1", b"\n", b"f", b"\n"], 0, True)
@example([b"v", b" ", b"1"], 2, False)
@example([b"\n", b"\n"], 0, True)
def test_tokens_split_like_a_plain_python_split(parts, lines_before, comments):
    """Tokens (both its fast path for texts of single spaces and its general one) against a
    byte-by-byte split: the same tokens, first tokens, line numbers, counts and line ends."""
    from weavecut.readers.obj_tokens import Tokens
    data = b"".join(parts)
    tokens = Tokens(data, lines_before, comments)
    words, first, number, count, n_lines = _oracle_tokens(data, lines_before, comments)
    got = [tokens.buf[a:b].tobytes() for a, b in zip(tokens.start.tolist(), tokens.end.tolist())]
    assert got == words
    assert tokens.first.tolist() == first
    assert tokens.line.tolist() == number
    assert tokens.count.tolist() == count
    assert tokens.n_lines == n_lines


@given(st.lists(st.sampled_from([b"v", b"1", b"-2.5", b"#", b" ", b"  ", b"\n"]), max_size=30))
def test_tokens_leave_texts_of_spaces_and_line_feeds_as_they_are(parts):
    """A text whose only bytes below 33 are spaces and line feeds skips the control-byte pass
    (the common case, kept fast), and comments are blanked by default."""
    from weavecut.readers.obj_tokens import Tokens
    data = b"".join(parts)
    with patch.object(obj_tokens, "_normalise_controls", side_effect=AssertionError("normalised")):
        tokens = Tokens(data)
    assert b"#" not in tokens.buf.tobytes()
    assert Tokens(b"v 1\n").line.tolist() == [1]  # lines count from 1 by default
