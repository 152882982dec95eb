"""``weave-cut build RECIPE``: run the jobs of a recipe into one folder, each checked first
(``recipe.Planner``), then write the folder's kit page (``weavecut.kitpage``)."""

from __future__ import annotations

from pathlib import Path

import click

from ..fileio import make_folder, protect
from ..manifest import file_hash, record_manifest
from ..schema import RECIPE, nearest, read_toml
from .common import CONTEXT, complete_preset, force_option, reports_errors
from .outputs import forced
from .recipe import PAGE, Planner, RecipeError, find_recipe


@click.command("build", context_settings=CONTEXT)
@click.argument("recipe", metavar="RECIPE", shell_complete=complete_preset("recipes"))
@click.option("-o", "--output-dir", type=click.Path(file_okay=False), default="build",
              show_default=True, help="Folder for the outputs; every output lands inside it.")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help="Override an option in every job that has it (repeatable).")
@click.option("--allow-read", multiple=True, metavar="DIR",
              type=click.Path(file_okay=False, exists=True, path_type=Path),
              help="Also read inputs from DIR (default: the recipe's folder only; repeatable).")
@force_option
@click.option("--dry-run", is_flag=True,
              help="Check the recipe and print every job and output path without running.")
@click.pass_context
@reports_errors
def build_command(ctx: click.Context, recipe: str, output_dir: str, overrides: tuple[str, ...],
                  allow_read: tuple[Path, ...], dry_run: bool) -> None:
    """Run every job of RECIPE (a .toml file, or a recipe name from templates/recipes) into a
    folder. The whole recipe is checked before the first job runs.

    \b
    Examples:
      weave-cut build jigsaw-50cm-poplar -o out --set kerf=0.2mm
      weave-cut build templates/recipes/square-grid-paper-model.toml --dry-run
      weave-cut build examples/house.toml -o house --allow-read shared-meshes
    """
    parsed = {}
    for item in overrides:
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            raise click.BadParameter(f"{item!r} is not KEY=VALUE", param_hint="'--set'")
        parsed[key.strip().replace("_", "-")] = value.strip()
    path = find_recipe(recipe)
    doc = read_toml(path, RecipeError)
    RECIPE.check(doc, str(path), RecipeError)
    out_dir = Path(output_dir).absolute()
    planner = Planner(ctx.parent.command, ctx.parent, path, out_dir, output_dir, allow_read,
                      forced())
    known = {k for job in doc["job"] for c in [planner.commands().get(job["command"])] if c
             for k in planner.options(c)}
    for key in parsed:
        if key not in known or key == "output":
            raise click.BadParameter(f"no job has an option {key!r}{nearest(key, known)}",
                                     param_hint="'--set'")
    jobs = [planner.plan(n, job, parsed) for n, job in enumerate(doc["job"], start=1)]
    planner.check_outputs(jobs)
    if dry_run:
        for job in jobs:
            click.echo(job.command_line())
        return
    make_folder(out_dir)  # locks the folder: another weave-cut writing there is waited for
    planner.check_outputs(jobs)
    for job in jobs:
        for p in job.reads:
            protect(p)
    runs = [planner.run(job, n, len(jobs)) for n, job in enumerate(jobs, start=1)]
    page = out_dir / PAGE
    from .. import kitpage

    kitpage.write(page, (doc.get("recipe") or {}).get("name") or path.stem, runs)
    record_manifest(out_dir, {PAGE: file_hash(page)})
