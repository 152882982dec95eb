"""The command line on surfaces: meshes in and out, --project sphere, and one-line refusals
from the commands that draw flat meshes."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.mesh_io import read_valid_mesh


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.mark.parametrize("args", [
    ("subdivide", "cube", "-o", "{tmp}/x.svg"),
    ("subdivide", "{tmp}/ball.obj", "-o", "{tmp}/x.pdf"),
    ("weave", "dodecahedron", "-o", "{tmp}/x.svg"),
    ("puzzle", "cube", "-o", "{tmp}/puzzle"),
    ("convexity", "icosahedron"),
    ("subdivide", "cube", "--scheme", "loop", "-o", "{tmp}/x.obj"),
])
def test_flat_only_commands_refuse_surfaces_in_one_line(tmp_path, args):
    (tmp_path / "ball.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                       "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
    result = run(*(a.format(tmp=tmp_path) for a in args))
    assert result.exit_code in (1, 2)
    errors = [ln for ln in result.output.splitlines() if ln.startswith("Error")]
    assert len(errors) == 1 and "surface" in errors[0], result.output
    assert "Traceback" not in result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ball.obj"]


def test_subdivide_a_solid_to_a_mesh_file_on_the_sphere(tmp_path):
    out = tmp_path / "ball.json"
    result = run("subdivide", "dodecahedron", "--levels", "2", "--project", "sphere", "-o", out)
    assert result.exit_code == 0, result.output
    mesh = read_valid_mesh(out)
    assert (mesh.n_vertices, mesh.n_faces) == (452, 300)
    np.testing.assert_allclose(np.linalg.norm(mesh.vertices, axis=1), 1.0, rtol=1e-12)


def test_project_sphere_refuses_a_flat_input(tmp_path):
    result = run("subdivide", "pentagon", "--project", "sphere", "-o", tmp_path / "x.obj")
    assert result.exit_code == 1
    assert "needs a surface in space" in result.output


@pytest.mark.parametrize("name, angle", [("tetrahedron", 60.0), ("cube", 90.0),
                                         ("octahedron", 60.0), ("dodecahedron", 108.0),
                                         ("icosahedron", 60.0)])
def test_stats_on_a_solid_count_per_eq2_and_keep_euler_2(name, angle):
    result = run("stats", name, "--levels", "2", "--project", "sphere", "--json")
    assert result.exit_code == 0, result.output
    rows = json.loads(result.output)["levels"]
    # the solid's own faces are regular: the angles in space, not a projection of them
    assert rows[0]["min_angle_deg"] == pytest.approx(angle)
    assert rows[0]["max_angle_deg"] == pytest.approx(angle)
    for before, row in zip(rows, rows[1:]):
        assert row["euler_characteristic"] == 2 and row["boundary_edges"] == 0
        corners = sum(int(k) * n for k, n in before["face_degrees"].items())
        assert (row["vertices"], row["edges"], row["faces"]) == (
            before["vertices"] + 2 * before["edges"] + before["faces"],
            3 * before["edges"] + corners, corners)
        assert row["eq2_holds"] and row["nonconvex_faces"] == 0
        assert row["closed_strands"] == row["strands"] == len(row["strand_lengths"])
        assert 0 < min(row["strand_lengths"])


def test_stats_text_names_euler_and_the_loops():
    result = run("stats", "dodecahedron", "--levels", "1")
    assert result.exit_code == 0, result.output
    assert "level 1: V - E + F = 2; eq. (2) holds; 6 strands (6 closed)" in result.output
