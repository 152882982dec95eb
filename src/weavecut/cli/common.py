"""What every command shares: option types, the error wrapper, mesh loading, provenance.

Light on purpose (numpy at most): every command module imports it, and ``weave-cut --help``
imports every command module; shapely, scipy and the writers load where they are used.
"""

from __future__ import annotations

import contextlib
import functools
import math
import os
import shlex
import sys
from pathlib import Path

import click
from click.shell_completion import CompletionItem
import numpy as np

from .. import __version__, inputs, units
from ..errors import MeshError, WeaveCutError
from ..fileio import note, protect, recording
from ..mesh import Mesh
from ..readers import DEFAULT_FLATTEN, MESH_CHOICES
from ..text import clean, nearest
from .outputs import force_option, path_options, writing  # noqa: F401  (one place)

CONTEXT = {"help_option_names": ["-h", "--help"], "max_content_width": 100}


class Length(click.ParamType):
    """A length with its unit ('50cm', '0.15mm', '2in'; zero may go without) -> float mm
    (``units.length``: a bare number is refused, in an option as in a recipe)."""

    name = "length"

    def __init__(self, minimum: float = 0.0, inclusive: bool = False) -> None:
        self.minimum, self.inclusive = minimum, inclusive

    def convert(self, value, param, ctx):
        if isinstance(value, bool):
            self.fail(f"{value!r} is not a length", param, ctx)
        try:
            mm = units.length(value)
        except ValueError as exc:
            self.fail(str(exc), param, ctx)
        if mm < self.minimum or (mm == self.minimum and not self.inclusive):
            bound = ">=" if self.inclusive else ">"
            self.fail(f"{value!r} must be {bound} {self.minimum:g} mm", param, ctx)
        if mm > 1e6:
            self.fail(f"{value!r} is larger than a kilometre", param, ctx)
        return mm


class Choice(click.Choice):
    """click's Choice, whose refusal also says which choice was probably meant."""

    def convert(self, value, param, ctx):
        try:
            return super().convert(value, param, ctx)
        except click.BadParameter as exc:
            exc.message = exc.message.rstrip(".") + nearest(str(value), self.choices)
            raise


class Finite(click.FloatRange):
    """A finite float within optional bounds (click's FloatRange lets NaN and inf through)."""

    def convert(self, value, param, ctx):
        number = super().convert(value, param, ctx)
        if not math.isfinite(number):
            self.fail(f"{value!r} is not a finite number", param, ctx)
        return number


class PageSize(click.ParamType):
    name = "page"

    def convert(self, value, param, ctx):
        if isinstance(value, tuple):
            return value
        if not isinstance(value, str):  # a number in a recipe
            self.fail(f"{value!r} is not a page size: use a4, a3, letter, a preset or WxH "
                      "like 200x300mm", param, ctx)
        from .. import presets

        try:
            return presets.page_size(value)
        except ValueError as exc:
            self.fail(str(exc), param, ctx)


page_option = click.option(
    "--page", type=PageSize(), default="a4", show_default=True,
    help="PDF page: a4, letter, a3, a preset or WxH like 300x200mm. The drawing is printed "
         "1:1, centred, or tiled over pages with overlap marks when larger.")


class Formats(click.ParamType):
    """'svg,dxf,lbrn2': the files a laser command writes per sheet (``presets.LASER_FORMATS``,
    comma-separated) -> a tuple in that order."""

    name = "formats"

    def convert(self, value, param, ctx):
        from ..presets import LASER_FORMATS

        items = value if isinstance(value, (list, tuple)) else str(value).split(",")
        items = [str(item).strip().lower().lstrip(".") for item in items]
        bad = [item for item in items if item not in LASER_FORMATS]
        if bad or not items:
            self.fail(f"{bad[0] if bad else value!r} is not a laser file format; give one or "
                      f"more of {','.join(LASER_FORMATS)}, comma-separated", param, ctx)
        return tuple(f for f in LASER_FORMATS if f in items)


formats_option = click.option(
    "--formats", type=Formats(), default=None,
    help="Files written per sheet, comma-separated: svg, dxf, lbrn2 (a LightBurn project: a "
         "layer per operation with the material's speed, power and passes, run in order) "
         "[default: the laser preset's formats, else svg,dxf].")


def write_drawing(drawing, output: str, page: tuple[float, float]) -> None:
    """Write ``drawing`` with its provenance to ``output``; a PDF goes onto ``page``s."""
    from .. import export
    from ..layout.tiling import on_pages

    drawing = drawing.with_metadata(**provenance())
    if Path(output).suffix.lower() == ".pdf":
        drawing = on_pages(drawing, page)
    export.write(drawing, output)


def write_png(data: bytes, output: str, title: str) -> None:
    """Write a raster picture's PNG ``data`` with its title and provenance as text chunks."""
    from ..export.png import with_text
    from ..fileio import write_atomic

    write_atomic(output, with_text(data, [("Title", title), *provenance().items()]))


def reports_errors(f):
    """Turn a WeaveCutError (or a ValueError from option checks) into a one-line exit 1; where
    the command writes is checked before any work, and its folders are locked at the first
    write (``outputs.writing``)."""

    @functools.wraps(f)
    def wrapper(*args, **kwargs):
        try:
            with writing(click.get_current_context(silent=True)):
                return f(*args, **kwargs)
        except WeaveCutError as exc:
            raise click.ClickException(str(exc)) from exc
        except _geometry_errors() as exc:  # a last resort: meshes are checked before layout
            raise click.ClickException(f"the geometry cannot be laid out ({exc}); a mesh with "
                                       "sliver faces or tiny features is the usual cause") from exc
        except KeyboardInterrupt:
            click.echo("weave-cut: interrupted; no output was left half-written", err=True)
            sys.exit(130)

    return wrapper


def _geometry_errors() -> tuple[type[Exception], ...]:
    """shapely's GEOSException, once shapely is loaded (nothing else raises it)."""
    errors = sys.modules.get("shapely.errors")
    return (errors.GEOSException,) if errors else ()


def html_option(f):
    """``--html PAGE``: after the command, write its kit page to PAGE (a picture of every file
    it wrote, what each is for, sizes, the command and its summary). Goes below
    ``@reports_errors``."""

    @functools.wraps(f)
    def wrapper(*args, html: str | None = None, **kwargs):
        if html is None:
            return f(*args, **kwargs)
        from .. import kitpage

        with recording() as record:
            result = f(*args, **kwargs)
        if Path(os.path.abspath(html)) in record.files:
            raise click.BadParameter("the page would replace an output", param_hint="'--html'")
        name = click.get_current_context().info_name
        kitpage.write(html, f"weave-cut {name}", [kitpage.Run.of(record, command_line(), name)])
        return result

    return click.option("--html", type=click.Path(dir_okay=False), metavar="PAGE",
                        help="Also write an HTML page that shows every output (pictures, sizes, "
                        "what each file is for).")(wrapper)


def load_mesh(spec: str, allow_nonconvex: bool = False, flat: str | None = None) -> Mesh:
    """A built-in input by name, or a mesh file or drawing, validated; no output may replace
    the file. A drawing (.svg, .dxf) is read with the options of ``drawing_options``, which
    the running command keeps in its context. With ``flat`` (what needs a flat mesh) a
    surface in space is refused. Built-in inputs are valid as built (a test validates each),
    so they skip the validation and its imports."""
    if (inputs.is_builtin(spec) or not Path(spec).suffix) and not Path(spec).exists():
        mesh = inputs.get(spec)
    else:
        from ..mesh_io import read_valid_mesh

        protect(spec)
        ctx = click.get_current_context(silent=True)
        drawing = ctx.meta.get(DRAWING_KEY, {}) if ctx else {}
        mesh = read_valid_mesh(spec, allow_nonconvex=allow_nonconvex, note=say, **drawing)
    if flat and mesh.dim == 3:
        raise MeshError(f"{spec} is a surface in space (x, y, z vertices); {flat} needs a flat "
                        "mesh so far")
    return mesh


def check_levels(levels, what: str) -> None:
    """Refuse a subdivision whose last level is empty or has coordinates that are not finite
    (an area centroid of a face too small for floating point), instead of writing it."""
    mesh = levels[-1].mesh
    if mesh.n_faces == 0:
        raise MeshError(f"{what} has no faces at level {len(levels) - 1} (the scheme needs "
                        "inner vertices or edges this mesh does not have); try another "
                        "scheme or input")
    if not np.isfinite(mesh.vertices).all():
        raise MeshError(f"{what} has coordinates that are not finite at level "
                        f"{len(levels) - 1} (faces too small for --centre area?); scale the "
                        "mesh up or use --centre vertex")


def command_line() -> str:
    """The command that is running, for output metadata (control characters and undecodable
    bytes replaced; an absolute path by its name, see :func:`shown_path`)."""
    return clean("weave-cut " + " ".join(shlex.quote(shown_path(a)) for a in sys.argv[1:]))


def shown_path(word: str) -> str:
    """``word`` as an output file may show it: an absolute path (or an ``--option=PATH``) by
    the file's name, so no file tells where the maker keeps theirs (and the same command
    writes the same bytes wherever it runs); anything else as it is."""
    key, eq, value = word.partition("=") if word.startswith("-") else ("", "", word)
    return f"{key}{eq}{Path(value).name}" if os.path.isabs(value) else word


def option_key(p: click.Parameter) -> str:
    """An option's long name without dashes (``--laser-card``: ``laser-card``), as a recipe
    and the web form name it."""
    return max(p.opts, key=len).lstrip("-")


def input_title(spec: str) -> str:
    """An INPUT as a title names it: a built-in input by its name, a file by its name only."""
    return spec if inputs.is_builtin(spec) else Path(spec).name


def provenance() -> dict[str, str]:
    return {"generator": f"weave-cut {__version__}", "command": command_line()}


def _names_or_files(names, incomplete: str) -> list[CompletionItem]:
    """Shell completion: the names that start with ``incomplete``, and the shell's files."""
    return ([CompletionItem(n) for n in names if n.startswith(incomplete)]
            + [CompletionItem(incomplete, type="file")])


def complete_inputs(ctx, param, incomplete: str) -> list[CompletionItem]:
    """Built-in input names, then mesh files."""
    return _names_or_files(inputs.INPUTS, incomplete)


def complete_preset(kind: str):
    """Shell completion for a preset of ``kind`` (palettes, materials, ...): names, then files."""

    def complete(ctx, param, incomplete: str) -> list[CompletionItem]:
        from .. import presets

        return _names_or_files(presets.names(kind), incomplete)

    return complete


def input_argument(f):
    """Decorator adding the INPUT argument and the options for reading a drawing as INPUT."""
    return click.argument("input_mesh", metavar="INPUT",
                          shell_complete=complete_inputs)(drawing_options(f))


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
        click.option("--mesh", type=Choice(MESH_CHOICES), default="auto",
                     show_default=True, help="Drawings: mesh the inside of the outline (auto: "
                     "when there is a single outline; none: faces as drawn).", **kept),
        click.option("--cell", type=Length(), default=None, help="Drawings: face size when "
                     "meshing an outline [default: about 60 faces].", **kept),
    ]
    for option in reversed(options):
        f = option(f)
    return f


def quiet() -> bool:
    """Whether -q was given: then stdout carries only what was asked for (such as --json)."""
    ctx = click.get_current_context(silent=True)
    return ctx is not None and ctx.find_root().meta.get("weavecut.quiet", False)


def progress(items, label: str):
    """A progress bar on stderr over ``items``; silent with -q or when stderr is no terminal."""
    if quiet() or not sys.stderr.isatty():
        return contextlib.nullcontext(items)
    return click.progressbar(items, label=label, file=sys.stderr)


def say(message: str) -> None:
    """A line of progress on stderr, unless -q."""
    if not quiet():
        click.echo(message, err=True)


def summary(text: str) -> None:
    """What a command made, for people to read, on stdout, unless -q (and for the kit page)."""
    note(said=text)
    if not quiet():
        click.echo(text)


def flag_nonconvex(hierarchy, into: list[str] | None = None) -> dict:
    """Warn on stderr about every produced level (1..N) with non-convex faces (even with -q:
    such a mesh is refused as input without --allow-nonconvex), or add the warnings to
    ``into`` (a command's warnings, which it prints and writes down itself), and return the
    counts for --json: ``{"nonconvex_faces": total, "nonconvex_faces_by_level": {"5": 72,
    ...}}``."""
    from ..analysis.convexity import SEE, nonconvex_levels, nonconvex_message

    rows = nonconvex_levels(hierarchy) if hierarchy[0].mesh.dim == 2 else []  # flat faces only
    for row in rows:
        message = nonconvex_message(row) + SEE
        if into is None:
            click.echo(f"weave-cut: warning: {message}", err=True)
        else:
            into.append(message)
    return {"nonconvex_faces": sum(r["nonconvex_faces"] for r in rows),
            "nonconvex_faces_by_level": {str(r["level"]): r["nonconvex_faces"] for r in rows}}
