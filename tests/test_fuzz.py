"""Bad input of every kind ends in a one-line error with exit status 1 or 2, no traceback,
and no partial or temporary file; interrupted builds leave earlier outputs intact."""

from __future__ import annotations

import json
import os
import pty
import select
import signal
import subprocess
import sys

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.strategies import examples
from weavecut.cli import cli
from weavecut.manifest import MANIFEST

OBJ_CASES = {
    "empty": b"",
    "truncated": b"v 0 0\nv 1 0\nv 0 1\nf 1 2",
    "garbage": bytes(range(256)) * 4,
    "huge-index": b"v 0 0\nv 1 0\nv 0 1\nf 1 2 99999999999999999999999\n",
    "negative-index": b"v 0 0\nv 1 0\nv 0 1\nf -1 -2 -9\n",
    "nan": b"v 0 nan\nv 1 0\nv 0 1\nf 1 2 3\n",
    "inf": b"v 0 inf\nv 1 0\nv 0 1\nf 1 2 3\n",
    "unicode": "v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n\u00e9t\u00e9 1\n".encode(),
    "duplicate-faces": b"v 0 0\nv 1 0\nv 0 1\nf 1 2 3\nf 1 2 3\n",
    "two-corner-face": b"v 0 0\nv 1 0\nf 1 2\n",
    "repeated-corner": b"v 0 0\nv 1 0\nv 0 1\nf 1 2 2 3\n",
    "collinear": b"v 0 0\nv 1 0\nv 2 0\nf 1 2 3\n",
    "z": b"v 0 0 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "bowtie": b"v 0 0\nv 1 -1\nv 1 1\nv -1 1\nv -1 -1\nf 1 2 3\nf 1 4 5\n",
    "overlap": b"v 0 0\nv 2 0\nv 2 2\nv 0 2\nv 1 1\nv 3 1\nv 3 3\nv 1 3\nf 1 2 3 4\nf 5 6 7 8\n",
    "mixed-orientation": b"v 0 0\nv 1 0\nv 2 0\nv 2 1\nv 1 1\nv 0 1\nf 1 2 5 6\nf 2 5 4 3\n",
}

JSON_CASES = {
    "empty": b"",
    "not-json": b"{{{",
    "list": b"[1, 2, 3]",
    "no-faces": json.dumps({"format": "weave-cut-mesh", "version": 1, "vertices": [[0, 0]],
                            "faces": []}).encode(),
    "string-coords": json.dumps({"format": "weave-cut-mesh", "version": 1,
                                 "vertices": [["a", 0]], "faces": [[0, 0, 0]]}).encode(),
    "bool-index": json.dumps({"format": "weave-cut-mesh", "version": 1,
                              "vertices": [[0, 0], [1, 0], [0, 1]],
                              "faces": [[0, True, 2]]}).encode(),
    "huge-index": json.dumps({"format": "weave-cut-mesh", "version": 1,
                              "vertices": [[0, 0], [1, 0], [0, 1]],
                              "faces": [[0, 1, 10**30]]}).encode(),
    "nan": b'{"format": "weave-cut-mesh", "version": 1, "vertices": [[NaN, 0], [1, 0], [0, 1]],'
           b' "faces": [[0, 1, 2]]}',
}


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def assert_clean_failure(result, folder, statuses=(1, 2)):
    assert result.exit_code in statuses, result.output
    assert "Traceback" not in result.output
    lines = [ln for ln in result.output.strip().splitlines() if ln.startswith("Error")]
    assert len(lines) == 1, result.output
    leftovers = [p.name for p in folder.iterdir() if p.name.endswith(".part")
                 or p.suffix in (".svg", ".dxf", ".pdf", ".png")]
    assert not leftovers


@pytest.mark.parametrize("name", sorted(OBJ_CASES))
def test_bad_obj(tmp_path, name):
    path = tmp_path / "in.obj"
    path.write_bytes(OBJ_CASES[name])
    assert_clean_failure(run("subdivide", path, "-o", tmp_path / "out.svg"), tmp_path)


@pytest.mark.parametrize("name", sorted(JSON_CASES))
def test_bad_json(tmp_path, name):
    path = tmp_path / "in.json"
    path.write_bytes(JSON_CASES[name])
    assert_clean_failure(run("subdivide", path, "-o", tmp_path / "out.svg"), tmp_path)


@settings(max_examples=examples(40), deadline=None)
@given(st.binary(max_size=300))
def test_random_bytes_never_crash(tmp_path_factory, data):
    folder = tmp_path_factory.mktemp("fuzz")
    for suffix in (".obj", ".json"):
        path = folder / f"in{suffix}"
        path.write_bytes(data)
        result = run("stats", path)
        assert result.exit_code in (0, 1), result.output
        assert "Traceback" not in result.output and result.exception is None or isinstance(
            result.exception, SystemExit)


@settings(max_examples=examples(40), deadline=None)
@given(st.lists(st.sampled_from(["v 0 0", "v 1 0", "v 0 1", "v 1 1", "f 1 2 3", "f 1 2 4",
                                 "f 2 4 3", "f 3 2 1", "f 1 2", "f 1 5 2", "v 2 2 0",
                                 "# x", "g a", "f -1 -2 -3", "v 1e308 1e308"]), max_size=12))
def test_random_obj_statements_never_crash(tmp_path_factory, lines):
    folder = tmp_path_factory.mktemp("fuzz")
    path = folder / "in.obj"
    path.write_text("\n".join(lines))
    result = run("subdivide", path, "--levels", "2", "-o", folder / "out.json")
    assert result.exit_code in (0, 1), result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)


@pytest.mark.parametrize("args", [
    ["subdivide", "pentagon", "--size", "0", "-o", "{d}/x.svg"],
    ["subdivide", "pentagon", "--size", "-3cm", "-o", "{d}/x.svg"],
    ["subdivide", "pentagon", "--size", "1e99km", "-o", "{d}/x.svg"],
    ["subdivide", "pentagon", "--size", "nan", "-o", "{d}/x.svg"],
    ["subdivide", "pentagon", "--levels", "1000", "-o", "{d}/x.svg"],
    ["subdivide", "pentagon", "--levels", "13", "-o", "{d}/x.svg"],
    ["subdivide", "ngon:99999", "-o", "{d}/x.svg"],
    ["subdivide", "square-grid:0x5", "-o", "{d}/x.svg"],
    ["subdivide", "pentagon", "--chirality", "up", "-o", "{d}/x.svg"],
    ["subdivide", "pentagon", "-o", "{d}/no/such/dir/x.svg"],
    ["subdivide", "pentagon", "-o", "{d}"],
    ["weave", "pentagon", "--palette", "nope", "-o", "{d}/x.svg"],
    ["weave", "pentagon", "--size", "0mm", "-o", "{d}/x.svg"],
    ["stats", "unknown-input"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--kerf", "50mm"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--size", "1mm"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--kerf", "-1mm"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--sheet", "10x10mm", "--mode", "separate"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--material", "nope"],
    ["strands", "square-grid", "--tile-size", "0", "-o", "{d}/s.pdf"],
    ["strands", "square-grid", "--page", "5x5mm", "-o", "{d}/s.pdf"],
    ["strands", "square-grid", "-o", "{d}/s.dxf"],
    ["build", "{d}/missing.toml"],
    ["nope"],
])
def test_bad_options(tmp_path, args):
    assert_clean_failure(run(*[a.format(d=tmp_path) for a in args]), tmp_path)


def test_read_only_existing_file_is_replaced_or_refused_cleanly(tmp_path):
    out = tmp_path / "x.svg"
    out.write_text("old")
    out.chmod(0o444)
    result = run("subdivide", "pentagon", "-o", out)
    # the file is replaced by rename (the folder is writable), never half-written
    assert result.exit_code in (0, 1)
    text = out.read_text()
    assert text == "old" or text.startswith("<svg")
    assert not list(tmp_path.glob(".*part"))


def _started(command: list[str]) -> tuple[subprocess.Popen, int]:
    """Start ``weave-cut`` with stderr on a terminal and return once its progress bar shows,
    i.e. the commands are loaded and the subdivision is under way."""
    main, child = pty.openpty()
    proc = subprocess.Popen([sys.executable, "-m", "weavecut", *command],
                            stdout=subprocess.PIPE, stderr=child)
    os.close(child)
    seen = b""
    while b"levels" not in seen:
        assert select.select([main], [], [], 120)[0], seen
        seen += os.read(main, 4096)
    return proc, main


def _rest(main: int) -> str:
    out = b""
    while True:
        try:
            chunk = os.read(main, 4096)
        except OSError:  # the child end is closed
            break
        if not chunk:
            break
        out += chunk
    os.close(main)
    return out.decode(errors="replace")


@pytest.mark.slow
def test_interrupt_leaves_earlier_outputs_and_no_partial_files(tmp_path):
    """Each signal arrives while level 8 (a minute of work) is being made: the run stops with
    status 130 and one line, leaves no output nor temporary file, and keeps earlier outputs."""
    done = tmp_path / "done.svg"
    assert run("subdivide", "pentagon", "--levels", "2", "-o", done).exit_code == 0
    before = done.read_bytes()
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT):
        proc, main = _started(["subdivide", "pentagon", "--levels", "8",
                               "-o", str(tmp_path / "big.svg")])
        proc.send_signal(sig)
        assert proc.wait(timeout=60) == 130, sig
        err = _rest(main)
        assert "interrupted; no output was left half-written" in err, err
        assert "Traceback" not in err
        assert sorted(p.name for p in tmp_path.iterdir()) == [MANIFEST, "done.svg"]
    assert done.read_bytes() == before


@pytest.mark.slow
def test_same_bytes_across_hash_seeds_for_every_format(tmp_path):
    outputs = {}
    for seed in ("0", "123"):
        folder = tmp_path / seed
        folder.mkdir()
        env = dict(os.environ, PYTHONHASHSEED=seed)
        for suffix in ("svg", "dxf", "pdf", "png"):
            subprocess.run([sys.executable, "-m", "weavecut", "weave", "square-grid:2x2",
                            "--levels", "2", "--outline-level", "1", "-o", f"w.{suffix}"],
                           check=True, env=env, cwd=folder)
            outputs.setdefault(suffix, []).append((folder / f"w.{suffix}").read_bytes())
    for suffix, (a, b) in outputs.items():
        assert a == b, suffix


def _grid_obj(n: int) -> str:
    x, y = np.meshgrid(np.arange(n + 1), np.arange(n + 1))
    verts = "\n".join(f"v {a} {b}" for a, b in zip(x.ravel().tolist(), y.ravel().tolist()))
    i, j = np.meshgrid(np.arange(n), np.arange(n))
    v0 = (j * (n + 1) + i).ravel() + 1
    quads = np.column_stack([v0, v0 + 1, v0 + n + 2, v0 + n + 1])
    faces = "\n".join("f %d %d %d %d" % tuple(q) for q in quads.tolist())
    return verts + "\n" + faces + "\n"


@pytest.mark.slow
def test_a_million_faces_are_read_and_checked(tmp_path):
    text = _grid_obj(1000)
    path = tmp_path / "big.obj"
    path.write_text(text)
    result = run("stats", path, "--levels", "0", "--json")
    assert result.exit_code == 0, result.output
    assert json.loads(result.output)["levels"][0]["faces"] == 1_000_000
    path.write_text(text + "f 1 2 9999999\n")
    result = run("stats", path, "--levels", "0")
    assert result.exit_code == 1 and "line 2002002: face index 9999999" in result.output
