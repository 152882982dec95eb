"""``weave-cut strands``: printable paper strips for the weave (paper section 5.2)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import click
import numpy as np

from .. import export
from ..subdivision import snub, subdivide
from ..weave.colour import palette
from .common import (CONTEXT, Finite, Length, PageSize, complete_preset,
                     flag_nonconvex, input_argument, load_mesh, provenance, reports_errors,
                     html_option, summary)
from .mesh_commands import project_option

FORMATS = ("pdf", "svg")


class PrintLength(Length):
    """A length that must carry its unit ("20mm", "23cm"): a bare number is refused."""

    def convert(self, value, param, ctx):
        if isinstance(value, str) and re.fullmatch(r"\s*[-+]?[\d.]+(e[-+]?\d+)?\s*", value, re.I):
            self.fail(f"{value!r} has no unit: write it like '20mm', '2.5cm' or '1in'", param, ctx)
        return super().convert(value, param, ctx)


@click.command("strands", context_settings=CONTEXT)
@input_argument
@click.option("--levels", "-n", type=click.IntRange(1, 8), default=None,
              help="Snub steps [default: 2; pentagon-flower 3].")
@click.option("--page", type=PageSize(), default="a4", show_default=True,
              help="a4, letter, a3 or WxH like 300x200mm.")
@click.option("--tile-size", type=PrintLength(), default=None,
              help="Distance across an octagon, with a unit: the print's true scale "
                   "[default: 20mm]. Strips under 8 mm wide are refused (they tear).")
@click.option("--size", "model_size", type=PrintLength(), default=None,
              help="Width of the finished model, with a unit (e.g. 23cm); sets the tile size. "
                   "A ball's diameter [default: octagons 40 mm across].")
@click.option("--layout", type=click.Choice(("mixed", "module")), default="mixed", show_default=True,
              help="mixed: every copy's strips packed densely together; module: the paper's "
                   "way, the module's pages printed once per direction.")
@click.option("--margin", type=Length(), default="10mm", show_default=True,
              help="Blank paper round every page.")
@click.option("--palette", "palette_name", default=None,
              shell_complete=complete_preset("palettes"),
              help="Palette preset: maritime-12 (shade families; the default) or a flat one "
                   "such as maritime-4 (one colour per module copy).")
@click.option("--turn", type=Finite(-3600, 3600), default=None,
              help="Degrees the pattern is turned on the assembly sheet; module strands head "
                   "down in it [default: 45 for square-grid, else 0].")
@click.option("--chirality", type=click.Choice(snub.CHIRALITIES), default="left",
              show_default=True, help="Side the first Z edge turns to.")
@project_option
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True,
              help="Output: .pdf (one page per sheet) or .svg (a layer per page).")
@click.option("--json", "as_json", is_flag=True,
              help="Print the plan and the page checks (ink, smallest label) as JSON.")
@reports_errors
@html_option
def strands_command(input_mesh, levels, page, tile_size, model_size, layout, margin,
                    palette_name, turn, chirality, project, output, as_json) -> None:
    """Printable paper strips for weaving INPUT by hand: an assembly sheet, a page of weaving
    steps, then one strip per strand, grouped into modules by the pattern's rotational symmetry.
    A closed surface in space gives a woven ball: every loop one strip, unfolded pentagon by
    pentagon with fold lines and numbered glue bands, and views of the ball on page 1.

    \b
    Examples:
      weave-cut strands square-grid --size 27cm -o square.pdf
      weave-cut strands pentagon-flower --size 23cm -o pentagon.pdf
      weave-cut strands square-grid --layout module --page letter -o square-module.pdf
      weave-cut strands dodecahedron --levels 1 --project sphere --size 12cm -o ball.pdf
    """
    from ..papermodel.book import preset_for, strand_book, tile_size_for
    from ..papermodel.checks import report
    from ..weave.snub_weave import snub_weaves

    fmt = Path(output).suffix.lower().lstrip(".")
    if fmt not in FORMATS:
        raise click.BadParameter(f"unknown format {Path(output).suffix!r}; use .pdf or .svg",
                                 param_hint="'-o'")
    if tile_size is not None and model_size is not None:
        raise click.BadParameter("give --tile-size or --size, not both", param_hint="'--size'")
    preset = preset_for(input_mesh)
    levels = preset["levels"] if levels is None else levels
    pal = palette(palette_name or preset["palette"])
    from ..validation import check_layout

    mesh = load_mesh(input_mesh)
    if mesh.dim == 3:
        if layout != "mixed" or turn is not None:
            raise click.UsageError("--layout and --turn are for flat models; a ball prints "
                                   "every strip once")
        return ball(mesh, input_mesh, levels, page, tile_size, model_size, margin, pal,
                    chirality, project, output, as_json)
    if project:
        raise click.BadParameter(f"{input_mesh} is flat; --project sphere is for surfaces "
                                 "in space", param_hint="'--project'")
    turn = preset["turn"] if turn is None else math.radians(turn)
    hierarchy = subdivide(check_layout(mesh, "the paper model"), levels, chirality=chirality)
    weaves = snub_weaves(hierarchy)
    nonconvex = flag_nonconvex(hierarchy)
    if model_size is not None:
        tile_size = tile_size_for(weaves[-1], model_size)
    try:
        book = strand_book(weaves, pal, page, tile_size or 20.0, margin, turn,
                           title=f"weave-cut strands: {input_mesh}, level {levels}",
                           layout=layout)
    except ValueError as exc:
        raise click.ClickException(str(exc)) from exc
    for warning in book.warnings:
        click.echo(f"weave-cut: warning: {warning}", err=True)
    export.write(book.drawing.with_metadata(**provenance()), output)
    plan = book.plan
    if as_json:
        click.echo(json.dumps({"input": input_mesh, "levels": levels, "output": output,
                               "layout": layout, **report(book),
                               "rotation_order": plan.k, "copies": plan.k,
                               "module_strips": int(plan.copies.shape[1]),
                               "extra_strips": len(plan.extras),
                               "strands": int(weaves[-1].n_strands), **nonconvex}, indent=2))
    else:
        summary(f"{output}: {len(book.drawing.sheets)} pages ({len(book.strip_pages)} of "
                f"strips, {100 * book.ink:.0f} % ink); C{plan.k}, {plan.k} copies of "
                f"a {plan.copies.shape[1]}-strip module"
                + (f" + {len(plan.extras)} extras" if len(plan.extras) else ""))


BALL_TILE = 40.0  # mm across an octagon: a ball's default size


def ball(mesh, input_mesh, levels, page, tile_size, diameter, margin, pal, chirality, project,
         output, as_json) -> None:
    """``strands`` of a surface in space: a woven ball's strips, ``diameter`` mm across."""
    from ..papermodel.ball import ball_book
    from ..papermodel.checks import report
    from ..weave.snub_weave import snub_weaves

    hierarchy = subdivide(mesh, levels, chirality=chirality, project=project)
    weaves = snub_weaves(hierarchy)
    weave = weaves[-1]
    book = ball_book(weaves, pal, page, diameter, margin,
                     title=f"weave-cut strands: {input_mesh}, level {levels}"
                           + (f", projected to the {project}" if project else ""),
                     tile_size=tile_size or BALL_TILE)
    for warning in book.warnings:
        click.echo(f"weave-cut: warning: {warning}", err=True)
    export.write(book.drawing.with_metadata(**provenance()), output)
    if as_json:
        click.echo(json.dumps({"input": input_mesh, "levels": levels, "project": project,
                               "output": output, **report(book), **book.flattening(),
                               "strands": int(weave.n_strands),
                               "strand_lengths_mm": np.round(weave.strand_lengths()
                                                             * book.scale, 1).tolist()},
                              indent=2))
    else:
        summary(f"{output}: {len(book.drawing.sheets)} pages ({len(book.strip_pages)} of "
                f"strips, {100 * book.ink:.0f} % ink); {weave.n_strands} strips in "
                f"{len(book.pieces)} pieces, a ball {book.diameter / 10:.1f} cm across; "
                f"unfolded edges change by at most {100 * book.stretch:.2f} %, pentagons are at most "
                f"{100 * float(book.non_planarity.max()):.1f} % off their planes")
