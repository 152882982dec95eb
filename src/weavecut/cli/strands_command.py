"""``weave-cut strands``: printable paper strips for the weave (paper section 5.2)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click

from .. import export
from ..subdivision import snub, subdivide
from ..weave.colour import palette
from .common import (CONTEXT, Finite, Length, PageSize, check_layout, complete_preset,
                     flag_nonconvex, input_argument, load_mesh, provenance, reports_errors,
                     summary)

FORMATS = ("pdf", "svg")


@click.command("strands", context_settings=CONTEXT)
@input_argument
@click.option("--levels", "-n", type=click.IntRange(1, 8), default=None,
              help="Snub steps [default: 2; pentagon-flower 3].")
@click.option("--page", type=PageSize(), default="a4", show_default=True,
              help="a4, letter, a3 or WxH like 300x200mm.")
@click.option("--tile-size", type=Length(), default="20mm", show_default=True,
              help="Distance across an octagon: the print's true scale (thinner strips tear).")
@click.option("--margin", type=Length(), default="10mm", show_default=True,
              help="Blank paper round every page.")
@click.option("--palette", "palette_name", default=None,
              shell_complete=complete_preset("palettes"), help="Palette preset: maritime-12 (braided pairs, copies alike; the default) or "
                   "a flat one such as maritime-4 (one colour per module copy).")
@click.option("--turn", type=Finite(-3600, 3600), default=None,
              help="Degrees the pattern is turned on the assembly sheet; module strands head "
                   "down in it [default: 45 for square-grid, else 0].")
@click.option("--chirality", type=click.Choice(snub.CHIRALITIES), default="left",
              show_default=True, help="Side the first Z edge turns to.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True,
              help="Output: .pdf (one page per sheet) or .svg (a layer per page).")
@click.option("--json", "as_json", is_flag=True, help="Print the plan (pages, copies) as JSON.")
@reports_errors
def strands_command(input_mesh, levels, page, tile_size, margin, palette_name, turn,
                    chirality, output, as_json) -> None:
    """Printable paper strips for weaving INPUT by hand: an assembly sheet, then one strip
    per strand, grouped into modules by the pattern's rotational symmetry.

    \b
    Examples:
      weave-cut strands square-grid -o square.pdf
      weave-cut strands pentagon-flower -o pentagon.pdf
      weave-cut strands square-grid --palette maritime-4 --page letter -o square-4.pdf
    """
    from ..papermodel.book import preset_for, strand_book
    from ..weave.snub_weave import snub_weaves

    fmt = Path(output).suffix.lower().lstrip(".")
    if fmt not in FORMATS:
        raise click.BadParameter(f"unknown format {Path(output).suffix!r}; use .pdf or .svg",
                                 param_hint="'-o'")
    preset = preset_for(input_mesh)
    levels = preset["levels"] if levels is None else levels
    turn = preset["turn"] if turn is None else math.radians(turn)
    pal = palette(palette_name or preset["palette"])
    hierarchy = subdivide(check_layout(load_mesh(input_mesh), "the paper model"), levels,
                          chirality=chirality)
    weaves = snub_weaves(hierarchy)
    flag_nonconvex(hierarchy)
    try:
        book = strand_book(weaves, pal, page, tile_size, margin, turn,
                           title=f"weave-cut strands: {input_mesh}, level {levels}")
    except ValueError as exc:
        raise click.ClickException(str(exc)) from exc
    export.write(book.drawing.with_metadata(**provenance()), output)
    plan = book.plan
    if as_json:
        click.echo(json.dumps({"input": input_mesh, "levels": levels, "output": output,
                               "pages": len(book.drawing.sheets), "rotation_order": plan.k,
                               "copies": plan.k, "module_strips": int(plan.copies.shape[1]),
                               "extra_strips": len(plan.extras),
                               "strands": int(weaves[-1].n_strands)}, indent=2))
    else:
        summary(f"{output}: {len(book.drawing.sheets)} pages; C{plan.k}, {plan.k} copies of "
                f"a {plan.copies.shape[1]}-strip module"
                + (f" + {len(plan.extras)} extras" if len(plan.extras) else ""))
