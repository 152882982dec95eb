"""The analysis commands through click: outputs, JSON shape, one-line errors and exit codes."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.figures import subdivision as figures


def run(*args):
    return CliRunner().invoke(cli, list(args))


def test_fractal_json_and_svg(tmp_path):
    out = tmp_path / "f.svg"
    r = run("fractal", "pentagon", "--levels", "5", "--json", "-o", str(out))
    assert r.exit_code == 0, r.output
    data = json.loads(r.output)
    assert data["alpha_deg"] == pytest.approx(19.1066, abs=1e-4)
    assert max(data["boundary_lsystem_max_error"]) < 1e-13
    assert {row["kind"] for row in data["inner_curves"]} >= {"boundary", "outer-inner",
                                                             "inner-inner"}
    assert out.read_bytes().startswith(b"<svg")


def test_levels_png(tmp_path):
    out = tmp_path / "l.png"
    r = run("levels", "pentagon", "--levels", "5", "--size", "64", "-o", str(out))
    assert r.exit_code == 0, r.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    r = run("levels", "pentagon", "--levels", "6", "--size", "32", "--window", "0,0,0.2,0.2",
            "-o", str(out))
    assert r.exit_code == 0, r.output


@pytest.mark.parametrize("args,code", [
    (["levels", "pentagon", "--size", "8", "--window", "1,1,0,0", "-o", "x.png"], 2),
    (["levels", "pentagon", "--size", "8", "--window", "a,b", "-o", "x.png"], 2),
    (["levels", "pentagon", "--size", "8", "-o", "x.svg"], 2),
    (["fractal", "nosuchinput", "--levels", "2"], 1),
    (["fractal", "pentagon", "--levels", "4", "--curve", "9:0"], 2),
    (["fractal", "pentagon", "--levels", "4", "--curve", "1:999"], 1),
    (["figure", "nosuchfigure", "-o", "x.svg"], 2),
    (["figure", "level-image", "-o", "x.svg"], 2),
    (["convexity", "pentagon", "--levels", "2", "-o", "x.txt"], 2),
])
def test_errors_are_one_line(tmp_path, monkeypatch, args, code):
    monkeypatch.chdir(tmp_path)
    r = run(*args)
    assert r.exit_code == code, r.output
    assert "Traceback" not in r.output
    assert list(tmp_path.iterdir()) == []   # nothing half-written


def test_figure_list_names_every_figure():
    r = run("figure", "--list")
    assert r.exit_code == 0
    for name in figures.FIGURES:
        assert name in r.output


@pytest.mark.parametrize("name", ["z-triplet", "operations", "first-steps", "smoothing"])
def test_small_figures_build(tmp_path, name):
    out = tmp_path / f"{name}.svg"
    r = run("figure", name, "-o", str(out))
    assert r.exit_code == 0, r.output
    assert b"<svg" in out.read_bytes()


def test_paper_input_has_two_inner_and_three_outer_vertices_in_view():
    import numpy as np

    from weavecut.mesh import outer_vertices

    mesh = figures.paper_input()
    seen = figures._inside(mesh.vertices, figures.PAPER_VIEW)
    outer = outer_vertices(mesh)
    assert int((seen & ~outer).sum()) == 2 and int((seen & outer).sum()) == 3
    assert np.all(mesh.vertices[seen & outer][:, 0] > 0.9)  # the boundary is to the right
