"""``--formats`` of the laser commands: which files a run writes per sheet, from the option, a
recipe or the laser preset, and one-line refusals."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from weavecut.cli import cli

SMALL = ("puzzle", "--levels", "2", "--size", "20cm", "--mode", "separate")


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def laser_files(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.suffix in (".svg", ".dxf", ".lbrn2")
                  and "guide" not in p.name)


def test_default_is_svg_and_dxf_and_the_option_picks(tmp_path):
    assert run(*SMALL, "-o", tmp_path / "a").exit_code == 0
    assert laser_files(tmp_path / "a") == ["puzzle-separate-sheet-1.dxf",
                                           "puzzle-separate-sheet-1.svg"]
    assert run(*SMALL, "--formats", "LBRN2, svg", "-o", tmp_path / "b").exit_code == 0
    assert laser_files(tmp_path / "b") == ["puzzle-separate-sheet-1.lbrn2",
                                           "puzzle-separate-sheet-1.svg"]
    text = (tmp_path / "b" / "README.txt").read_text()
    assert "puzzle-separate-sheet-1.svg / .lbrn2 - " in text and "LightBurn projects" in text


def test_the_laser_preset_names_its_formats(tmp_path):
    preset = tmp_path / "mine.toml"
    preset.write_text('formats = ["lbrn2"]\n' + "".join(
        f'[{role}]\ncolour = "{colour}"\n' for role, colour in
        (("cut", "#ff0000"), ("score", "#0000ff"), ("engrave", "#000000"))))
    assert run(*SMALL, "--laser", preset, "-o", tmp_path / "p").exit_code == 0
    assert laser_files(tmp_path / "p") == ["puzzle-separate-sheet-1.lbrn2"]
    preset.write_text(preset.read_text().replace('"lbrn2"', '"pdf"'))
    result = run(*SMALL, "--laser", preset, "-o", tmp_path / "q")
    assert result.exit_code == 1 and "formats: item 1: 'pdf' is not one of svg, dxf, lbrn2" \
        in result.output and not (tmp_path / "q").exists()


def test_a_recipe_job_names_its_formats(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text("".join(
        f'[[job]]\ncommand = "puzzle"\nlevels = 2\nsize = "20cm"\nmode = "separate"\n'
        f'formats = {value}\noutput = "{name}"\n'
        for name, value in (("two", '"lbrn2,dxf"'), ("one", '"lbrn2"'))))
    result = run("build", recipe, "-o", tmp_path / "out")
    assert result.exit_code == 0, result.output
    assert laser_files(tmp_path / "out" / "two") == ["puzzle-separate-sheet-1.dxf",
                                                      "puzzle-separate-sheet-1.lbrn2"]
    assert laser_files(tmp_path / "out" / "one") == ["puzzle-separate-sheet-1.lbrn2"]


@pytest.mark.parametrize("args, message", [
    (("--formats", "svg,pdf"), "'pdf' is not a laser file format; give one or more of "
                               "svg,dxf,lbrn2"),
    (("--formats", ""), "'' is not a laser file format"),
])
def test_bad_formats_are_usage_errors(tmp_path, args, message):
    result = run(*SMALL, *args, "-o", tmp_path / "x")
    assert result.exit_code == 2 and message in result.output and not (tmp_path / "x").exists()


def test_formats_go_with_the_laser_card(tmp_path):
    result = run("strands", "square-grid", "--formats", "lbrn2", "-o", tmp_path / "s.pdf")
    assert result.exit_code == 2 and "--formats goes with --laser-card" in result.output
    assert not list(tmp_path.iterdir())
