"""A recipe is confined to its output folder and reads only beside itself; it is checked whole
before any job runs, and every error names the recipe, the job and the key."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from weavecut.manifest import MANIFEST, file_hash

from .helpers import files_under, refused, run

JOB = '[[job]]\ncommand = "{command}"\n'

# recipe body -> what the one-line error must say (every case once wrote, hung or crashed)
HOSTILE = {
    'output = "../../x.svg"': ["job 1 (subdivide)", "'../../x.svg'", "no '..'"],
    'output = "/tmp/weave-cut-absolute.svg"': ["job 1 (subdivide)", "not absolute"],
    'output = "a/../../x.svg"': ["job 1", "no '..'"],
    'output = ""': ["job 1", "relative path"],
    'output = 5': ["job 1", "relative path"],
    'output = "x.svg"\nlevel = 2': ["job 1 (subdivide)", "unknown key 'level'",
                                    "did you mean 'levels'"],
    'output = "x.svg"\nlevels = "--output=/etc"': ["job 1 (subdivide)", "levels"],
    'output = "x.svg"\nlevels = 2.5': ["levels", "expected an integer"],
    'output = "x.svg"\nlevels = true': ["levels", "expected a value"],
    'output = "x.svg"\nlevels = [1, 2]': ["levels", "one value"],
    'output = "x.svg"\nlevels = 99': ["levels", "99"],
    'output = "x.svg"\nsize = "nan"': ["size", "not a length"],
    'output = "x.svg"\nsize = nan': ["size", "not a finite number"],
    'output = "x.svg"\nsize = "1e400mm"': ["size", "not a finite length"],
    'output = "x.svg"\nsize = "-3mm"': ["size", "must be >"],
    'output = "x.svg"\nsize = -3.0': ["size", "'-3.0' has no unit"],
    'output = "x.svg"\nsize = 300': ["size", "'300' has no unit: write it like '300mm'"],
    'output = "x.svg"\nscheme = "snubb"': ["scheme"],
    'output = "x.svg"\nno-smooth = "maybe"': ["no-smooth"],
    'output = "x.svg"\nlevels = 1979-05-27': ["levels", "string, number or boolean"],
    f'output = "{MANIFEST}"': ["manifest"],
}


def write_recipe(folder: Path, body: str, command: str = "subdivide",
                 input_: str | None = "pentagon") -> Path:
    text = JOB.format(command=command) + (f'input = "{input_}"\n' if input_ else "") + body
    path = folder / "r.toml"
    path.write_text(text + "\n")
    return path


@pytest.mark.parametrize("body", sorted(HOSTILE))
def test_hostile_recipe_is_refused_before_any_work(tmp_path, body):
    recipe = write_recipe(tmp_path, body)
    before = files_under(tmp_path.parent)
    error = refused(run("build", recipe, "-o", tmp_path / "out"), *HOSTILE[body])
    assert "r.toml" in error
    assert files_under(tmp_path.parent) == before  # nothing written, not even the folder


@pytest.mark.parametrize("input_", ["--output=DIR", "--help", "-o", "../outside.obj",
                                    "/etc/passwd", "nope"])
def test_input_never_becomes_an_option_or_a_read_outside(tmp_path, input_):
    (tmp_path.parent / "outside.obj").write_text("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n")
    recipe = write_recipe(tmp_path, 'output = "s.json"', "stats", input_)
    refused(run("build", recipe, "-o", tmp_path / "out"), "job 1 (stats)", "input")
    assert not (tmp_path / "out").exists()


def test_a_later_job_runs_after_a_help_input_is_refused_not_swallowed(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text(JOB.format(command="stats") + 'input = "--help"\n'
                      + JOB.format(command="inputs") + 'output = "inputs.txt"\n')
    refused(run("build", recipe, "-o", tmp_path / "out"), "job 1")


def test_reads_beside_the_recipe_or_from_allow_read(tmp_path):
    shared = tmp_path / "shared"
    shared.mkdir()
    (shared / "t.obj").write_text("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n")
    folder = tmp_path / "recipes"
    folder.mkdir()
    recipe = write_recipe(folder, 'output = "t.json"', "subdivide", "../shared/t.obj")
    refused(run("build", recipe, "-o", tmp_path / "out"), "outside the recipe's folder",
            "--allow-read")
    result = run("build", recipe, "-o", tmp_path / "out", "--allow-read", shared)
    assert result.exit_code == 0, result.output
    assert json.loads((tmp_path / "out" / "t.json").read_text())["faces"]


def test_preset_files_are_read_only_beside_the_recipe(tmp_path):
    (tmp_path / "p.toml").write_text('colours = ["#ff0000", "#00ff00"]\n')
    sub = tmp_path / "r"
    sub.mkdir()
    recipe = write_recipe(sub, 'output = "w.svg"\nlevels = 1\npalette = "../p.toml"', "weave",
                          "square-grid")
    refused(run("build", recipe, "-o", tmp_path / "out"), "palette", "outside")
    recipe = write_recipe(sub, 'output = "s.pdf"\npage = "/etc/page.toml"', "strands",
                          "square-grid")
    refused(run("build", recipe, "-o", tmp_path / "out"), "page", "outside")
    recipe = write_recipe(sub, 'output = "w.svg"\nlevels = 1\npalette = "nope"', "weave",
                          "square-grid")
    refused(run("build", recipe, "-o", tmp_path / "out"), "job 1 (weave)", "palette",
            "unknown palette")


def test_symlink_out_of_the_build_folder_is_refused(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (out / "link").symlink_to(elsewhere)
    recipe = write_recipe(tmp_path, 'output = "link/x.svg"')
    refused(run("build", recipe, "-o", out), "symlink")
    (out / "file-link.svg").symlink_to(elsewhere / "target.svg")
    recipe = write_recipe(tmp_path, 'output = "file-link.svg"')
    refused(run("build", recipe, "-o", out), "symlink")
    assert not list(elsewhere.iterdir())


def test_printing_jobs_write_only_inside_and_never_replace_devices(tmp_path):
    recipe = write_recipe(tmp_path, 'output = "../stolen.txt"', "stats")
    refused(run("build", recipe, "-o", tmp_path / "out"), "no '..'")
    out = tmp_path / "out"
    out.mkdir()
    os.mkfifo(out / "fifo.txt")
    recipe = write_recipe(tmp_path, 'output = "fifo.txt"', "stats")
    refused(run("build", recipe, "-o", out, "--force"), "not a regular file")
    assert (out / "fifo.txt").is_fifo()


def test_existing_files_are_replaced_only_if_weave_cut_wrote_them(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "mine.txt").write_text("precious")
    recipe = write_recipe(tmp_path, 'output = "mine.txt"', "stats")
    refused(run("build", recipe, "-o", out), "mine.txt", "--force", MANIFEST)
    assert (out / "mine.txt").read_text() == "precious"
    recipe = write_recipe(tmp_path, 'output = "s.txt"', "stats")
    assert run("build", recipe, "-o", out).exit_code == 0
    assert run("build", recipe, "-o", out).exit_code == 0  # its own output: rebuilt freely
    manifest = json.loads((out / MANIFEST).read_text())
    assert set(manifest["files"]) == {"s.txt", "index.html"}  # and the build's page
    (out / "s.txt").write_text("edited by hand")  # no longer what weave-cut wrote
    refused(run("build", recipe, "-o", out), "s.txt")
    assert run("build", recipe, "-o", out, "--force").exit_code == 0
    assert "pentagon" in (out / "s.txt").read_text()


def test_folder_outputs_check_the_files_the_command_writes(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "puzzle-summary.json").write_text("{}")
    recipe = write_recipe(tmp_path, 'output = "."\nlevels = 2\nmode = "shared"', "puzzle",
                          None)
    refused(run("build", recipe, "-o", out), "puzzle-summary.json", "--force")
    assert run("build", recipe, "-o", out, "--force").exit_code == 0
    assert run("build", recipe, "-o", out).exit_code == 0
    assert {n for n in json.loads((out / MANIFEST).read_text())["files"]} >= {
        "puzzle-summary.json", "puzzle-shared-cut.svg"}


def test_every_file_a_job_writes_is_in_the_manifest_and_stale_ones_go(tmp_path):
    out = tmp_path / "out"
    cut = 'output = "sq.pdf"\ncutter = "silhouette"\ntile-size = "{}"'
    recipe = write_recipe(tmp_path, cut.format("40mm"), "strands", "square-grid:2x2")
    assert run("build", recipe, "-o", out).exit_code == 0
    manifest = json.loads((out / MANIFEST).read_text())
    pages = ["sq.pdf", "sq-3d.glb",  # the woven 3-D model beside the strips
             *(f"sq-p{n:02d}-cut.{s}" for n in (3, 4, 5) for s in ("dxf", "svg"))]
    assert manifest["outputs"] == {"sq.pdf": sorted(pages)}
    assert set(manifest["files"]) == {*pages, "index.html"}
    assert all(manifest["files"][p] == file_hash(out / p) for p in pages)
    recipe = write_recipe(tmp_path, cut.format("20mm"), "strands", "square-grid:2x2")
    assert run("build", recipe, "-o", out).exit_code == 0  # one strip page now
    left = {p.name for p in out.iterdir()}
    assert left == {"sq.pdf", "sq-3d.glb", "sq-p03-cut.dxf", "sq-p03-cut.svg", "index.html",
                    MANIFEST}
    assert set(json.loads((out / MANIFEST).read_text())["files"]) == left - {MANIFEST}
    (out / "sq-p07-cut.svg").write_text("<svg/>")  # a file weave-cut did not write, in the way
    refused(run("build", recipe, "-o", out), "sq-p07-cut.svg", "--force")
    (out / "sq-p07-cut.svg").unlink()
    (out / "sq-p03-cut.dxf").write_text("edited")  # no longer what weave-cut wrote
    refused(run("build", recipe, "-o", out), "sq-p03-cut.dxf", "--force")
    assert (out / "sq-p03-cut.dxf").read_text() == "edited"


def test_an_output_is_never_an_input(tmp_path):
    (tmp_path / "m.obj").write_text("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n")
    recipe = write_recipe(tmp_path, 'output = "m.obj"', "subdivide", "m.obj")
    refused(run("build", recipe, "-o", tmp_path, "--force"), "input of", "job 1")
    recipe = write_recipe(tmp_path, 'output = "r.toml"', "subdivide")
    refused(run("build", recipe, "-o", tmp_path, "--force"), "the recipe itself")
    recipe.write_text(JOB.format(command="subdivide") + 'input = "pentagon"\noutput = "a.svg"\n'
                      + JOB.format(command="weave") + 'input = "pentagon"\noutput = "a.svg"\n')
    refused(run("build", recipe, "-o", tmp_path / "o"), "job 2", "also the output of job 1")


@pytest.mark.parametrize("args", [["subdivide", "{m}", "-o", "{m}"],
                                  ["subdivide", "{m}", "-o", "{link}"],
                                  ["weave", "{m}", "--levels", "1", "-o", "{hard}"]])
def test_plain_commands_never_write_over_their_input(tmp_path, args):
    mesh = tmp_path / "m.obj"
    mesh.write_text("v 0 0\nv 1 0\nv 1 1\nv 0 1\nf 1 2 3 4\n")
    before = mesh.read_bytes()
    (tmp_path / "link.obj").symlink_to(mesh)
    os.link(mesh, tmp_path / "hard.svg")
    paths = {"m": mesh, "link": tmp_path / "link.obj", "hard": tmp_path / "hard.svg"}
    refused(run(*[a.format(**paths) for a in args]), "input")
    assert mesh.read_bytes() == before


def test_nested_errors_name_recipe_job_and_key_without_usage(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text(JOB.format(command="weave") + 'input = "square-grid"\nlevels = 2\n'
                      'outline-level = 1\noutput = "w.svg"\n')
    error = refused(run("build", recipe, "-o", tmp_path / "out", "--set", "levels=1"),
                    "r.toml job 1 (weave)", "outline-level")
    assert "weave-cut weave-cut" not in error
    refused(run("build", recipe, "-o", tmp_path / "out", "--set", "level=1"),
            "did you mean 'levels'", status=(2,))
    recipe.write_text(JOB.format(command="weave") + 'input = "square-grid"\n')
    refused(run("build", recipe, "-o", tmp_path / "out"), "r.toml job 1 (weave)")
    recipe.write_text(JOB.format(command="puzzle"))
    refused(run("build", recipe, "-o", tmp_path / "out"), "job 1 (puzzle)", "needs 'output'")
    recipe.write_text(JOB.format(command="weev"))
    refused(run("build", recipe, "-o", tmp_path / "out"), "did you mean 'weave'")


@pytest.mark.parametrize("text,needles", [
    ("job = [1, 2, 3]", ["job 1", "[[job]] table"]),
    ("[[job]]\ncommand = 'stats'\ninput = 'pentagon'\n[[job]]\ncommand = 5",
     ["job 2", "command"]),
    ("job = []", ["[[job]]"]),
    ("[recipe]\nnmae = 'x'\n[[job]]\ncommand = 'inputs'", ["[recipe]", "did you mean 'name'"]),
    ("[[jobs]]\ncommand = 'inputs'", ["did you mean 'job'"]),
    ("[[job]\n", ["r.toml"]),
])
def test_malformed_recipes(tmp_path, text, needles):
    recipe = tmp_path / "r.toml"
    recipe.write_text(text + "\n")
    refused(run("build", recipe, "-o", tmp_path / "out"), "r.toml", *needles)


def test_recipe_by_name_and_dry_run_lists_every_output(tmp_path):
    result = run("build", "jigsaw-50cm-poplar", "-o", tmp_path / "out", "--dry-run")
    assert result.exit_code == 0, result.output
    assert f"-o {tmp_path / 'out'}" in result.output
    recipe = tmp_path / "r.toml"
    recipe.write_text(JOB.format(command="stats") + 'input = "pentagon"\njson = true\n'
                      'output = "s.json"\n' + JOB.format(command="subdivide")
                      + 'input = "pentagon"\noutput = "p.svg"\n')
    result = run("build", recipe, "-o", "out", "--dry-run")
    assert result.output.splitlines() == [
        "weave-cut stats pentagon --json > out/s.json",
        "weave-cut subdivide pentagon -o out/p.svg"]
    refused(run("build", "jigsaw-50cm-popler"), "did you mean 'jigsaw-50cm-poplar'")


@pytest.mark.parametrize("command", ["build", "worker"])
def test_a_recipe_job_neither_builds_nor_serves(tmp_path, command):
    """A recipe cannot start a queue worker (it would serve until stopped) or a build."""
    recipe = tmp_path / "r.toml"
    recipe.write_text(f'[[job]]\ncommand = "{command}"\noutput = "x.txt"\n')
    refused(run("build", recipe, "-o", tmp_path / "out"), f"unknown command {command!r}")
    assert files_under(tmp_path) == {"r.toml"}
