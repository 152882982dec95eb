"""The command line as a shell user meets it: -q leaves stdout to what was asked for, shell
completion knows inputs, presets, recipes and figures, and `make figures` (part of `make run`)
builds every figure."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner

from weavecut import inputs, presets
from weavecut.cli import cli
from weavecut.figures import gallery

ROOT = Path(__file__).resolve().parents[1]


def run(*args):
    result = CliRunner().invoke(cli, [str(a) for a in args])
    assert result.exit_code == 0, result.output
    return result


@pytest.mark.parametrize("args", [
    ["puzzle", "--levels", "2", "--mode", "shared", "-o", "{d}/p"],
    ["strands", "square-grid", "-o", "{d}/s.pdf"],
    ["levels", "pentagon", "-n", "3", "--size", "32", "-o", "{d}/l.png"],
    ["weave", "square-grid", "-n", "1", "-o", "{d}/w.svg"],
    ["subdivide", "pentagon", "-n", "1", "-o", "{d}/s.dxf"],
    ["build", "subdivisions", "-o", "{d}/b"],
], ids=lambda a: a[0])
def test_quiet_prints_nothing(tmp_path, args):
    (tmp_path / "loud").mkdir()
    loud = run(*[a.format(d=tmp_path / "loud") for a in args])
    result = run("-q", *[a.format(d=tmp_path) for a in args])
    assert result.stdout == "" and result.stderr == ""
    assert args[0] in ("weave", "subdivide", "build") or loud.stdout  # it had something to say


@pytest.mark.parametrize("args", [
    ["puzzle", "--levels", "2", "--mode", "shared", "-o", "{d}/p", "--json"],
    ["strands", "square-grid", "-o", "{d}/s.pdf", "--json"],
    ["levels", "pentagon", "-n", "3", "--size", "32", "-o", "{d}/l.png", "--json"],
], ids=lambda a: a[0])
def test_quiet_json_prints_only_json(tmp_path, args):
    result = run("-q", *[a.format(d=tmp_path) for a in args])
    assert isinstance(json.loads(result.stdout), dict)


def complete(line: str) -> list[tuple[str, str]]:
    """What bash completion offers for ``line`` (the last word is being typed)."""
    words = line.split(" ")
    env = {"_WEAVE_CUT_COMPLETE": "bash_complete", "COMP_WORDS": line,
           "COMP_CWORD": str(len(words) - 1)}
    out = CliRunner().invoke(cli, [], env=env, prog_name="weave-cut").output
    return [tuple(item.split(",", 1)) for item in out.splitlines()]


@pytest.mark.parametrize("line, expect, files", [
    ("weave-cut weave ", list(inputs.INPUTS), True),
    ("weave-cut puzzle penta", ["pentagon", "pentagon-flower"], True),
    ("weave-cut weave pentagon --palette ", presets.names("palettes"), True),
    ("weave-cut strands pentagon --palette ma", ["maritime-12", "maritime-4"], True),
    ("weave-cut puzzle --material ", presets.names("materials"), True),
    ("weave-cut puzzle --laser ", presets.names("laser"), True),
    ("weave-cut build ", presets.names("recipes"), True),
    ("weave-cut figure ", list(gallery.FIGURES), False),
])
def test_completion(line, expect, files):
    offered = complete(line)
    assert [v for t, v in offered if t == "plain"] == expect
    assert any(t == "file" for t, _ in offered) == files


def test_figures_recipe_makes_every_figure():
    with open(ROOT / "templates" / "recipes" / "figures.toml", "rb") as f:
        jobs = tomllib.load(f)["job"]
    assert [j["input"] for j in jobs] == list(gallery.FIGURES)
    assert all(j["command"] == "figure" for j in jobs)
    makefile = (ROOT / "Makefile").read_text()
    assert "\nfigures: $(OUT)/figures/.built" in makefile  # `make run` builds it as a recipe
