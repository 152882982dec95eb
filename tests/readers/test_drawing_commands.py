"""Commands take drawings like any other INPUT: weave, subdivide, strands, stats and recipes."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from click.testing import CliRunner

from weavecut.cli import cli

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def run(*args: str):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_subdivide_a_drawn_mesh_counts_from_its_faces(tmp_path):
    """One snub step gives one pentagon per corner: the tiles have 6 + 6 x 4 + 6 x 3 = 48."""
    out = tmp_path / "tiles.json"
    result = run("subdivide", EXAMPLES / "tiles.svg", "--levels", 1, "-o", out)
    assert result.exit_code == 0, result.output
    assert len(json.loads(out.read_text())["faces"]) == 48
    assert "13 faces, 18 vertices" in result.output  # the reading report (stderr)


def test_subdivide_a_dxf_layer(tmp_path):
    out = tmp_path / "grid.json"
    result = run("subdivide", EXAMPLES / "plate.dxf", "--layer", "GRID", "--levels", 1,
                 "-o", out)
    assert result.exit_code == 0, result.output
    assert len(json.loads(out.read_text())["faces"]) == 8 * 4


@pytest.mark.parametrize("name, options", [("heart.svg", ["--cell", "10mm"]),
                                           ("star.svg", ["--mesh", "quad"])])
def test_weave_a_meshed_outline(tmp_path, name, options):
    out = tmp_path / "weave.svg"
    result = run("weave", EXAMPLES / name, "--levels", 2, *options, "-o", out)
    assert result.exit_code == 0, result.output
    assert "meshed" in result.output
    assert ET.parse(out).getroot().get("width").endswith("mm")


def test_stats_counts_follow_the_mesh_options():
    """--cell sets the size of the faces, so a smaller cell gives more faces."""
    counts = []
    for cell in ("12mm", "6mm"):
        result = run("stats", EXAMPLES / "heart.svg", "--cell", cell, "--levels", 0, "--json")
        assert result.exit_code == 0, result.output
        counts.append(json.loads(result.output[result.output.index("{"):])["levels"][0]["faces"])
    assert 3 < counts[1] / counts[0] < 5  # a quarter of the area each: about 4 times as many


@pytest.mark.slow
@pytest.mark.parametrize("name, options", [
    ("heart.svg", ["--levels", "1", "--tile-size", "31mm"]),  # what the size checks ask for
    ("star.svg", ["--levels", "1", "--cell", "10mm", "--tile-size", "19mm"])])
def test_strands_of_a_drawing(tmp_path, name, options):
    out = tmp_path / "model.pdf"
    result = run("strands", EXAMPLES / name, *options, "-o", out)
    assert result.exit_code == 0, result.output
    assert out.read_bytes().startswith(b"%PDF")


def test_bad_drawing_options_are_one_line(tmp_path):
    result = run("subdivide", EXAMPLES / "plate.dxf", "--layer", "NOPE", "-o", tmp_path / "x.svg")
    assert result.exit_code == 1
    assert "no outlines on layer 'NOPE' (did you mean 'NOTES'?); layers: GRID, NOTES, OUTLINE" \
        in result.output
    assert not list(tmp_path.iterdir())
    result = run("subdivide", EXAMPLES / "heart.svg", "--mesh", "pentagons", "-o",
                 tmp_path / "x.svg")
    assert result.exit_code == 2


def test_recipes_pass_drawing_options(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text('[[job]]\ncommand = "subdivide"\ninput = "heart.svg"\nmesh = "quad"\n'
                      'cell = "10mm"\nlevels = 0\noutput = "heart.json"\n', encoding="utf-8")
    (tmp_path / "heart.svg").write_bytes((EXAMPLES / "heart.svg").read_bytes())
    result = run("build", recipe, "-o", tmp_path / "out")
    assert result.exit_code == 0, result.output
    faces = json.loads((tmp_path / "out" / "heart.json").read_text())["faces"]
    assert 50 <= len(faces) <= 75  # 6275 mm2 / 100 mm2 per cell


@pytest.mark.parametrize("suffix", ["svg", "dxf"])
def test_weave_cuts_own_drawings_read_back_with_the_papers_counts(tmp_path, suffix):
    """The tiles (V, E, F) = (18, 30, 13) after one snub step, drawn by weave-cut as a cut file
    (every edge once: inner lines and the outline) and read back as the faces the lines
    enclose: eq. (2) gives V + 2E + F = 91, 3E + 48 = 138 and 48."""
    out = tmp_path / f"tiles-1.{suffix}"
    assert run("subdivide", EXAMPLES / "tiles.svg", "--levels", 1, "-o", out).exit_code == 0
    result = run("stats", out, "--levels", 0, "--json")
    assert result.exit_code == 0, result.output
    level = json.loads(result.output[result.output.index("{"):])["levels"][0]
    assert (level["vertices"], level["edges"], level["faces"]) == (91, 138, 48)
