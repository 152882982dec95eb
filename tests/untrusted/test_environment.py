"""Odd environments: a read-only or missing folder, stdout on a full device, long names, a
deleted working folder, and Ctrl-C while the modules load (one line). SIGHUP and SIGQUIT
cleaning up like SIGTERM: tests/test_fuzz.py."""

from __future__ import annotations

import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from weavecut.manifest import MANIFEST

from .helpers import refused, run

COMMAND = str(Path(sys.executable).with_name("weave-cut"))


def _denied(*args, **kwargs):
    raise PermissionError(13, "Permission denied")


@pytest.mark.parametrize("args", [["puzzle", "-o", "{d}/pz", "--levels", "2"],
                                  ["build", "jigsaw-50cm-poplar", "-o", "{d}/b"]])
def test_read_only_folder(tmp_path, monkeypatch, args):
    monkeypatch.setattr(Path, "mkdir", _denied)  # as root, chmod would not stop us
    refused(run(*[a.format(d=tmp_path) for a in args]), "cannot create folder",
            "Permission denied")


def test_read_only_folder_for_a_file(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "mkstemp", _denied)
    refused(run("subdivide", "pentagon", "-o", tmp_path / "x.svg"), "cannot write to")
    assert not list(tmp_path.iterdir())


def test_output_folder_is_a_file(tmp_path):
    (tmp_path / "f").write_text("x")
    refused(run("puzzle", "-o", tmp_path / "f" / "pz", "--levels", "2"), "f' is a file, not a "
            "folder", status=(2,))


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="needs /dev/full")
@pytest.mark.parametrize("args", [["stats", "pentagon", "--levels", "6"],
                                  ["inputs", "--json"], ["--help"]])
def test_stdout_on_a_full_device(args):
    with open("/dev/full", "w") as full:
        proc = subprocess.run([COMMAND, *args], stdout=full, stderr=subprocess.PIPE,
                              text=True, timeout=120)
    assert proc.returncode == 1
    assert proc.stderr.strip() == ("weave-cut: error: cannot write the output: No space left "
                                   "on device"), proc.stderr


def test_long_output_names(tmp_path):
    name = "p" * 251 + ".svg"  # 255 bytes: the longest name the file system takes
    result = run("subdivide", "pentagon", "-o", tmp_path / name)
    assert result.exit_code == 0, result.output
    refused(run("subdivide", "pentagon", "-o", tmp_path / ("p" * 300 + ".svg")),
            "too long for a file system", "(this one 304)", status=(2,))
    assert sorted(p.name for p in tmp_path.iterdir()) == [MANIFEST, name]


def test_deleted_working_folder(tmp_path):
    gone = tmp_path / "gone"
    gone.mkdir()
    proc = subprocess.run(["sh", "-c", 'cd "$1" && rmdir "$1" && exec "$2" stats pentagon',
                           "sh", str(gone), COMMAND], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 1
    assert proc.stderr == "weave-cut: error: the working folder no longer exists; cd to " \
                          "another one\n"


def test_interrupt_handler_is_in_place_before_the_heavy_imports():
    code = ("import sys, signal; sys.argv[0] = 'weave-cut'; import weavecut.cli as c; "
            "assert signal.getsignal(signal.SIGINT) is c._interrupted_while_loading; "
            "heavy = {'numpy', 'click', 'shapely', 'scipy', 'reportlab', 'ezdxf'}; "
            "print(sorted(heavy & set(sys.modules)))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "[]"


@pytest.mark.parametrize("delay", [0.3, 0.6])
def test_ctrl_c_while_loading_is_one_line(tmp_path, delay):
    proc = subprocess.Popen([COMMAND, "subdivide", "pentagon", "--levels", "7", "-o",
                             str(tmp_path / "x.svg")], stderr=subprocess.PIPE, text=True)
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
    assert proc.returncode in (0, 130, -signal.SIGINT), err
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".part")]


def test_an_interrupt_while_click_parses_is_one_line_and_130(monkeypatch, capsys):
    """Ctrl-C while click reads the options (the command not yet started) is the same line and
    status as anywhere else, not click's "Aborted!" and 1 (a race the test above hit once)."""
    import click

    from weavecut import cli as package
    from weavecut.cli import app

    def parse_interrupted(**_):
        raise click.Abort()

    monkeypatch.setattr(package.signal, "signal", lambda *args: None)  # this process's own
    monkeypatch.setattr(app.cli, "main", parse_interrupted)
    with pytest.raises(SystemExit) as exit_:
        package.main(["stats", "pentagon"])
    err = capsys.readouterr().err
    assert exit_.value.code == 130 and err == f"{package.INTERRUPTED}\n"
