"""What used to end in an internal error: surfaces in space with a degenerate face or a vertex
in no face (NaN corners after the first smoothing; once "SVD did not converge"), and a
closed stdout (a traceback from the flush at exit). Each is now one line."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import weavecut
from weavecut import inputs

from .helpers import files_under, refused, run, well_formed_xml

OCTAHEDRON = ("v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
              "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n")
CUBE_VERTICES = ("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n")
CUBE_FACES = "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
SURFACES = {
    # vertex 9 sits on vertex 6: the top and front faces have an edge of no length
    "coincident": (CUBE_VERTICES + "v 1 0 1\n" + CUBE_FACES.replace("f 5 6 7 8", "f 5 9 6 7 8")
                   .replace("f 1 2 6 5", "f 1 2 6 9 5"),
                   "face 2 (line 11) has an edge of zero length: edge (9, 6) joins two vertices "
                   "at one point"),
    # a seventh vertex that no face uses (a duplicate of vertex 1)
    "unused": (OCTAHEDRON.replace("f 1 3 5", "v 1 0 0\nf 1 3 5"), "vertex 7 is in no face"),
    # the apex moved onto the middle of an edge: a face of zero area
    "zero-area": (OCTAHEDRON.replace("v 0 0 1\n", "v 0.5 0.5 0\n"),
                  "face 1 (line 7) has zero area"),
}
COMMANDS = [["strands", "{m}", "-o", "{d}/s.pdf"],
            ["strands", "{m}", "--project", "sphere", "-o", "{d}/s.pdf"],
            ["weave", "{m}", "--levels", "2", "--json"],
            ["weave", "{m}", "--levels", "1", "-o", "{d}/w.glb"],
            ["subdivide", "{m}", "--levels", "2", "-o", "{d}/s.obj"]]


@pytest.mark.parametrize("command", COMMANDS,
                         ids=lambda c: " ".join(a for a in c if "{" not in a))
@pytest.mark.parametrize("kind", sorted(SURFACES))
def test_degenerate_surfaces_are_refused(tmp_path, kind, command):
    text, needle = SURFACES[kind]
    mesh = tmp_path / "in" / "m.obj"
    mesh.parent.mkdir()
    mesh.write_text(text)
    out = tmp_path / "out"
    out.mkdir()
    refused(run(*[a.format(m=mesh, d=out) for a in command]), f"m.obj: {needle}")
    assert files_under(out) == set()


def test_the_cube_itself_is_fine(tmp_path):
    mesh = tmp_path / "cube.obj"
    mesh.write_text(CUBE_VERTICES + CUBE_FACES)
    assert run("weave", mesh, "--levels", "2", "--json").exit_code == 0


SOLIDS = ["tetrahedron", "cube", "octahedron", "dodecahedron", "icosahedron"]


def _obj(vertices, mesh) -> str:
    lines = [f"v {float(x)!r} {float(y)!r} {float(z)!r}" for x, y, z in vertices]
    fo, fi = mesh.face_offsets, mesh.face_indices
    lines += ["f " + " ".join(str(int(i) + 1) for i in fi[fo[f]:fo[f + 1]])
              for f in range(mesh.n_faces)]
    return "\n".join(lines) + "\n"


@settings(max_examples=max(5, settings.default.max_examples // 4),
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(name=st.sampled_from(SOLIDS), data=st.data(),
       move=st.sampled_from(["onto", "between", "centre", "near", "scale"]),
       command=st.sampled_from([["weave", "--levels", "2", "--json"],
                                ["subdivide", "--levels", "2", "-o", "x.obj"]]))
def test_a_moved_vertex_never_makes_an_internal_error(tmp_path, name, data, move, command):
    """One vertex of a solid moved onto another, between two, to the centre, a hair from
    another, or scaled: the command works or refuses in one line."""
    mesh = inputs.get(name)
    v = mesh.vertices.copy()
    i, j, k = (data.draw(st.integers(0, len(v) - 1)) for _ in range(3))
    v[i] = {"onto": v[j], "between": (v[j] + v[k]) / 2, "centre": v.mean(axis=0),
            "near": v[j] + 1e-9, "scale": v[i] * data.draw(st.sampled_from([1e-3, 0.5, 10]))
            }[move]
    path = tmp_path / "m.obj"
    path.write_text(_obj(v, mesh))
    args = [command[0], path, *command[1:]]
    if "-o" in args:
        args[-1] = tmp_path / args[-1]
    result = run(*args)
    if result.exit_code != 0:
        refused(result)


# -- a closed stdout ----------------------------------------------------------------------------

def _closed(args) -> subprocess.CompletedProcess:
    """``weave-cut ARGS >&-``."""
    env = {**os.environ, "PYTHONPATH": str(Path(weavecut.__file__).parents[1])}
    return subprocess.run([sys.executable, "-m", "weavecut", *args], env=env,
                          preexec_fn=lambda: os.close(1), stderr=subprocess.PIPE, text=True,
                          timeout=120)


@pytest.mark.parametrize("args", [["inputs"], ["inputs", "--json"], ["--help"],
                                  ["stats", "pentagon", "--levels", "2"]])
def test_closed_stdout_is_one_line(args):
    proc = _closed(args)
    assert proc.returncode == 1
    assert proc.stderr == "weave-cut: error: cannot write the output: stdout is closed\n"


def test_closed_stdout_takes_no_file_descriptor_of_an_output(tmp_path):
    """With -q nothing goes to stdout: the command works, and its file is whole (descriptor 1
    was never handed to it)."""
    proc = _closed(["-q", "subdivide", "pentagon", "--levels", "2", "-o", tmp_path / "x.svg"])
    assert (proc.returncode, proc.stderr) == (0, "")
    assert well_formed_xml(tmp_path / "x.svg").tag.endswith("svg")


def test_closed_pipe_is_quiet():
    """``weave-cut inputs | head -c0``: the reader is gone before anything is written."""
    env = {**os.environ, "PYTHONPATH": str(Path(weavecut.__file__).parents[1])}
    with subprocess.Popen([sys.executable, "-m", "weavecut", "inputs"], env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as proc:
        proc.stdout.close()
        err = proc.stderr.read()
    assert proc.returncode == 1
    assert "Traceback" not in err and len(err.splitlines()) <= 1, err
