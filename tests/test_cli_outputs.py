"""Where every command writes, one rule each, over every path option of every command (found by
walking the click group, so a command or option added later fails here until the table below
has a line for it):

- ``-o`` (and every path option) is a file when the command writes one file, a folder when it
  writes several; the folder above it must exist, a folder output is not named like a file,
  a file output is not a folder: each refused as a usage error naming the option, before the
  command's own function runs;
- an existing file weave-cut did not write (not listed with its hash in the folder's
  manifest, or changed since) is refused with its name and ``--force``, before any work and
  with every file left as it was; weave-cut's own files are replaced without a word.

The oracles: file bytes, inode numbers (a replaced file gets a new one) and SHA-256 computed
here; whether the command's function ran is seen by a profile hook, not by its output."""

from __future__ import annotations

import hashlib
import inspect
import json
import os
import re
import shlex
import sys
from pathlib import Path

import click
import pytest

from weavecut.cli import cli
from weavecut.cli.outputs import is_folder, path_options, problem, written
from weavecut.cli.recipe import Planner
from weavecut.manifest import MANIFEST

from .untrusted.helpers import files_under, refused, run
from .untrusted.test_confinement import job

RECIPE = '[[job]]\ncommand = "subdivide"\ninput = "pentagon"\nlevels = 1\noutput = "s.svg"\n'

# (command, option, kind) -> (the name the option gets, the command line: {path} is the path
# under test, {t} a scratch folder holding r.toml, for the command's other outputs)
WRITERS = {
    ("subdivide", "output", "file"): ("s.svg", ["subdivide", "pentagon", "-n", "1", "-o",
                                                "{path}"]),
    ("weave", "output", "file"): ("w.svg", ["weave", "square-grid:2x2", "-n", "1", "-o",
                                            "{path}"]),
    ("weave", "html", "file"): ("w.html", ["weave", "square-grid:2x2", "-n", "1", "-o",
                                           "{t}/w.svg", "--html", "{path}"]),
    ("puzzle", "out_dir", "folder"): ("kit", ["puzzle", "-n", "2", "--mode", "shared", "-o",
                                              "{path}"]),
    ("puzzle", "html", "file"): ("p.html", ["puzzle", "-n", "2", "--preview", "-o", "{t}/kit",
                                            "--html", "{path}"]),
    ("strands", "output", "file"): ("s.pdf", ["strands", "square-grid:2x2", "-n", "1", "-o",
                                              "{path}"]),
    ("strands", "output", "folder"): ("card", ["strands", "square-grid:2x2", "-n", "1",
                                               "--laser-card", "-o", "{path}"]),
    ("strands", "html", "file"): ("s.html", ["strands", "square-grid:2x2", "-n", "1",
                                             "--preview", "-o", "{t}/s.svg", "--html",
                                             "{path}"]),
    ("fractal", "output", "file"): ("f.svg", ["fractal", "pentagon", "-n", "2", "-o",
                                              "{path}"]),
    ("levels", "output", "file"): ("l.png", ["levels", "pentagon", "-n", "2", "--size", "64",
                                             "-o", "{path}"]),
    ("levels", "tiles", "folder"): ("tiles", ["levels", "pentagon", "-n", "2", "--size", "64",
                                              "-j", "1", "--tiles", "{path}"]),
    ("convexity", "output", "file"): ("c.svg", ["convexity", "pentagon", "-n", "2", "-o",
                                                "{path}"]),
    ("figure", "output", "file"): ("z.svg", ["figure", "z-triplet", "-o", "{path}"]),
    ("build", "output_dir", "folder"): ("b", ["build", "{t}/r.toml", "-o", "{path}"]),
}
# more ways one option writes: files named after a file output, beside it
MORE = {("strands", "output", "cutter"): ("c.pdf", ["strands", "square-grid:2x2", "-n", "1",
                                                    "--cutter", "silhouette", "-o", "{path}"])}
ALL = {**WRITERS, **MORE}
FOLDER = {"folder"}


def kinds(option) -> set[str]:
    """The kinds of path an option takes: a file, a folder, or each (strands -o)."""
    if getattr(option.type, "folder_with", None):
        return {"file", "folder"}
    return {"folder" if is_folder(option, {}) else "file"}


def test_the_table_has_every_path_option_of_every_command_and_each_takes_force():
    walked = {(n, p.name, k) for n in cli.commands for p in path_options(cli.commands[n])
              for k in kinds(p)}
    assert set(WRITERS) == walked
    for name in {n for n, _, _ in walked}:
        assert "--force" in {o for p in cli.commands[name].params for o in p.opts}, name


@pytest.fixture
def world(tmp_path):
    """tmp/out (the folder under test, existing and empty) and tmp/t (scratch, r.toml)."""
    (tmp_path / "out").mkdir()
    (tmp_path / "t").mkdir()
    (tmp_path / "t" / "r.toml").write_text(RECIPE)
    return tmp_path


def command_line(key, path: Path, world: Path) -> list[str]:
    return [a.format(path=path, t=world / "t") for a in ALL[key][1]]


def run_watching(args):
    """Run the CLI in this process; also whether the function of a command that writes
    (under its wrappers: the error wrapper, --html, click's context) was entered: the
    command's own, or for ``build`` (whose function plans and checks every job first) a
    job's."""
    bodies = {inspect.unwrap(c.callback).__code__ for n, c in cli.commands.items()
              if n != "build"}
    entered = []

    def hook(frame, event, arg):
        if event == "call" and frame.f_code in bodies:
            entered.append(frame)

    sys.setprofile(hook)
    try:
        result = run(*args)
    finally:
        sys.setprofile(None)
    return result, bool(entered)


def snapshot(folder: Path) -> dict[str, tuple[int, bytes]]:
    """Every file under ``folder`` but the manifest: inode number and bytes."""
    return {n: (os.stat(folder / n).st_ino, (folder / n).read_bytes())
            for n in files_under(folder) if Path(n).name != MANIFEST}


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


# --- the meaning of -o ------------------------------------------------------------------------

@pytest.mark.parametrize("key", sorted(ALL), ids="-".join)
def test_an_output_lands_where_its_path_says(world, key):
    """A file option's path becomes that file (files named after it beside it); a folder
    option's path becomes a folder holding everything the run wrote; into a fresh temporary
    folder (as the web app runs commands), with or without --force."""
    out, name = world / "out", ALL[key][0]
    path = out / name
    result = run(*command_line(key, path, world))
    assert result.exit_code == 0, result.output
    written = set(snapshot(out))
    if key[2] in FOLDER:
        assert path.is_dir() and written and all(n.startswith(f"{name}/") for n in written)
    else:
        stem = Path(name).stem
        assert path.is_file() and name in written
        assert all(n == name or n.startswith(f"{stem}-") for n in written), written
    assert run(*command_line(key, path, world), "--force").exit_code == 0


@pytest.mark.parametrize("key", sorted(ALL), ids="-".join)
def test_a_missing_folder_above_an_output_is_refused_before_any_work(world, key):
    before = files_under(world)
    path = world / "missing" / ALL[key][0]
    result, entered = run_watching(command_line(key, path, world))
    option = next(p for p in path_options(cli.commands[key[0]]) if p.name == key[1])
    line = refused(result, f"the folder '{world / 'missing'}' does not exist; create it first",
                   status=(2,))
    assert any(f"'{o}'" in line for o in option.opts), line
    assert not entered and files_under(world) == before


@pytest.mark.parametrize("key", sorted(ALL), ids="-".join)
def test_a_file_where_the_folder_above_should_be_is_refused(world, key):
    (world / "f").write_text("mine")
    before = files_under(world)
    result, entered = run_watching(command_line(key, world / "f" / ALL[key][0], world))
    refused(result, "f' is a file, not a folder", status=(2,))
    assert not entered and files_under(world) == before


@pytest.mark.parametrize("key", sorted(k for k in ALL if k[2] in FOLDER), ids="-".join)
@pytest.mark.parametrize("suffix", [".pdf", ".svg", ".zip"])
def test_a_folder_output_named_like_a_file_is_refused_with_a_hint(world, key, suffix):
    before = files_under(world)
    path = world / "out" / f"kit{suffix}"
    result, entered = run_watching(command_line(key, path, world))
    refused(result, f"'{path}' is named like a file", f"like '{world / 'out' / 'kit'}'",
            status=(2,))
    assert not entered and files_under(world) == before and not path.exists()


@pytest.mark.parametrize("key", sorted(k for k in ALL if k[2] not in FOLDER), ids="-".join)
def test_a_file_output_that_is_a_folder_is_refused(world, key):
    path = world / "out" / ALL[key][0]
    path.mkdir()
    result, entered = run_watching(command_line(key, path, world))
    refused(result, str(path), status=(2,))
    assert not entered and files_under(world) == {"t/r.toml"}


@pytest.mark.parametrize("command,key", [(n, k) for n in sorted(cli.commands) if n != "build"
                                         for k, p in Planner.options(cli.commands[n]).items()
                                         if p in path_options(cli.commands[n])
                                         and "folder" in kinds(p)])
def test_a_recipe_folder_output_named_like_a_file_is_refused_the_same_way(tmp_path, command,
                                                                          key):
    """The build applies the same rule to its jobs (``Planner.plan``), before the first runs;
    a folder option that is a folder only with a flag gets the flag."""
    option = Planner.options(cli.commands[command])[key]
    flag = getattr(option.type, "folder_with", None)
    extra = f"{flag.replace('_', '-')} = true\n" if flag else ""
    (tmp_path / "r.toml").write_text(job(command, key, "kit.pdf") + extra)
    for dry in ([], ["--dry-run"]):
        refused(run("build", tmp_path / "r.toml", "-o", tmp_path / "out", *dry), "r.toml",
                "job 1", key, "is named like a file", "like")
    assert files_under(tmp_path) == {"r.toml"}


# --- nothing of the maker's is replaced -------------------------------------------------------

@pytest.mark.parametrize("key", sorted(ALL), ids="-".join)
def test_weave_cut_replaces_only_its_own_files(world, key):
    out, name = world / "out", ALL[key][0]
    path = out / name
    args = command_line(key, path, world)
    assert run(*args).exit_code == 0
    first = snapshot(out)
    home = path if key[2] in FOLDER else out  # the manifest is that of the output folder
    listed = json.loads((home / MANIFEST).read_text())["files"]
    assert listed == {os.path.relpath(out / n, home): sha256(b) for n, (_, b) in first.items()
                      if (out / n).resolve().is_relative_to(home)}
    assert {n for n in first if (out / n).resolve().is_relative_to(home)} == {
        os.path.relpath(home / n, out) for n in listed}
    # its own files: replaced without a word, with the same bytes
    result = run(*args)
    assert result.exit_code == 0, result.output
    again = snapshot(out)
    assert {n: b for n, (_, b) in again.items()} == {n: b for n, (_, b) in first.items()}
    # the file written last, edited by hand: refused before any work, nothing replaced
    last = max(again, key=lambda n: (os.stat(out / n).st_mtime_ns, n))
    (out / last).write_bytes(b"mine")
    kept = snapshot(out)
    result, entered = run_watching(args)
    refused(result, Path(last).name, "weave-cut did not write it", "--force")
    assert not entered and snapshot(out) == kept
    # no manifest at all (a folder weave-cut never wrote into): every file is the maker's
    (home / MANIFEST).unlink()
    (out / last).write_bytes(again[last][1])
    kept = snapshot(out)
    result, entered = run_watching(args)
    refused(result, "weave-cut did not write it", "--force")
    assert not entered and snapshot(out) == kept
    # --force: replaced, and listed as weave-cut's again
    assert run(*args, "--force").exit_code == 0
    forced = snapshot(out)
    assert {n: b for n, (_, b) in forced.items()} == {n: b for n, (_, b) in first.items()}
    assert json.loads((home / MANIFEST).read_text())["files"] == listed


def test_a_makers_readme_in_the_puzzle_folder_is_kept(world):
    """Issue #29: ``puzzle -o FOLDER`` replaced the maker's README.txt without a word."""
    kit = world / "out" / "kit"
    kit.mkdir()
    (kit / "README.txt").write_text("my notes")
    result = run("puzzle", "-n", "2", "--mode", "shared", "-o", kit)
    refused(result, f"{kit / 'README.txt'} exists and weave-cut did not write it", "--force")
    assert files_under(kit) == {"README.txt"} and (kit / "README.txt").read_text() == "my notes"



@pytest.mark.parametrize("preview", [[], ["--preview"]])
def test_the_puzzle_checks_only_the_files_it_writes(world, preview):
    """Walk of issue #29: ``puzzle --preview`` refused a folder holding the maker's
    README.txt (or a guide of an earlier run) though it writes only puzzle-preview.svg. What
    the command says it may replace (``beside``) is what a run writes: a stray file of any
    other name, the maker's or weave-cut's, neither refuses the run nor is touched."""
    kit = world / "out" / "kit"
    args = ("puzzle", "-n", "2", "--mode", "shared", *preview, "-o", kit)
    assert run(*args).exit_code == 0
    wrote = files_under(kit) - {MANIFEST}
    command = cli.commands["puzzle"]
    values = command.make_context("puzzle", [str(a) for a in args[1:]]).params
    assert {p.name for p in command.beside(values)} == wrote
    other = world / "out" / "other"
    other.mkdir()
    strays = {"README.txt", "puzzle-front-guide.svg", "puzzle-notes.txt", "puzzle-preview.svg",
              "puzzle-3d.glb.bak"} - wrote
    for name in strays:
        (other / name).write_text("mine")
    assert run(*args[:-1], other).exit_code == 0
    assert {n: (other / n).read_text() for n in strays} == dict.fromkeys(strays, "mine")
    assert files_under(other) - {MANIFEST} == wrote | strays


@pytest.mark.parametrize("command", sorted(n for n in cli.commands if n != "build"
                                           and path_options(cli.commands[n])))
def test_a_recipe_cannot_say_force(tmp_path, command):
    """Only the person running the build gives --force: not an untrusted recipe."""
    (tmp_path / "r.toml").write_text(job(command, "output", "x") + "force = true\n")
    refused(run("build", tmp_path / "r.toml", "-o", tmp_path / "out"), "unknown key 'force'")
    (tmp_path / "r.toml").write_text(RECIPE)
    refused(run("build", tmp_path / "r.toml", "-o", tmp_path / "out", "--set", "force=true"),
            "no job has an option 'force'", status=(2,))
    assert files_under(tmp_path) == {"r.toml"}


def test_a_symlink_in_the_way_is_never_replaced(world):
    target = world / "t" / "elsewhere.svg"
    target.write_text("mine")
    (world / "out" / "s.svg").symlink_to(target)
    for force in ([], ["--force"]):
        refused(run("subdivide", "pentagon", "-o", world / "out" / "s.svg", *force),
                "is a symlink")
    assert target.read_text() == "mine" and (world / "out" / "s.svg").is_symlink()


# --- the examples people copy -----------------------------------------------------------------

ROOT = Path(__file__).resolve().parents[1]
PLACEHOLDERS = re.compile(r"^(INPUT|DIR|RECIPE|PAGE|FILE|NAME|KEY=VALUE|\[.*|.*\.\.\.)$")


def examples() -> list[str]:
    """Every ``weave-cut COMMAND ...`` line of the README (code spans and blocks, continued
    lines joined) and of every command's --help."""
    text = (ROOT / "README.md").read_text(encoding="utf-8").replace("\\\n", " ")
    lines = re.findall(r"`(weave-cut [a-z][^`\n]*)`", text)
    lines += re.findall(r"^(weave-cut [a-z][^\n]*)$", text, re.M)
    for name in sorted(cli.commands):
        lines += re.findall(r"^\s+(weave-cut [a-z][^\n]*)$", cli.commands[name].help or "",
                            re.M)
    found = []
    for line in lines:
        words = shlex.split(line.split("#")[0])
        words = words[:next((i for i, w in enumerate(words) if w in (">", "|")), len(words))]
        if (words[1] in cli.commands and len(words) > 2  # (not a command named in prose)
                and not any(PLACEHOLDERS.match(w) for w in words[2:])):
            found.append(shlex.join(words[1:]))
    return sorted(set(found))


EXAMPLES = examples()


def test_the_examples_are_found():
    assert "puzzle -o puzzle --material poplar-3mm --numbers" in EXAMPLES
    assert {e.split()[0] for e in EXAMPLES} == set(cli.commands) - {"inputs"}  # (no args)


@pytest.mark.parametrize("line", EXAMPLES)
def test_every_example_command_follows_the_rules_in_a_fresh_folder(tmp_path, monkeypatch, line):
    """Every command the README or a --help shows parses (lengths with units, names that
    exist) and writes where the rules let it in an empty folder (no folder above an output
    missing, no folder named like a file): copied into a terminal, it works."""
    monkeypatch.chdir(tmp_path)
    name, *args = shlex.split(line)
    for i, word in enumerate(args[:-1]):
        if word == "--allow-read":
            (tmp_path / args[i + 1]).mkdir()
    command = cli.commands[name]
    try:
        ctx = command.make_context(name, list(args))
    except click.ClickException as exc:
        pytest.fail(f"weave-cut {line}: {exc.format_message()}")
    for option, path in written(command, ctx.params):
        made = {os.path.abspath(p) for o, p in written(command, ctx.params)
                if is_folder(o, ctx.params)}
        assert problem(path, is_folder(option, ctx.params),
                       os.path.dirname(os.path.abspath(path)) in made) is None, line


def test_a_page_into_the_folder_the_command_makes_is_no_missing_folder(world):
    """`puzzle -o kit --html kit/index.html` (the README's): kit is made by the run itself."""
    kit = world / "out" / "kit"
    result = run("puzzle", "-n", "2", "--preview", "-o", kit, "--html", kit / "index.html")
    assert result.exit_code == 0, result.output
    assert files_under(kit) == {"index.html", "puzzle-preview.svg", MANIFEST}
    refused(run("puzzle", "-n", "2", "--preview", "-o", kit, "--html",
                world / "out" / "elsewhere" / "index.html"), "elsewhere' does not exist",
            status=(2,))


def _listed(home: Path) -> set[str]:
    return set(json.loads((home / MANIFEST).read_text())["files"])


def test_a_rerun_removes_the_sheets_it_no_longer_needs_and_nothing_else(world):
    """``puzzle -o FOLDER`` cut on 300 x 200 mm sheets needs 8, on 600 x 600 mm 2: the rerun
    removes sheets 3-8, which weave-cut wrote last time, and keeps the maker's notes; a stale
    sheet the maker edited since is kept (with --force, as the rerun would replace it) and is
    no longer listed as weave-cut's."""
    kit = world / "out" / "kit"
    small = ("puzzle", "-n", "2", "--mode", "separate", "--sheet", "300x200mm", "-o", kit)
    large = ("puzzle", "-n", "2", "--mode", "separate", "--sheet", "600x600mm", "-o", kit)
    sheets = {f"puzzle-separate-sheet-{n}.{s}" for n in range(3, 9) for s in ("svg", "dxf")}
    assert run(*small).exit_code == 0 and sheets <= files_under(kit)
    (kit / "notes.txt").write_text("my notes")
    assert run(*large).exit_code == 0
    assert not sheets & files_under(kit) and "puzzle-separate-sheet-2.svg" in files_under(kit)
    assert (kit / "notes.txt").read_text() == "my notes"
    assert _listed(kit) == files_under(kit) - {"notes.txt", MANIFEST}
    assert run(*small).exit_code == 0 and sheets <= files_under(kit)
    (kit / "puzzle-separate-sheet-8.svg").write_text("mine")
    assert run(*large, "--force").exit_code == 0
    assert files_under(kit) & sheets == {"puzzle-separate-sheet-8.svg"}
    assert (kit / "puzzle-separate-sheet-8.svg").read_text() == "mine"
    assert _listed(kit) == files_under(kit) - {"notes.txt", "puzzle-separate-sheet-8.svg",
                                               MANIFEST}


def test_a_rerun_removes_the_cut_files_of_pages_it_no_longer_prints(world):
    """``strands --cutter -o FILE``: at 60 mm tiles the strips take pages 3-5, at 20 mm page 3
    only; the rerun removes the cut files of pages 4-5 beside the PDF, not those of another
    PDF in the folder (its own -o's)."""
    out = world / "out"
    line = ("strands", "square-grid:3x3", "-n", "1", "--cutter", "silhouette", "-o")
    assert run(*line, out / "other.pdf", "--tile-size", "60mm").exit_code == 0
    assert run(*line, out / "c.pdf", "--tile-size", "60mm").exit_code == 0
    pages = {f"c-p0{n}-cut.{s}" for n in (4, 5) for s in ("svg", "dxf")}
    assert pages <= files_under(out)
    assert run(*line, out / "c.pdf", "--tile-size", "20mm").exit_code == 0
    assert not pages & files_under(out) and "c-p03-cut.svg" in files_under(out)
    assert {f"other-p0{n}-cut.svg" for n in (3, 4, 5)} <= files_under(out)
    assert _listed(out) == files_under(out) - {MANIFEST}
