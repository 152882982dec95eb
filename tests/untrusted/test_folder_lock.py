"""Two weave-cut processes never write one folder at once: the first write of a command locks
the folder of every path option it writes (``fileio.writing_into``); a second writer waits,
saying so on stderr, at most ``fileio.LOCK_WAIT`` seconds, then is refused."""

from __future__ import annotations

import fcntl
import os
import select
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from weavecut import fileio
from weavecut.cli import cli
from weavecut.cli.common import path_options

from .helpers import files_under, refused, run

pytestmark = pytest.mark.slow  # whole builds in concurrent processes

TILES = ["pentagon", "--size", "256", "--tile-size", "16", "-j", "1"]  # 345 tiles, one by one


def contents(folder: Path) -> dict[str, bytes]:
    return {n: (folder / n).read_bytes() for n in files_under(folder)}


def weave_cut(*args, cwd=None) -> subprocess.Popen:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    return subprocess.Popen([sys.executable, "-m", "weavecut", *map(str, args)], env=env,
                            cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True)


def first_line(process: subprocess.Popen, bound: float = 300.0) -> str:
    """The first line ``process`` writes to stderr ('' if it ends first; bounded, so a test
    that would hang fails instead)."""
    ready, _, _ = select.select([process.stderr], [], [], bound)
    return process.stderr.readline() if ready else ""


# ``python -c STOPS WHERE ARGS...``: weave-cut ARGS, stopping itself (SIGSTOP) once at its
# first tile, before the rename (its temporary file lies in the folder) or after it
STOPS = """
import os, signal, sys
where, rename, stopped = sys.argv[1], os.replace, []
def replace(src, dst, *args, **kwargs):
    first = str(dst).endswith(".png") and not stopped
    if first and where == "before":
        stopped.append(os.kill(os.getpid(), signal.SIGSTOP))
    rename(src, dst, *args, **kwargs)
    if first and where == "after":
        stopped.append(os.kill(os.getpid(), signal.SIGSTOP))
os.replace = replace
sys.argv = ["weave-cut", *sys.argv[2:]]
from weavecut.cli import main
main()
"""


@pytest.mark.parametrize("where", ["after", "before"])
def test_a_second_writer_waits_and_the_folder_holds_one_whole_run(tmp_path, where):
    """The first run stops itself mid-run, at a known point (no race with the test's clock):
    just after a tile, or with a tile's temporary file in the folder, which is gone when the
    second gets the folder (the second refused it as a file weave-cut did not write)."""
    expected = {}
    for levels in (2, 3):  # the same tiles, other colours
        assert run("levels", *TILES, "-n", levels, "--tiles", tmp_path / f"r{levels}"
                   ).exit_code == 0
        expected[levels] = contents(tmp_path / f"r{levels}")
    assert expected[2].keys() == expected[3].keys() and expected[2] != expected[3]
    folder = tmp_path / "tiles"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    first = subprocess.Popen([sys.executable, "-c", STOPS, where, "levels", *TILES, "-n", "2",
                              "--tiles", str(folder)], env=env, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
    try:
        _, status = os.waitpid(first.pid, os.WUNTRACED)  # until it stops (or ends)
        assert os.WIFSTOPPED(status), (status, first.stderr.read())
        assert not (folder / "levels.dzi").exists()  # written last: the first is not done
        parts = list(folder.rglob(".wc-*.part"))
        assert len(parts) == (where == "before")
        second = weave_cut("levels", *TILES, "-n", 3, "--tiles", folder)
        said = first_line(second)
    finally:
        first.send_signal(signal.SIGCONT)
    assert said.startswith(f"weave-cut: waiting for another weave-cut writing into {folder}")
    assert first.wait() == 0 and second.wait() == 0, second.stderr.read()
    assert contents(folder) == expected[3]  # the second run whole, none of the first left


def test_two_builds_at_once_leave_one_builds_files(tmp_path):
    """Two builds of different puzzles into one folder, started together: the folder ends
    byte for byte as one of them writes it alone (never one puzzle's summary beside the other's
    cut files), with both exiting 0."""
    for size in ("30cm", "40cm"):
        (tmp_path / f"{size}.toml").write_text(
            f'[[job]]\ncommand = "puzzle"\noutput = "."\nlevels = 2\nsize = "{size}"\n'
            'mode = "shared"\n')
    args = {size: ("build", f"../{size}.toml", "-o", "out") for size in ("30cm", "40cm")}
    alone = {}
    for size in args:  # the same command lines (they are in the files), one at a time
        (tmp_path / size).mkdir()
        assert weave_cut(*args[size], cwd=tmp_path / size).wait() == 0
        alone[size] = contents(tmp_path / size / "out")
    assert alone["30cm"].keys() == alone["40cm"].keys()
    (tmp_path / "both").mkdir()
    both = [weave_cut(*a, cwd=tmp_path / "both") for a in args.values()]
    assert [p.wait() for p in both] == [0, 0], [p.stderr.read() for p in both]
    assert contents(tmp_path / "both" / "out") in alone.values()


@pytest.fixture
def held(tmp_path, monkeypatch):
    """A folder another process holds (this test, through its own file description), and a
    short wait."""
    folder = tmp_path / "busy"
    folder.mkdir()
    fd = os.open(folder, os.O_RDONLY)
    fcntl.flock(fd, fcntl.LOCK_EX)
    monkeypatch.setattr(fileio, "LOCK_WAIT", 0.3)
    yield folder
    os.close(fd)


# every path option of every command, written into the held folder
WRITERS = {
    ("subdivide", "output"): ["subdivide", "pentagon", "-n", "1", "-o", "{d}/s.svg"],
    ("weave", "output"): ["weave", "square-grid", "-n", "1", "-o", "{d}/w.svg"],
    ("weave", "html"): ["weave", "square-grid", "-n", "1", "-o", "{t}/w.svg", "--html",
                        "{d}/w.html"],
    ("puzzle", "out_dir"): ["puzzle", "-n", "2", "--mode", "shared", "-o", "{d}"],
    ("puzzle", "html"): ["puzzle", "-n", "2", "--mode", "shared", "-o", "{t}/p", "--html",
                         "{d}/p.html"],
    ("strands", "output"): ["strands", "square-grid", "-o", "{d}/s.pdf"],
    ("strands", "html"): ["strands", "square-grid", "-o", "{t}/s.pdf", "--html", "{d}/s.html"],
    ("fractal", "output"): ["fractal", "pentagon", "-n", "2", "-o", "{d}/f.svg"],
    ("levels", "output"): ["levels", "pentagon", "-n", "2", "--size", "64", "-o", "{d}/l.png"],
    ("levels", "tiles"): ["levels", "pentagon", "-n", "2", "--size", "64", "--tiles", "{d}"],
    ("convexity", "output"): ["convexity", "pentagon", "-n", "2", "-o", "{d}/c.svg"],
    ("figure", "output"): ["figure", "z-triplet", "-o", "{d}/f.svg"],
    ("build", "output_dir"): ["build", "{t}/r.toml", "-o", "{d}"],
}


def test_the_table_has_every_path_option_of_every_command():
    assert set(WRITERS) == {(n, p.name) for n in cli.commands
                            for p in path_options(cli.commands[n])}


@pytest.mark.parametrize("writer", sorted(WRITERS), ids="-".join)
def test_every_writing_command_waits_for_the_folder_then_is_refused(tmp_path, held, writer):
    (tmp_path / "r.toml").write_text('[[job]]\ncommand = "stats"\ninput = "pentagon"\n'
                                     'output = "s.txt"\n')
    args = [a.format(d=held, t=tmp_path) for a in WRITERS[writer]]
    result = run(*args)
    assert f"weave-cut: waiting for another weave-cut writing into {held}" in result.output
    refused(result, "another weave-cut has been writing into", str(held), "0.3 s")
    assert files_under(held) == set()


def test_a_build_holds_its_folder_through_every_job_and_the_manifest(tmp_path):
    """The build locks the folder once; its jobs and the manifest writer take the same lock
    again in this process without waiting for themselves."""
    recipe = tmp_path / "r.toml"
    recipe.write_text('[[job]]\ncommand = "stats"\ninput = "pentagon"\noutput = "s.txt"\n'
                      '[[job]]\ncommand = "subdivide"\ninput = "pentagon"\nlevels = 1\n'
                      'output = "sub/p.svg"\n')
    result = run("build", recipe, "-o", tmp_path / "out")
    assert result.exit_code == 0 and "waiting" not in result.output, result.output
    assert fileio._LOCKS.held == {} and fileio._LOCKS.roots == []  # all released
