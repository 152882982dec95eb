"""Disconnected and sliver meshes in the puzzle and the paper model: a clear error naming the
face or the parts, never a GEOS exception; NaN coordinates from --centre area are refused."""

from __future__ import annotations

import pytest

from .helpers import refused, run

TWO_SQUARES = "v 0 0\nv 1 0\nv 1 1\nv 0 1\nv 3 0\nv 4 0\nv 4 1\nv 3 1\nf 1 2 3 4\nf 5 6 7 8\n"
SLIVER = "v 0 0\nv 1 0\nv 1 1e-7\nv 0 1e-7\nf 1 2 3 4\n"
SLIVER_PENTAGON = "v 0 0\nv 1 0\nv 1 1e-9\nv 0.5 2e-9\nv 0 1e-9\nf 1 2 3 4 5\n"
# a sliver beside a good square: the thin face is named
SLIVER_BESIDE = "v 0 0\nv 1 0\nv 1 1\nv 0 1\nv 0 1.000001\nv 1 1.000001\nf 1 2 3 4\nf 4 3 6 5\n"


@pytest.mark.parametrize("text,needles", [
    (TWO_SQUARES, ["2 separate parts", "the puzzle"]),
    (SLIVER, ["face 1 is a sliver", "the puzzle"]),
    (SLIVER_PENTAGON, ["face 1 is a sliver"]),
    (SLIVER_BESIDE, ["face 2 is a sliver"]),
])
def test_puzzle(tmp_path, text, needles):
    mesh = tmp_path / "m.obj"
    mesh.write_text(text)
    refused(run("puzzle", mesh, "--levels", "2", "-o", tmp_path / "pz"), *needles)
    assert not (tmp_path / "pz").exists()


@pytest.mark.parametrize("text", [SLIVER, SLIVER_PENTAGON, SLIVER_BESIDE])
def test_strands(tmp_path, text):
    mesh = tmp_path / "m.obj"
    mesh.write_text(text)
    refused(run("strands", mesh, "-o", tmp_path / "s.pdf"), "sliver", "the paper model")
    assert not (tmp_path / "s.pdf").exists()


def test_strands_of_two_parts_still_works(tmp_path):
    mesh = tmp_path / "m.obj"
    mesh.write_text(TWO_SQUARES)
    assert run("strands", mesh, "-o", tmp_path / "s.pdf").exit_code == 0


@pytest.mark.parametrize("command", ["subdivide", "convexity", "stats", "weave"])
def test_area_centres_of_tiny_faces_are_refused_not_written_as_nan(tmp_path, command):
    mesh = tmp_path / "tiny.obj"
    mesh.write_text("v 0 0\nv 1e-155 0\nv 1e-155 1e-155\nv 0 1e-155\nf 1 2 3 4\n")
    args = [command, mesh, "--levels", "3", "--centre", "area"]
    args += ["-o", tmp_path / "out.json"] if command == "subdivide" else ["--json"]
    result = run(*args)
    refused(result, "not finite", "--centre vertex")
    assert "NaN" not in result.output and not (tmp_path / "out.json").exists()
