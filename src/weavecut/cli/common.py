"""What every command shares: option types, the error wrapper, mesh loading, provenance."""

from __future__ import annotations

import contextlib
import functools
import shlex
import sys
from pathlib import Path

import click

from .. import __version__, inputs, units
from ..analysis.convexity import nonconvex_levels, nonconvex_message
from ..errors import WeaveCutError
from ..mesh import Mesh
from ..mesh_io import read_mesh
from ..validation import validate

CONTEXT = {"help_option_names": ["-h", "--help"], "max_content_width": 100}


class Length(click.ParamType):
    """'50cm', '0.15mm', '2in' or a bare number of millimetres -> float mm (> 0)."""

    name = "length"

    def __init__(self, minimum: float = 0.0, inclusive: bool = False) -> None:
        self.minimum, self.inclusive = minimum, inclusive

    def convert(self, value, param, ctx):
        if isinstance(value, float):
            return value
        try:
            mm = units.to_mm(value)
        except ValueError as exc:
            self.fail(str(exc), param, ctx)
        if mm < self.minimum or (mm == self.minimum and not self.inclusive):
            bound = ">=" if self.inclusive else ">"
            self.fail(f"{value!r} must be {bound} {self.minimum:g} mm", param, ctx)
        if mm > 1e6:
            self.fail(f"{value!r} is larger than a kilometre", param, ctx)
        return mm


class PageSize(click.ParamType):
    name = "page"

    def convert(self, value, param, ctx):
        if isinstance(value, tuple):
            return value
        try:
            return units.page_size(value)
        except ValueError as exc:
            self.fail(str(exc), param, ctx)


def reports_errors(f):
    """Turn a WeaveCutError (or a ValueError from option checks) into a one-line exit 1."""

    @functools.wraps(f)
    def wrapper(*args, **kwargs):
        try:
            return f(*args, **kwargs)
        except WeaveCutError as exc:
            raise click.ClickException(str(exc)) from exc
        except KeyboardInterrupt:
            click.echo("weave-cut: interrupted; no output was left half-written", err=True)
            sys.exit(130)

    return wrapper


def load_mesh(spec: str, allow_nonconvex: bool = False) -> Mesh:
    """A built-in input by name, or a mesh file, validated."""
    if inputs.is_builtin(spec) or not Path(spec).suffix:
        if not Path(spec).exists():
            return validate(inputs.get(spec), allow_nonconvex=allow_nonconvex)
    return validate(read_mesh(spec), allow_nonconvex=allow_nonconvex)


def command_line() -> str:
    """The command that is running, for output metadata."""
    return "weave-cut " + " ".join(shlex.quote(a) for a in sys.argv[1:])


def provenance() -> dict[str, str]:
    return {"generator": f"weave-cut {__version__}", "command": command_line()}


input_argument = click.argument("input_mesh", metavar="INPUT")
allow_nonconvex_option = click.option(
    "--allow-nonconvex", is_flag=True, help="Accept non-convex input faces (the paper assumes "
    "convex ones).")


def progress(items, label: str):
    """A progress bar on stderr over ``items``; silent with -q or when stderr is no terminal."""
    ctx = click.get_current_context(silent=True)
    quiet = ctx is not None and ctx.find_root().meta.get("weavecut.quiet", False)
    if quiet or not sys.stderr.isatty():
        return contextlib.nullcontext(items)
    return click.progressbar(items, label=label, file=sys.stderr)


def say(message: str) -> None:
    """A line of progress on stderr, unless -q."""
    ctx = click.get_current_context(silent=True)
    if not (ctx is not None and ctx.find_root().meta.get("weavecut.quiet", False)):
        click.echo(message, err=True)


def flag_nonconvex(hierarchy) -> dict:
    """Warn on stderr about every produced level (1..N) with non-convex faces (even with -q:
    such a mesh is refused as input without --allow-nonconvex), and return the counts for
    --json: ``{"nonconvex_faces": total, "nonconvex_faces_by_level": {"5": 72, ...}}``."""
    rows = nonconvex_levels(hierarchy)
    for row in rows:
        click.echo(f"weave-cut: warning: {nonconvex_message(row)}; see weave-cut convexity",
                   err=True)
    return {"nonconvex_faces": sum(r["nonconvex_faces"] for r in rows),
            "nonconvex_faces_by_level": {str(r["level"]): r["nonconvex_faces"] for r in rows}}
