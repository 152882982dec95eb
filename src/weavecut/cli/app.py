"""The ``weave-cut`` click group: every command, each a thin shell over the library, imported
when it is first used (``lazy.LazyCommands``)."""

from __future__ import annotations

import click

from .. import __version__
from .common import CONTEXT
from .lazy import LazyCommands


@click.group(context_settings=CONTEXT)
@click.version_option(__version__, prog_name="weave-cut")
@click.option("-q", "--quiet", is_flag=True,
              help="No progress or summaries: stdout holds only what was asked for (--json).")
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


cli.commands = LazyCommands({
    "inputs": ".mesh_commands:inputs_command",
    "subdivide": ".mesh_commands:subdivide_command",
    "stats": ".mesh_commands:stats_command",
    "weave": ".weave_command:weave_command",
    "puzzle": ".puzzle_command:puzzle_command",
    "strands": ".strands_command:strands_command",
    "fractal": ".analysis_commands:fractal_command",
    "levels": ".analysis_commands:levels_command",
    "convexity": ".analysis_commands:convexity_command",
    "figure": ".analysis_commands:figure_command",
    "findings": ".findings_command:findings_command",
    "build": ".build_command:build_command",
    "serve": ".serve_command:serve_command",
    "worker": ".worker_command:worker_command",
})
