"""The ``weave-cut`` click group: every command, each a thin shell over the library."""

from __future__ import annotations

import click

from .. import __version__
from .build_command import build_command
from .common import CONTEXT
from .analysis_commands import COMMANDS as ANALYSIS_COMMANDS
from .findings_command import findings_command
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
