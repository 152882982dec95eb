"""The ``weave-cut`` command line. ``main`` is the console entry point; it is light on purpose:
signals are handled and the working folder checked before the commands (numpy, shapely, ...)
are imported, so Ctrl-C at any moment ends in one line.

Errors: a WeaveCutError is one line on stderr and exit status 1; a bad option is click's
usage error and exit status 2. Nothing prints a traceback.
"""

from __future__ import annotations

import os
import sys

import _signal  # builtin: no import time (``signal`` itself imports enum)

# OpenBLAS starts a thread per core when numpy is imported and keeps them spinning after every
# call: 0.07-0.13 s of CPU per command for arrays far too small to share (a whole kit's CPU
# time, 1.0 -> 0.9 s for the puzzle). One thread, unless the caller asks for more; before
# anything imports numpy. Its results do not change (tests/test_determinism.py).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

INTERRUPTED = "weave-cut: interrupted; no output was left half-written"


def _interrupted_while_loading(signum, frame) -> None:
    os.write(2, f"{INTERRUPTED}\n".encode())
    os._exit(130)


if os.path.basename(sys.argv[0] if sys.argv else "") == "weave-cut":  # the console script
    _signal.signal(_signal.SIGINT, _interrupted_while_loading)

import errno  # noqa: E402
import signal  # noqa: E402
# a write to stdout or a file that fails for want of room or a reader, not for a bug
_NO_ROOM = {errno.ENOSPC, errno.EPIPE, errno.EIO, errno.EFBIG, errno.EDQUOT, errno.EBADF}


def __getattr__(name: str):
    if name == "cli":  # ``from weavecut.cli import cli`` imports the commands on first use
        from .app import cli

        return cli
    raise AttributeError(name)


def _terminate(signum, frame) -> None:
    raise KeyboardInterrupt


def _say(message: str) -> None:
    try:
        sys.stderr.write(f"weave-cut: {message}\n")
        sys.stderr.flush()
    except OSError:
        pass


def _stdout_gone(exc: OSError) -> int:
    """Report a failed write to stdout once, and silence the flush at exit."""
    why = "stdout is closed" if exc.errno == errno.EBADF else exc.strerror or exc
    _say(f"error: cannot write the output: {why}")
    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, ValueError):
        pass
    return 1


def _closed_streams() -> None:
    """Stand in for a closed stdout or stderr (``weave-cut inputs >&-``; Python then sets
    ``sys.stdout`` to None): /dev/null takes the descriptor, so no file weave-cut opens gets
    it, read-only for stdout, so the first write fails as on a closed one and is reported
    in one line, and writable for stderr, whose lines have nowhere to go."""
    import io

    for fd, name, flags in ((1, "stdout", os.O_RDONLY), (2, "stderr", os.O_WRONLY)):
        if getattr(sys, name) is None:
            null = os.open(os.devnull, flags)
            if null != fd:
                os.dup2(null, fd)
                os.close(null)
            setattr(sys, name, io.TextIOWrapper(io.FileIO(fd, "w", closefd=False),
                                                line_buffering=True))


def main(argv: list[str] | None = None) -> None:
    """Console entry point: run ``cli`` and turn anything unexpected into one line."""
    _closed_streams()
    # SIGTERM, SIGHUP (terminal closed) and SIGQUIT clean up temporary files like Ctrl-C does;
    # Ctrl-C while the commands load exits at once (nothing is written yet)
    for sig in (signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT):
        signal.signal(sig, _terminate)
    signal.signal(signal.SIGINT, _interrupted_while_loading)
    code: int | str | None = 0
    try:
        try:
            os.getcwd()
        except OSError:
            _say("error: the working folder no longer exists; cd to another one")
            sys.exit(1)
        from ..subdivision.hierarchy import keep_freed_memory
        from .app import cli

        keep_freed_memory()  # big levels reuse freed pages instead of faulting in new ones
        signal.signal(signal.SIGINT, signal.default_int_handler)
        import click

        try:  # not click's standalone mode: it ends a Ctrl-C while parsing in "Aborted!", 1
            returned = cli.main(args=argv, prog_name="weave-cut", standalone_mode=False)
            code = returned if isinstance(returned, int) else 0  # click's Exit, --help
        except click.ClickException as exc:
            exc.show()
            code = exc.exit_code
        except click.Abort:
            raise KeyboardInterrupt from None
    except SystemExit as exc:
        code = exc.code
    except KeyboardInterrupt:
        _say(INTERRUPTED.removeprefix("weave-cut: "))
        code = 130
    except MemoryError:
        _say("error: out of memory; try fewer levels")
        code = 1
    except Exception as exc:  # a bug: still one line, unless asked for the traceback
        if isinstance(exc, OSError) and exc.errno in _NO_ROOM:
            code = _stdout_gone(exc)
        elif os.environ.get("WEAVECUT_DEBUG"):
            raise
        else:
            _say(f"internal error: {type(exc).__name__}: {exc} (set WEAVECUT_DEBUG=1 for a "
                 "traceback)")
            code = 1
    try:
        sys.stdout.flush()
    except OSError as exc:
        code = _stdout_gone(exc)
    sys.exit(code)
