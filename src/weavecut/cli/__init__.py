"""The ``weave-cut`` command: a click group whose commands are thin shells over the library.

Errors: a WeaveCutError is one line on stderr and exit status 1; a bad option is click's
usage error and exit status 2. Nothing prints a traceback.
"""

from __future__ import annotations

import os
import signal
import sys

import click

from .. import __version__
from .build_command import build_command
from .findings_command import findings_command
from .common import CONTEXT
from .analysis_commands import COMMANDS as ANALYSIS_COMMANDS
from .mesh_commands import inputs_command, stats_command, subdivide_command
from .puzzle_command import puzzle_command
from .strands_command import strands_command
from .weave_command import weave_command


@click.group(context_settings=CONTEXT)
@click.version_option(__version__, prog_name="weave-cut")
@click.option("-q", "--quiet", is_flag=True, help="No progress output.")
@click.pass_context
def cli(ctx: click.Context, quiet: bool) -> None:
    """Pentagon snub subdivision, its weaving patterns, paper strand models and laser-cut
    jigsaw puzzles (Lipschuetz, Reitebuch, Skrodzki, Polthier).

    \b
    Examples:
      weave-cut inputs
      weave-cut subdivide pentagon --levels 4 -o pentagon.svg
      weave-cut stats pentagon --levels 6 --json

    Shell completion (bash): eval "$(_WEAVE_CUT_COMPLETE=bash_source weave-cut)"
    """
    ctx.meta["weavecut.quiet"] = quiet or ctx.meta.get("weavecut.quiet", False)


for command in (inputs_command, subdivide_command, stats_command, weave_command,
                puzzle_command, strands_command, *ANALYSIS_COMMANDS, findings_command,
                build_command):
    cli.add_command(command)


def _terminate(signum, frame) -> None:
    raise KeyboardInterrupt


def main(argv: list[str] | None = None) -> None:
    """Console entry point: run ``cli`` and turn anything unexpected into one line."""
    signal.signal(signal.SIGTERM, _terminate)  # clean up temporary files like Ctrl-C does
    try:
        cli.main(args=argv, prog_name="weave-cut", standalone_mode=True)
    except KeyboardInterrupt:
        click.echo("weave-cut: interrupted; no output was left half-written", err=True)
        sys.exit(130)
    except MemoryError:
        click.echo("weave-cut: error: out of memory; try fewer levels", err=True)
        sys.exit(1)
    except Exception as exc:  # a bug: still one line, unless asked for the traceback
        if os.environ.get("WEAVECUT_DEBUG"):
            raise
        click.echo(f"weave-cut: internal error: {type(exc).__name__}: {exc} "
                   "(set WEAVECUT_DEBUG=1 for a traceback)", err=True)
        sys.exit(1)
