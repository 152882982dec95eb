"""weave-cut installed as a package behaves as in the checkout: the wheel holds every module
and every preset, and its commands find palettes, materials and recipes by name from a fresh
virtual environment in a folder far from the checkout.

The wheel is built once per session from a copy of the sources (so no build folder lands in the
checkout) and installed with its dependencies as a user's ``pip install`` would, at the
versions of ``constraints.txt`` (pip's cache makes the second time fast).
"""

from __future__ import annotations

import json
import os
import shutil
import re
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.slow  # a wheel and a virtual environment
SOURCES = ("src", "templates", "examples", "pyproject.toml", "setup.py", "README.md")


def _pip(python: Path | str, *args: str, cwd: Path) -> None:
    subprocess.run([str(python), "-m", "pip", "--disable-pip-version-check", *args], cwd=cwd,
                   check=True, capture_output=True, text=True, env=_clean_env())


def _clean_env() -> dict[str, str]:
    """The environment without anything that points into the checkout."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "WEAVECUT_TEMPLATES", "VIRTUAL_ENV")}
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep)
                                  if not p.startswith(str(ROOT)))
    return env


@pytest.fixture(scope="session")
def wheel(tmp_path_factory) -> Path:
    copy = tmp_path_factory.mktemp("sources")
    for name in SOURCES:
        source = ROOT / name
        if source.is_dir():
            shutil.copytree(source, copy / name,
                            ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
        else:
            shutil.copy2(source, copy / name)
    out = tmp_path_factory.mktemp("wheel")
    _pip(sys.executable, "wheel", "--no-deps", "--quiet", "-w", str(out), str(copy), cwd=out)
    (built,) = out.glob("weave_cut-*.whl")
    return built


@pytest.fixture(scope="session")
def installed(wheel, tmp_path_factory) -> Path:
    """A fresh virtual environment with the wheel installed; returns its bin folder."""
    venv = tmp_path_factory.mktemp("venv")
    # without a pip of its own: this pip installs into it (--python), as the venv's own pip
    # would; that saves ensurepip's 3 s CPU, and --no-compile pip's byte-compiling every file
    # of numpy, scipy, ... (10 s CPU): Python compiles what the commands import when they do
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True,
                   env=_clean_env())
    bin_dir = venv / ("Scripts" if os.name == "nt" else "bin")
    # the dependencies at the versions of constraints.txt, as make test has them
    _pip(sys.executable, "--python", str(bin_dir / "python"), "install", "--quiet",
         "--no-compile", "-c", str(ROOT / "constraints.txt"), str(wheel), cwd=venv)
    return bin_dir


@pytest.fixture()
def weave_cut(installed, tmp_path):
    """Run the installed ``weave-cut`` in an empty folder outside the checkout."""

    def run(*args: str) -> subprocess.CompletedProcess:
        result = subprocess.run([str(installed / "weave-cut"), *args], cwd=tmp_path,
                                capture_output=True, text=True, env=_clean_env())
        assert result.returncode == 0, result.stderr
        return result

    return run


def test_wheel_holds_every_module_and_preset(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    modules = {p.relative_to(ROOT / "src").as_posix()
               for p in (ROOT / "src" / "weavecut").rglob("*.py")}
    presets = {"weavecut/templates/" + p.relative_to(ROOT / "templates").as_posix()
               for p in (ROOT / "templates").rglob("*.toml")}
    examples = {"weavecut/examples/" + p.name for p in (ROOT / "examples").iterdir()
                if p.suffix in (".toml", ".svg", ".dxf", ".obj", ".json")}
    assert presets and modules - names == set() and presets - names == set()
    assert examples and examples - names == set()
    assert "weavecut/templates/__init__.py" in names


def test_installed_package_is_not_the_checkout(installed, tmp_path):
    where = subprocess.run([str(installed / "python"), "-c",
                            "import weavecut, weavecut.presets as p; "
                            "print(weavecut.__file__); print(p.templates_dir())"],
                           cwd=tmp_path, capture_output=True, text=True, check=True,
                           env=_clean_env()).stdout.split()
    assert all(not Path(w).resolve().is_relative_to(ROOT) for w in where)
    assert all(Path(w).resolve().is_relative_to(installed.parent.resolve()) for w in where)


def test_weave_finds_its_default_palette(weave_cut, tmp_path):
    weave_cut("weave", "square-grid", "-n", "2", "-o", "w.svg")
    with open(ROOT / "templates" / "palettes" / "maritime-12.toml", "rb") as f:
        colours = {c for family in tomllib.load(f)["families"] for c in family}
    fills = set(re.findall(r'fill="(#[0-9a-f]{6})"', (tmp_path / "w.svg").read_text()))
    assert len(fills & colours) >= 4


def test_strands_prints_a_paper_model(weave_cut, tmp_path):
    weave_cut("strands", "square-grid", "-o", "s.pdf")
    assert (tmp_path / "s.pdf").read_bytes().startswith(b"%PDF")


def test_puzzle_finds_its_material(weave_cut, tmp_path):
    out = weave_cut("-q", "puzzle", "--levels", "3", "--mode", "shared",
                    "--material", "poplar-3mm", "-o", "p", "--json").stdout
    assert json.loads(out)["material"] == "3 mm poplar plywood (the paper's puzzle)"
    assert (tmp_path / "p" / "puzzle-shared-cut.dxf").is_file()


def test_recipe_by_name(weave_cut, tmp_path):
    weave_cut("-q", "build", "subdivisions", "-o", "out")
    built = sorted(p.name for p in (tmp_path / "out").iterdir()
                   if not p.name.startswith("."))  # not the build manifest
    assert built == ["index.html", "pentagon-level4.dxf", "pentagon-level4.svg",
                     "square-grid-level3.dxf", "square-grid-level3.svg"]


def test_example_recipe_by_name(weave_cut, tmp_path):
    """The examples ship with their drawings: the star paper model builds from its name."""
    weave_cut("-q", "build", "star-paper-model", "-o", "star")
    assert (tmp_path / "star" / "star-paper-model.pdf").read_bytes().startswith(b"%PDF")
    assert (tmp_path / "star" / "star-level1-weave.svg").is_file()
