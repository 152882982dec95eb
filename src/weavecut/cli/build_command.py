"""``weave-cut build RECIPE.toml``: run the jobs of a recipe, as if typed on the command line.

A recipe is TOML with one ``[[job]]`` table per output::

    [[job]]
    command = "weave"                 # any weave-cut command
    input = "square-grid"             # its INPUT (a mesh file is read beside the recipe)
    output = "square-weave.svg"       # -o, relative to the build folder
    levels = 2                        # every other key is an option of that command
    outline-level = 1                 # (dashes or underscores; true for a flag)

``--set KEY=VALUE`` overrides a key in every job whose command has that option. An unknown key
is an error that names the key, the job and the file.
"""

from __future__ import annotations

import contextlib
import io
import tomllib
from pathlib import Path

import click

from .. import presets
from ..errors import WeaveCutError
from ..fileio import write_atomic
from .common import CONTEXT, complete_preset, reports_errors, say

RESERVED = {"command", "input", "output", "name"}


class RecipeError(WeaveCutError, ValueError):
    """A recipe file is missing, malformed, or names an unknown command or option."""


def load_recipe(path: Path) -> list[dict]:
    try:
        with open(path, "rb") as f:
            doc = tomllib.load(f)
    except OSError as exc:
        raise RecipeError(f"cannot read {path}: {exc.strerror}") from exc
    except tomllib.TOMLDecodeError as exc:
        raise RecipeError(f"{path}: {exc}") from exc
    unknown = set(doc) - {"job", "recipe"}
    if unknown:
        raise RecipeError(f"{path}: unknown key {sorted(unknown)[0]!r} (a recipe has [recipe] "
                          "and [[job]] tables)")
    jobs = doc.get("job")
    if not isinstance(jobs, list) or not jobs:
        raise RecipeError(f"{path}: no [[job]] tables")
    return jobs


def job_arguments(group: click.Group, job: dict, where: str, out_dir: Path,
                  overrides: dict[str, str], base: Path = Path(".")) -> list[str]:
    """The command line of one job: ``[command, INPUT, options..., -o OUT]``."""
    name = job.get("command")
    command = group.commands.get(name) if isinstance(name, str) else None
    if command is None or name == "build":
        raise RecipeError(f"{where}: unknown command {name!r}; choose one of "
                          f"{', '.join(sorted(set(group.commands) - {'build'}))}")
    options = {}
    for p in command.params:
        if isinstance(p, click.Option):
            for opt in p.opts:
                if opt.startswith("--"):
                    options[opt[2:].replace("-", "_")] = p
    has_input = any(isinstance(p, click.Argument) for p in command.params)
    args = [name]
    if has_input:
        if "input" not in job:
            raise RecipeError(f"{where}: command {name!r} needs an 'input'")
        given = str(job["input"])
        beside = base / given
        args.append(str(beside) if Path(given).suffix and beside.exists() else given)
    values = {k.replace("-", "_"): v for k, v in job.items() if k not in RESERVED}
    for key, value in overrides.items():
        if key in options:
            values[key] = value
    for key, value in values.items():
        option = options.get(key)
        if option is None or key == "output":
            raise RecipeError(f"{where}: unknown key {key.replace('_', '-')!r} for command "
                              f"{name!r}")
        flag = max(option.opts, key=len)
        if option.is_flag:
            if value is True or str(value).lower() in ("true", "1", "yes"):
                args.append(flag)
        elif isinstance(value, list):
            for item in value:
                args += [flag, str(item)]
        else:
            args += [flag, str(value)]
    if "output" in job and "o" in {o.lstrip("-") for p in command.params for o in p.opts}:
        args += ["-o", str(out_dir / str(job["output"]))]
    return args


@click.command("build", context_settings=CONTEXT)
@click.argument("recipe", type=click.Path(dir_okay=False, path_type=Path),
                shell_complete=complete_preset("recipes"))
@click.option("-o", "--output-dir", type=click.Path(file_okay=False, path_type=Path),
              default=Path("build"), show_default=True, help="Folder for the outputs.")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help="Override an option in every job that has it (repeatable).")
@click.option("--dry-run", is_flag=True, help="Print the commands instead of running them.")
@click.pass_context
@reports_errors
def build_command(ctx: click.Context, recipe: Path, output_dir: Path, overrides: tuple[str, ...],
                  dry_run: bool) -> None:
    """Run every job of RECIPE (a .toml file, or a recipe's name: see templates/recipes).

    \b
    Examples:
      weave-cut build square-grid-paper-model
      weave-cut build templates/recipes/jigsaw-50cm-poplar.toml -o out --set kerf=0.2mm
    """
    parsed = {}
    for item in overrides:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise click.BadParameter(f"{item!r} is not KEY=VALUE", param_hint="'--set'")
        parsed[key.strip().replace("-", "_")] = value.strip()
    group = ctx.parent.command
    recipe = recipe if recipe.suffix else presets.find("recipes", str(recipe))  # by name
    jobs = load_recipe(recipe)
    commands = [job_arguments(group, job, f"{recipe} job {n + 1}", output_dir, parsed,
                              recipe.parent) for n, job in enumerate(jobs)]
    if dry_run:
        for args in commands:
            click.echo("weave-cut " + " ".join(args))
        return
    output_dir.mkdir(parents=True, exist_ok=True)
    for n, (job, args) in enumerate(zip(jobs, commands), start=1):
        say(f"[{n}/{len(commands)}] weave-cut {' '.join(args)}")
        sub = group.make_context("weave-cut", list(args), parent=ctx.parent)
        if "-o" in args or "output" not in job:
            with sub:
                group.invoke(sub)
            continue
        printed = io.StringIO()  # a command that prints (stats --json): its output is the file
        with sub, contextlib.redirect_stdout(printed):
            group.invoke(sub)
        write_atomic(output_dir / str(job["output"]), printed.getvalue().encode("utf-8"))
