"""No output file tells where the maker keeps their files: recipes and commands given absolute
paths (of the inputs, the recipe and the output folder) write no absolute path into any file
they make, read as a maker's programs read it: a PDF's text (poppler's pdftotext) and its
metadata (pdfinfo), SVG, DXF, HTML, JSON and text as they are. A title names the input file by
its name; a kit page shows each job as run in its folder."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner

from weavecut.cli import cli

from .built_recipes import built
from .once import session_root
from .test_readback import program

ROOT = Path(__file__).resolve().parents[1]
RECIPES = [ROOT / "examples" / "star-paper-model.toml", ROOT / "examples" / "voronoi.toml",
           ROOT / "templates" / "recipes" / "heart-puzzle.toml",
           # a cutter's PDF with cut files beside it, and a laser card folder (whose summary
           # line began with the folder's absolute path on the kit page)
           ROOT / "templates" / "recipes" / "square-grid-cut-by-machine.toml"]


def _text(path: Path) -> str:
    """What a maker's programs show of ``path``."""
    if path.suffix == ".pdf":
        return "\n".join(subprocess.run([program(tool), str(path), *extra], check=True,
                                        capture_output=True, text=True).stdout
                         for tool, extra in (("pdftotext", ["-"]), ("pdfinfo", [])))
    return path.read_bytes().decode("utf-8", errors="replace")


def _machine_paths(folder: Path, *roots: Path) -> list[str]:
    """Every file under ``folder`` that holds one of ``roots`` (absolute paths)."""
    files = sorted(p for p in folder.rglob("*") if p.is_file() and p.suffix != ".png")
    assert files
    return [f"{p.relative_to(folder)}: {root}" for p in files for root in roots
            if str(root) in _text(p)]


@pytest.mark.slow  # every recipe built (the builds test_slim_pieces reads)
@pytest.mark.parametrize("recipe", RECIPES, ids=lambda p: p.stem)
def test_a_recipe_built_by_absolute_paths_writes_none(recipe, tmp_path_factory):
    """The session's build of the recipe (``built_recipes``: absolute paths, the command line
    recorded as a shell gives it) names neither the project's folder nor the session's."""
    out = built(tmp_path_factory, recipe)[0]
    assert _machine_paths(out, ROOT, session_root(tmp_path_factory)) == []


@pytest.mark.slow
def test_a_command_given_absolute_paths_writes_none(tmp_path, monkeypatch):
    """The star's paper model and weave, with the drawing and -o given absolutely: the titles
    say star.svg."""
    star = str(ROOT / "examples" / "star.svg")
    for args in (["strands", star, "--cell", "10mm", "--levels", "1", "--tile-size", "21mm",
                  "-o", str(tmp_path / "out" / "star.pdf")],
                 ["weave", star, "--cell", "10mm", "-o", str(tmp_path / "out" / "star.svg")]):
        (tmp_path / "out").mkdir(exist_ok=True)
        monkeypatch.setattr("sys.argv", ["weave-cut", "-q", *args])
        res = CliRunner().invoke(cli, ["-q", *args])
        assert res.exit_code == 0, res.output
    assert _machine_paths(tmp_path / "out", ROOT, tmp_path) == []
    assert "weave-cut strands: star.svg, level 1" in _text(tmp_path / "out" / "star.pdf")
