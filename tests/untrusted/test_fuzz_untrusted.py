"""Property-based fuzzing of untrusted input, one property per category, and the corpus of
cases that once failed (``corpus/``: each file says its kind and the error it must give).

CI runs the bounded ``ci`` profile; ``HYPOTHESIS_PROFILE=long make fuzz`` runs the long one.
A failure hypothesis finds goes into ``corpus/`` as a file once fixed.
"""

from __future__ import annotations

import hashlib
import math
import shlex
import tomllib
from pathlib import Path

import click
import pytest
from hypothesis import HealthCheck, event, example, given, settings
from hypothesis import strategies as st

from weavecut import presets
from weavecut.cli import cli
from weavecut.puzzle import workshop
from weavecut.schema import SchemaError, read_toml, toml_depth
from weavecut.weave.colour import palette

from . import strategies as ws
from .helpers import files_under, refused, run

CORPUS = Path(__file__).with_name("corpus")
# fewer examples for the properties that run commands for real
FEW = settings(max_examples=max(5, settings.default.max_examples // 4),
               suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def header(path: Path) -> dict[str, str]:
    lines = path.read_bytes().decode("latin-1").splitlines()
    return dict(ln[2:].split(": ", 1) for ln in lines[:2])


@pytest.mark.parametrize("path", sorted(CORPUS.glob("*.toml")), ids=lambda p: p.stem)
def test_corpus(tmp_path, path):
    meta = header(path)
    out = tmp_path / "out"
    args = {"recipe": ["build", path, "-o", out],
            "materials": ["puzzle", "-n", "2", "-o", out, "--material", path],
            "laser": ["puzzle", "-n", "2", "-o", out, "--laser", path],
            "palettes": ["weave", "square-grid", "-n", "1", "-o", f"{out}.svg", "--palette", path]}
    refused(run(*args[meta["kind"]]), path.name, meta["expect"])
    assert files_under(tmp_path) == set()


def world(root: Path) -> tuple[Path, Path]:
    """A recipe folder with a mesh and a palette, a build folder with a symlink out, and a
    file outside both that nothing may touch."""
    recipes, out, outside = root / "recipes", root / "out", root / "outside"
    for folder in (recipes, out, outside):
        folder.mkdir(exist_ok=True)
    (recipes / "m.obj").write_text("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n")
    (recipes / "p.toml").write_text('colours = ["#ff0000", "#00ff00"]\n')
    (outside / "x.svg").write_text("precious")
    if not (out / "link").exists():
        (out / "link").symlink_to(outside)
    return recipes, out


def snapshot(root: Path) -> dict[str, str]:
    return {name: hashlib.sha256((root / name).read_bytes()).hexdigest()
            for name in files_under(root) if not (root / name).is_symlink()}


@settings(suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(ws.recipes())
def test_recipe_is_checked_or_refused_and_only_names_outputs_inside(tmp_path_factory, text):
    root = tmp_path_factory.mktemp("recipe")
    recipes, out = world(root)
    (recipes / "r.toml").write_text(text)
    before = snapshot(root)
    result = run("build", recipes / "r.toml", "-o", out, "--dry-run")
    event(f"exit {result.exit_code}")
    assert snapshot(root) == before  # a dry run writes nothing
    if result.exit_code != 0:
        refused(result, status=(1, 2))
        return
    for line in result.output.splitlines():
        words = shlex.split(line)
        for marker in ("-o", ">"):
            if marker in words:
                target = Path(words[words.index(marker) + 1]).resolve()
                assert target == out.resolve() or target.is_relative_to(out.resolve()), line


CHEAP_JOB = st.fixed_dictionaries(
    {"command": st.sampled_from(["stats", "inputs", "subdivide"]),
     "input": st.sampled_from(["pentagon", "m.obj", "../outside/x.svg", "--help", "ngon:4"]),
     "output": st.sampled_from(ws.OUTPUTS)},
    optional={"levels": st.integers(-1, 2), "json": st.booleans()})


@FEW
@given(st.lists(CHEAP_JOB, min_size=1, max_size=3), st.booleans())
def test_recipe_run_writes_only_inside_its_folder(tmp_path_factory, jobs, force):
    root = tmp_path_factory.mktemp("run")
    recipes, out = world(root)
    (recipes / "r.toml").write_text("".join("[[job]]\n" + ws.toml_table(j) for j in jobs))
    before = snapshot(root)
    result = run("build", recipes / "r.toml", "-o", out, *(["--force"] if force else []))
    event(f"exit {result.exit_code}")
    if result.exit_code != 0:
        refused(result, status=(1, 2))
    after = snapshot(root)
    changed = {n for n in set(before) | set(after) if before.get(n) != after.get(n)}
    assert all(n.startswith("out/") and not n.startswith("out/link/") for n in changed), changed


@given(ws.materials())
def test_material_preset_is_refused_or_in_range(tmp_path_factory, table):
    path = tmp_path_factory.mktemp("m") / "m.toml"
    path.write_text(ws.toml_table(table))
    try:
        mat = workshop.material(str(path))
    except presets.PresetError as exc:
        assert "m.toml" in str(exc)
        return
    assert 0 < mat["thickness"] <= 100 and 0 <= mat["kerf"] <= 5
    assert 0 < mat["cut_speed"] <= 10_000
    assert all(0 < s <= 10_000 for s in mat["sheet"])


@given(ws.palettes())
def test_palette_preset_is_refused_or_valid(tmp_path_factory, table):
    path = tmp_path_factory.mktemp("p") / "p.toml"
    path.write_text(ws.toml_table(table))
    try:
        pal = palette(str(path))
    except presets.PresetError as exc:
        assert "p.toml" in str(exc)
        return
    assert pal.flat and all(len(c) == 7 and int(c[1:], 16) >= 0 for c in pal.flat)


def nesting(value) -> int:
    if isinstance(value, dict):
        return 1 + max(map(nesting, value.values()), default=0)
    if isinstance(value, list):
        return 1 + max(map(nesting, value), default=0)
    return 0


@settings(suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(st.text(st.sampled_from(list("[]{}.=,\"'#\n ab01")), max_size=60))
@example("[0]")  # found by the long profile: a lone header was counted one short
def test_depth_scan_never_underestimates_the_parser(text):
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        return
    assert nesting(doc) <= max(toml_depth(text), 1), text


@given(st.binary(max_size=200))
def test_any_bytes_read_as_toml_give_a_schema_error_or_a_table(tmp_path_factory, data):
    path = tmp_path_factory.mktemp("t") / "t.toml"
    path.write_bytes(data)
    try:
        assert isinstance(read_toml(path), dict)
    except SchemaError as exc:
        assert "t.toml" in str(exc)


NUMERIC_OPTIONS = [("puzzle", "--speed"), ("puzzle", "--kerf"), ("puzzle", "--sheet"),
                   ("puzzle", "--size"), ("puzzle", "--frame"), ("strands", "--turn"),
                   ("strands", "--page"), ("strands", "--margin"), ("strands", "--tile-size"),
                   ("subdivide", "--size"), ("weave", "--size"), ("levels", "--window"),
                   ("levels", "--size"), ("subdivide", "--levels")]


@settings(max_examples=settings.default.max_examples * 3)
@given(st.sampled_from(NUMERIC_OPTIONS), ws.OPTION_STRINGS)
def test_numeric_options_are_finite_and_bounded_or_refused(option, value):
    name, flag = option
    command = cli.commands[name]
    args = ["pentagon", flag, value, *(["-o", "x.svg"] if name != "puzzle" else ["-o", "d"])]
    try:
        ctx = command.make_context(name, args)
    except click.UsageError:
        return
    param = next(p for p in command.params if flag in p.opts)
    got = ctx.params[param.name]
    numbers = got if isinstance(got, tuple) else (got,)
    assert all(math.isfinite(x) and abs(x) <= 1e9 for x in numbers), (flag, value, got)
