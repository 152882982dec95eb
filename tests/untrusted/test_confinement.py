"""Every path a recipe, an option or a manifest names for writing or removing stays inside the
output folder: one rule (``recipe.Planner.output``) for every option that names a written path
(``common.path_options``: every ``click.Path`` that need not exist), found by walking the
commands, so a new path option is covered without a new test."""

from __future__ import annotations

import hashlib
import json
import os
import shlex
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from weavecut.cli import cli
from weavecut.cli.common import path_options
from weavecut.cli.recipe import NOT_IN_RECIPES, Planner
from weavecut.manifest import MANIFEST

from . import strategies as ws
from .helpers import files_under, refused, run

FEW = settings(max_examples=max(5, settings.default.max_examples // 4),
               suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def written_keys() -> list[tuple[str, str]]:
    """(command, recipe key) of every path a recipe job writes: the keys of the commands'
    path options, and ``output`` of a command that prints."""
    found = []
    for name in sorted(cli.commands):
        if name in NOT_IN_RECIPES:
            continue
        command = cli.commands[name]
        options = Planner.options(command)
        keys = [k for k, p in options.items() if p in path_options(command)]
        found += [(name, k) for k in keys + ([] if "output" in options else ["output"])]
    return found


WRITTEN = written_keys()
# what a job of each command needs besides the key under test (for a dry run to pass)
NEEDS = {"figure": {"input": "z-triplet"}, "inputs": {}, "findings": {}, "puzzle": {}}
HOSTILE = ["../escaped", "a/../../escaped", "/tmp/weave-cut-confinement", "~/escaped",
           "~", "", "x\x00y"]  # (a NUL is refused by the recipe's schema)


def job(command: str, key: str, value) -> str:
    """A recipe of one job of ``command`` with ``key = value`` (a folder or file name)."""
    table = {"command": command, **NEEDS.get(command, {"input": "pentagon"}), key: value}
    if command == "levels":
        table["size"] = 64
    return "[[job]]\n" + ws.toml_table(table)


def test_the_walk_finds_every_kind_of_written_path():
    assert ("levels", "tiles") in WRITTEN and ("levels", "output") in WRITTEN
    assert ("puzzle", "output") in WRITTEN and ("stats", "output") in WRITTEN
    with_o = {n for n in cli.commands if n != "build" and "output" in Planner.options(
        cli.commands[n])}
    assert {n for n, k in WRITTEN if k == "output"} >= with_o


@pytest.mark.parametrize("value", HOSTILE)
@pytest.mark.parametrize("command,key", WRITTEN)
def test_every_written_path_of_a_recipe_is_confined(tmp_path, monkeypatch, command, key,
                                                    value):
    monkeypatch.chdir(tmp_path)
    recipe = tmp_path / "r.toml"
    recipe.write_text(job(command, key, value))
    before = files_under(tmp_path)
    shown = [repr(value), "inside the build folder"] if "\x00" not in value else []
    refused(run("build", recipe, "-o", tmp_path / "out"), "r.toml", "job 1", key, *shown)
    refused(run("build", recipe, "-o", tmp_path / "out", "--dry-run"), "job 1")
    assert files_under(tmp_path) == before and not (tmp_path / "out").exists()


@pytest.mark.parametrize("command,key", WRITTEN)
def test_a_written_path_inside_is_shown_inside_in_the_dry_run(tmp_path, command, key):
    value = "sub/made.json" if command != "levels" or key != "output" else "sub/made.png"
    recipe = tmp_path / "r.toml"
    recipe.write_text(job(command, key, value) + ("json = true\n" if command in (
        "stats", "inputs", "findings") else ""))
    out = tmp_path / "out"
    result = run("build", recipe, "-o", out, "--dry-run")
    assert result.exit_code == 0, result.output
    assert str(out / value) in shlex.split(result.output.splitlines()[0])
    assert files_under(tmp_path) == {"r.toml"}


@pytest.mark.parametrize("value", ["../escaped", "/tmp/weave-cut-confinement", "~/x", ""])
def test_set_overrides_go_through_the_same_rule(tmp_path, value):
    recipe = tmp_path / "r.toml"
    recipe.write_text(job("levels", "tiles", "t"))
    for extra in ([], ["--dry-run"]):
        refused(run("build", recipe, "-o", tmp_path / "out", "--set", f"tiles={value}", *extra),
                "tiles", repr(value))
    assert files_under(tmp_path) == {"r.toml"}


@FEW
@given(st.sampled_from(WRITTEN), st.one_of(st.sampled_from(ws.OUTPUTS + ws.HOSTILE_STRINGS),
                                           st.text(max_size=12)))
def test_a_dry_run_names_only_paths_inside(tmp_path_factory, written, value):
    root = tmp_path_factory.mktemp("c")
    out = root / "out"
    out.mkdir()
    (out / "link").symlink_to(root)
    (root / "r.toml").write_text(job(*written, value))
    result = run("build", root / "r.toml", "-o", out, "--dry-run")
    if result.exit_code != 0:
        refused(result, status=(1, 2))
        return
    words = shlex.split(result.output.split("\n")[0])  # a name may hold a '\r'
    marker = {"output": "-o"}.get(written[1], f"--{written[1]}")
    target = Path(words[words.index(marker if marker in words else ">") + 1]).resolve()
    assert target == out.resolve() or target.is_relative_to(out.resolve()), words


def test_a_tile_pyramid_lands_inside_and_is_in_the_manifest(tmp_path, monkeypatch):
    cwd = tmp_path / "cwd"
    cwd.mkdir()
    monkeypatch.chdir(cwd)  # a relative tiles folder once resolved against this one
    recipe = tmp_path / "r.toml"
    recipe.write_text(job("levels", "tiles", "t") + "levels = 2\n")
    out = tmp_path / "out"
    assert run("build", recipe, "-o", out, "--set", "jobs=2").exit_code == 0
    assert files_under(cwd) == set()
    tiles = {n for n in files_under(out) if n.startswith("t/")}
    assert "t/levels.dzi" in tiles and len(tiles) > 3
    manifest = json.loads((out / MANIFEST).read_text())
    assert set(manifest["outputs"]["t"]) == tiles  # those the worker processes wrote too
    assert run("build", recipe, "-o", out).exit_code == 0  # its own tiles: rebuilt freely
    (out / "t" / "levels_files" / "0" / "0_0.png").write_bytes(b"mine")
    refused(run("build", recipe, "-o", out), "levels_files/0/0_0.png", "--force")
    (out / "t" / "levels_files" / "0" / "0_0.png").unlink()
    os.symlink(tmp_path, out / "t" / "levels_files" / "9")
    refused(run("build", recipe, "-o", out, "--force"), "symlink")


@pytest.mark.parametrize("option", sorted({(n, p.opts[-1]) for n in cli.commands
                                           for p in path_options(cli.commands[n])}))
def test_an_empty_path_option_is_refused(tmp_path, monkeypatch, option):
    name, flag = option
    monkeypatch.chdir(tmp_path)
    argument = {"build": ["r.toml"], "puzzle": [], "figure": ["z-triplet"]}.get(
        name, ["pentagon"])
    (tmp_path / "r.toml").write_text(job("stats", "output", "s.txt"))
    before = files_under(tmp_path)
    refused(run(name, *argument, "-o", "elsewhere", flag, ""), flag, "empty path",
            status=(2,))
    assert files_under(tmp_path) == before and not (tmp_path / "elsewhere").exists()


# --- the manifest is untrusted ---------------------------------------------------------------

def manifest_world(tmp_path: Path, listed) -> tuple[Path, Path, str]:
    """A build folder whose manifest lists ``listed`` names with the hash of the precious
    file v.txt beside the folder (which a trusted manifest would let build remove)."""
    out = tmp_path / "out"
    out.mkdir()
    (tmp_path / "v.txt").write_text("precious")
    (out / "up").symlink_to(tmp_path)
    digest = hashlib.sha256(b"precious").hexdigest()
    names = [n.replace("{abs}", str(tmp_path)) for n in listed]
    doc = {"format": "weave-cut-manifest", "version": 2,
           "files": {n: digest for n in ["s.txt", *names]}, "outputs": {"s.txt": names}}
    (out / MANIFEST).write_text(json.dumps(doc))
    recipe = tmp_path / "r.toml"
    recipe.write_text(job("stats", "output", "s.txt"))
    return out, recipe, digest


@pytest.mark.parametrize("listed", [["../v.txt"], ["{abs}/v.txt"], ["up/v.txt"],
                                    ["s.txt/../../v.txt"], ["./../v.txt"], ["up/../v.txt"]])
@pytest.mark.parametrize("force", [True, False])
def test_a_manifest_naming_a_file_outside_is_refused(tmp_path, listed, force):
    out, recipe, _ = manifest_world(tmp_path, listed)
    refused(run("build", recipe, "-o", out, *(["--force"] if force else [])), MANIFEST,
            listed[0].replace("{abs}", str(tmp_path)))
    assert (tmp_path / "v.txt").read_text() == "precious"


DIGEST = "0" * 64
BAD_MANIFESTS = {
    "deep": "[" * 100_000 + "]" * 100_000,
    "deep-object": '{"a":' * 50_000 + "1" + "}" * 50_000,
    "not-json": "{",
    "a-list": "[]",
    "no-files": '{"format": "weave-cut-manifest", "version": 2}',
    "version": '{"format": "weave-cut-manifest", "version": 3, "files": {}}',
    "extra-key": '{"format": "weave-cut-manifest", "version": 2, "files": {}, "x": 1}',
    "null-hash": '{"format": "weave-cut-manifest", "version": 2, "files": {"s.txt": null}}',
    "short-hash": '{"format": "weave-cut-manifest", "version": 2, "files": {"s.txt": "ab"}}',
    "nested-hash": '{"format": "weave-cut-manifest", "version": 2, "files": {"s.txt": '
                   '[[["x"]]]}}',
    "empty-name": f'{{"format": "weave-cut-manifest", "version": 2, "files": {{"": '
                  f'"{DIGEST}"}}}}',
    "nul-name": f'{{"format": "weave-cut-manifest", "version": 2, "files": {{"a\\u0000b": '
                f'"{DIGEST}"}}}}',
    "unlisted": f'{{"format": "weave-cut-manifest", "version": 2, "files": {{"s.txt": '
                f'"{DIGEST}"}}, "outputs": {{"s.txt": ["t.txt"]}}}}',
    "huge-number": '{"format": "weave-cut-manifest", "version": 1e999, "files": {}}',
    "long-int": '{"format": "weave-cut-manifest", "version": ' + "9" * 10_000 + "}",
}


@pytest.mark.parametrize("name", sorted(BAD_MANIFESTS))
def test_a_malformed_manifest_is_one_line_naming_it(tmp_path, name):
    out = tmp_path / "out"
    out.mkdir()
    (out / MANIFEST).write_text(BAD_MANIFESTS[name])
    recipe = tmp_path / "r.toml"
    recipe.write_text(job("stats", "output", "s.txt"))
    refused(run("build", recipe, "-o", out, "--force"), MANIFEST, "remove")
    assert not (out / "s.txt").exists()


@pytest.mark.parametrize("kind", ["symlink", "folder", "fifo", "huge"])
def test_a_manifest_that_is_no_small_file_is_refused(tmp_path, kind):
    out = tmp_path / "out"
    out.mkdir()
    (tmp_path / "elsewhere.json").write_text('{"format": "weave-cut-manifest", "version": 2, '
                                             '"files": {}}')
    path = out / MANIFEST
    {"symlink": lambda: path.symlink_to(tmp_path / "elsewhere.json"),
     "folder": path.mkdir, "fifo": lambda: os.mkfifo(path),
     "huge": lambda: path.write_text(" " * (16 * 2**20 + 1))}[kind]()
    recipe = tmp_path / "r.toml"
    recipe.write_text(job("stats", "output", "s.txt"))
    refused(run("build", recipe, "-o", out, "--force"), MANIFEST)


NAMES = st.one_of(st.sampled_from(["../v.txt", "up/v.txt", "{abs}/v.txt", "s.txt", ".", "",
                                   "./s.txt", "a//b", "up", "up/", "~/v.txt", "..", "/"]),
                  st.text(max_size=12))


@FEW
@given(st.lists(NAMES, min_size=1, max_size=4), st.booleans())
def test_no_manifest_makes_a_build_touch_a_file_outside(tmp_path_factory, listed, force):
    root = tmp_path_factory.mktemp("m")
    out, recipe, _ = manifest_world(root, listed)
    result = run("build", recipe, "-o", out, *(["--force"] if force else []))
    if result.exit_code != 0:
        refused(result, status=(1,))
    assert (root / "v.txt").read_text() == "precious"


# --- a folder where a TOML file is expected; a printing job's output --------------------------

@pytest.mark.parametrize("args", [["weave", "square-grid", "-n", "1", "-o", "{d}/w.svg",
                                   "--palette", "{d}/x.toml"],
                                  ["puzzle", "-n", "2", "-o", "{d}/p", "--material",
                                   "{d}/x.toml"],
                                  ["puzzle", "-n", "2", "-o", "{d}/p", "--laser", "{d}/x.toml"],
                                  ["build", "{d}/x.toml", "-o", "{d}/out"],
                                  ["build", "{d}/x", "-o", "{d}/out"]])
def test_a_folder_named_like_a_toml_file_is_refused(tmp_path, args):
    (tmp_path / "x.toml").mkdir()
    (tmp_path / "x").mkdir()
    refused(run(*[a.format(d=tmp_path) for a in args]), "x", "is a folder, not a TOML file")
    assert files_under(tmp_path) == set()


def test_a_folder_named_like_a_toml_file_in_a_recipe_is_refused(tmp_path):
    (tmp_path / "x.toml").mkdir()
    recipe = tmp_path / "r.toml"
    recipe.write_text(job("weave", "output", "w.svg") + 'palette = "x.toml"\n')
    refused(run("build", recipe, "-o", tmp_path / "out"), "job 1 (weave)", "palette",
            "is a folder")


PRINTED = {  # output of a printing job -> whether it is written
    "s.txt": True, "S.TXT": True, "s.html": False, "s.HTM": False, "s.svg": False,
    "s.xhtml": False, "s": False, "s.json": False, "s.txt.html": False, "s.md": False,
}


@pytest.mark.parametrize("output", sorted(PRINTED))
def test_a_printing_job_writes_only_text(tmp_path, output):
    name = "<img src=x onerror=alert(1)>.obj"
    (tmp_path / name).write_text("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n")
    recipe = tmp_path / "r.toml"
    recipe.write_text("[[job]]\n" + ws.toml_table({"command": "stats", "input": name,
                                                   "levels": 0, "output": output}))
    result = run("build", recipe, "-o", tmp_path / "out")
    if not PRINTED[output]:
        refused(result, "job 1 (stats)", repr(output), "a job that prints writes text",
                "name it .txt (or .json with json = true)")
        assert not (tmp_path / "out").exists()
        return
    assert result.exit_code == 0, result.output
    assert name in (tmp_path / "out" / output).read_text()
    assert "<img src=x" not in (tmp_path / "out" / "index.html").read_text()


def test_a_printing_job_writes_json_only_when_it_prints_json(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text(job("stats", "output", "s.json") + "json = true\nlevels = 0\n")
    assert run("build", recipe, "-o", tmp_path / "out").exit_code == 0
    assert json.loads((tmp_path / "out" / "s.json").read_text())["levels"]
    refused(run("build", recipe, "-o", tmp_path / "out", "--set", "json=false"),
            "name it .txt", status=(1,))


@pytest.mark.parametrize("written", WRITTEN, ids="-".join)
@pytest.mark.parametrize("value, out", [("x" * 256, "out"), ("d/" + "é" * 128, "out"),
                                        ("x", "o/" * 2100)])
def test_names_too_long_for_a_file_system_are_refused_before_any_work(tmp_path, written, value,
                                                                       out):
    """A name over 255 bytes (or a path over 4,096) made the build's own checks fail with
    ENAMETOOLONG, an internal error (found by hypothesis with the newest releases)."""
    (tmp_path / "r.toml").write_text(job(*written, value))
    for extra in ([], ["--dry-run"]):
        refused(run("build", tmp_path / "r.toml", "-o", tmp_path / out, *extra),
                "too long for a file system")
    assert files_under(tmp_path) == {"r.toml"}
