"""What every command shares: option types, the error wrapper, mesh loading, provenance."""

from __future__ import annotations

import contextlib
import functools
import shlex
import sys
from pathlib import Path

import click

from .. import __version__, inputs, units
from ..errors import WeaveCutError
from ..mesh import Mesh
from ..mesh_io import read_mesh
from ..readers import DEFAULT_FLATTEN, MESH_CHOICES, SUFFIXES as DRAWING_SUFFIXES
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
    """A built-in input by name, or a mesh file or drawing, validated.

    A drawing (.svg, .dxf) is read with the options of ``drawing_options``, which the running
    command keeps in its context.
    """
    if inputs.is_builtin(spec) or not Path(spec).suffix:
        if not Path(spec).exists():
            return validate(inputs.get(spec), allow_nonconvex=allow_nonconvex)
    options = {}
    if Path(spec).suffix.lower() in DRAWING_SUFFIXES:
        ctx = click.get_current_context(silent=True)
        options = {**(ctx.meta.get(DRAWING_KEY, {}) if ctx else {}), "report": say,
                   "allow_nonconvex": allow_nonconvex}
    return validate(read_mesh(spec, **options), allow_nonconvex=allow_nonconvex)


def command_line() -> str:
    """The command that is running, for output metadata."""
    return "weave-cut " + " ".join(shlex.quote(a) for a in sys.argv[1:])


def provenance() -> dict[str, str]:
    return {"generator": f"weave-cut {__version__}", "command": command_line()}


def input_argument(f):
    """Decorator adding the INPUT argument and the options for reading a drawing as INPUT."""
    return click.argument("input_mesh", metavar="INPUT")(drawing_options(f))


allow_nonconvex_option = click.option(
    "--allow-nonconvex", is_flag=True, help="Accept non-convex input faces (the paper assumes "
    "convex ones).")


DRAWING_KEY = "weavecut.drawing"


def _keep_drawing_option(ctx: click.Context, param: click.Parameter, value):
    ctx.meta.setdefault(DRAWING_KEY, {})[param.name] = value
    return value


def drawing_options(f):
    """Decorator adding how to read an SVG or DXF INPUT: --flatten, --layer, --mesh, --cell.

    The values go to ``load_mesh`` through the command's context, so a command's own
    parameters stay as they are.
    """
    kept = {"expose_value": False, "callback": _keep_drawing_option}
    options = [
        click.option("--flatten", type=Length(), default=f"{DEFAULT_FLATTEN}mm",
                     show_default=True, help="Drawings: curves stay this close to their "
                     "polylines; points closer than this merge.", **kept),
        click.option("--layer", default=None, help="Drawings: read only this DXF layer or "
                     "SVG (Inkscape) layer.", **kept),
        click.option("--mesh", type=click.Choice(MESH_CHOICES), default="auto",
                     show_default=True, help="Drawings: mesh the inside of the outline (auto: "
                     "when there is a single outline; none: faces as drawn).", **kept),
        click.option("--cell", type=Length(), default=None, help="Drawings: face size when "
                     "meshing an outline [default: about 60 faces].", **kept),
    ]
    for option in reversed(options):
        f = option(f)
    return f


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
