"""The console entry point, ``weavecut.cli.main``, run in this process (test_environment runs it
as a program, where mutation testing cannot reach it): whatever goes wrong before, during or
after a command is one line on stderr and the documented exit status."""

from __future__ import annotations

import signal

import pytest

from weavecut.cli import main

SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


@pytest.fixture
def entry(capsys):
    """Run ``main(argv)``: (exit status, stdout, stderr); the signal handlers it sets are put
    back afterwards."""
    def call(*argv: str) -> tuple[object, str, str]:
        handlers = {s: signal.getsignal(s) for s in SIGNALS}
        try:
            with pytest.raises(SystemExit) as exit_:
                main(list(argv))
        finally:
            for s, handler in handlers.items():
                signal.signal(s, handler)
        out, err = capsys.readouterr()
        return exit_.value.code, out, err

    return call


def test_a_working_folder_since_deleted_is_one_line_before_any_command(tmp_path, monkeypatch,
                                                                       entry):
    gone = tmp_path / "gone"
    gone.mkdir()
    monkeypatch.chdir(gone)
    gone.rmdir()
    assert entry("stats", "pentagon") == (
        1, "", "weave-cut: error: the working folder no longer exists; cd to another one\n")


def test_a_commands_error_is_its_line_and_status_1(entry):
    code, out, err = entry("stats", "no-such-input")
    assert (code, out) == (1, "") and len(err.splitlines()) == 1
    assert err.startswith("Error: ") and "no-such-input" in err


def test_ctrl_c_while_the_options_are_read_is_the_interrupted_line_and_130(monkeypatch, entry):
    """Not click's "Aborted!" and status 1: the same line as a Ctrl-C during the work."""
    from weavecut.cli.common import Length

    def interrupted(*args):
        raise KeyboardInterrupt

    monkeypatch.setattr(Length, "convert", interrupted)
    code, out, err = entry("strands", "square-grid", "--margin", "5mm", "-o", "x.pdf")
    assert (code, out) == (130, "")  # click ends the line the terminal's ^C began
    assert err == "\nweave-cut: interrupted; no output was left half-written\n"


def test_running_out_of_memory_is_one_line_and_status_1(monkeypatch, entry):
    import weavecut.subdivision.hierarchy as hierarchy

    def no_memory():
        raise MemoryError

    monkeypatch.setattr(hierarchy, "keep_freed_memory", no_memory)
    assert entry("inputs") == (1, "", "weave-cut: error: out of memory; try fewer levels\n")


def test_a_command_that_runs_is_status_0(entry):
    code, out, err = entry("inputs")
    assert (code, err) == (0, "") and "\npentagon " in out
