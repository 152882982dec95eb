"""Where non-convex faces occur; the counts agree with `weave-cut stats`."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from weavecut import inputs
from weavecut.analysis import convexity as cv
from weavecut.analysis.stats import level_stats
from weavecut.cli import cli
from weavecut.mesh import Mesh
from weavecut.mesh_geometry import corner_turns
from weavecut.subdivision import subdivide

CASES = [("pentagon", 5, True, "vertex"), ("pentagon", 5, False, "vertex"),
         ("square-grid:3x3", 4, False, "area"), ("ngon:24", 3, True, "area"),
         ("triangulated-ngon:24", 3, False, "vertex")]


@pytest.mark.parametrize("spec,levels,smooth,centre", CASES)
def test_counts_agree_with_stats(spec, levels, smooth, centre):
    h = subdivide(inputs.get(spec), levels, smooth=smooth, centre=centre)
    report = cv.convexity_report(h)
    for t, (row, lv) in enumerate(zip(report, h)):
        stats = level_stats(lv.mesh, t)
        assert row["nonconvex_faces"] == stats["nonconvex_faces"]
        assert row["faces"] == stats["faces"]
        assert row["nonconvex_inner_faces"] + row["nonconvex_boundary_faces"] == \
            row["nonconvex_faces"]
        assert sum(row["reflex_at"].values()) == row["reflex_corners"]
        assert sum(row["reflex_vertex_degrees"].values()) == row["reflex_corners"]
        # independent of angles: a CCW face is non-convex where its boundary turns right
        turns = corner_turns(lv.mesh) < -1e-12 * np.abs(corner_turns(lv.mesh)).max()
        assert row["reflex_corners"] == int(turns.sum())


def test_cli_convexity_matches_cli_stats():
    runner = CliRunner()
    args = ["pentagon", "--levels", "5", "--no-smooth"]
    conv = json.loads(runner.invoke(cli, ["convexity", *args, "--json"]).output)
    stats = json.loads(runner.invoke(cli, ["stats", *args, "--json"]).output)
    assert [r["nonconvex_faces"] for r in conv["levels"]] == \
        [r["nonconvex_faces"] for r in stats["levels"]]
    assert conv["levels"][-1]["nonconvex_faces"] > 0


def test_known_nonconvex_input_is_located():
    # an arrow-head quad (reflex at vertex 2) glued to a quad that fills its notch: one
    # non-convex face (with boundary edges), its reflex corner at an inner input vertex of
    # degree 2
    mesh = Mesh.from_faces([(0, 0), (2, 0), (1, 0.5), (1, 2), (3, 1)],
                           [[0, 1, 2, 3], [1, 4, 3, 2]])
    row = cv.convexity_report(subdivide(mesh, 0))[0]
    assert row["nonconvex_faces"] == 1
    assert row["nonconvex_boundary_faces"] == 1
    assert row["reflex_at"] == {"input inner": 1}
    assert row["reflex_vertex_degrees"] == {"2": 1}


def test_vertex_origins_follow_the_numbering():
    h = subdivide(inputs.get("pentagon"), 2)
    origins = cv.vertex_origins(h)
    assert np.bincount(origins[1]).tolist() == [5, 10, 1]
    assert np.bincount(origins[2]).tolist() == [5, 10 + 2 * 20, 1 + 5]


def test_drawing_highlights_nonconvex_faces():
    h = subdivide(inputs.get("pentagon"), 5, smooth=False)
    from weavecut.figures.subdivision import convexity_drawing

    drawing = convexity_drawing(h[-1].mesh)
    layers = {layer.name: layer for layer in drawing.sheets[0].layers}
    n_bad = cv.convexity_report(h)[-1]["nonconvex_faces"]
    assert layers["nonconvex"].shapes[0].n_polygons == n_bad
    assert layers["reflex-corners"].shapes[0].n_polygons == \
        cv.convexity_report(h)[-1]["reflex_corners"]
    assert "non-convex" in layers["caption"].shapes[0].text


def test_nonconvex_levels_name_count_level_and_place():
    # a measurement made apart from this code: the 24-gon has 72 non-convex faces at level 5, all with their
    # reflex corner at an outer Z vertex of degree 3
    h = subdivide(inputs.get("ngon:24"), 5)
    rows = cv.nonconvex_levels(h)
    assert [(r["level"], r["nonconvex_faces"]) for r in rows] == [(5, 72)]
    assert rows[0]["where"] == [(72, "outer Z vertices of degree 3")]
    assert cv.nonconvex_message(rows[0]) == ("level 5: 72 of 15,000 faces are non-convex "
                                             "(72 at outer Z vertices of degree 3)")
    assert cv.nonconvex_levels(subdivide(inputs.get("pentagon"), 5)) == []


def test_nonconvex_levels_of_another_scheme_and_of_the_input():
    # an arrow-head input, allowed: level 0 is not "produced", so only later levels count
    mesh = Mesh.from_faces([(0, 0), (2, 0), (1, 0.5), (1, 2), (3, 1)],
                           [[0, 1, 2, 3], [1, 4, 3, 2]])
    h = subdivide(mesh, 1, "catmull-clark")
    rows = cv.nonconvex_levels(h)
    assert all(r["level"] >= 1 for r in rows)
    assert cv.nonconvex_levels(h, first=0)[0]["where"] == [(1, "inner vertices of degree 2")]


@pytest.mark.parametrize("command", [
    ["subdivide", "ngon:24", "--levels", "5", "-o", "ng5.obj"],
    ["weave", "ngon:24", "--levels", "5", "--json"],
    ["strands", "triangulated-ngon:6", "--levels", "3", "-o", "s.pdf"],
])
def test_commands_warn_about_nonconvex_output(command, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, ["-q", *command])
    assert result.exit_code == 0, result.output
    assert "warning: level" in result.stderr and "non-convex" in result.stderr
    assert "at outer Z vertices of degree 3" in result.stderr
    if "--json" in command:
        assert json.loads(result.stdout)["nonconvex_faces"] == 72


def test_reading_nonconvex_output_back_explains_the_flag(tmp_path):
    runner = CliRunner()
    out = tmp_path / "ng5.obj"
    runner.invoke(cli, ["subdivide", "ngon:24", "--levels", "5", "-o", str(out)])
    refused = runner.invoke(cli, ["stats", str(out), "--levels", "0"])
    assert refused.exit_code == 1
    assert "--allow-nonconvex" in refused.output and "weave-cut convexity" in refused.output
    accepted = runner.invoke(cli, ["stats", str(out), "--levels", "0", "--allow-nonconvex"])
    assert accepted.exit_code == 0


@pytest.mark.parametrize("spec,levels,smooth", [("ngon:24", 5, True), ("pentagon", 5, False),
                                                ("triangulated-ngon:24", 3, False)])
def test_reflex_corner_ids_in_batches_match_the_angles(spec, levels, smooth, monkeypatch):
    monkeypatch.setattr(cv, "CHUNK", 333)        # many batches of faces
    mesh = subdivide(inputs.get(spec), levels, smooth=smooth)[-1].mesh
    expected = np.flatnonzero(cv.reflex_corners(mesh))
    assert len(expected) > 0
    assert cv.reflex_corner_ids(mesh).tolist() == expected.tolist()
