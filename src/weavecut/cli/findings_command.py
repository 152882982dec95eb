"""``weave-cut findings``: what the tool measures about the paper, as a Markdown or JSON table."""

from __future__ import annotations

import json

import click

from .common import CONTEXT, reports_errors


@click.command("findings", context_settings=CONTEXT)
@click.option("--json", "as_json", is_flag=True, help="Print JSON instead of Markdown.")
@click.option("--fast", is_flag=True, help="Skip the slow findings (level 7 of every input, "
              "levels 7-10 of the pentagon: a few minutes and about 3.5 GB).")
@reports_errors
def findings_command(as_json: bool, fast: bool) -> None:
    """Measure the paper's claims and open questions, and print every finding with the numbers
    measured and a command that repeats it. The README's findings section is this output.

    \b
    Examples:
      weave-cut findings --fast
      weave-cut findings --json > findings.json
    """
    from ..analysis import findings as fd

    rows = fd.findings(fast=fast)
    if as_json:
        click.echo(json.dumps(fd.as_json(rows), indent=2, ensure_ascii=False, allow_nan=False))
        return
    click.echo(fd.markdown(rows), nl=False)
