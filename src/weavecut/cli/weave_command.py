"""``weave-cut weave``: the weaving pattern of a subdivision, drawn or counted."""

from __future__ import annotations

import json
from pathlib import Path

import click

from ..errors import MeshError
from ..weave.colour import palette, strand_colours
from ..weave.report import weave_summaries
from ..weave.schemes import scheme_weaves
from ..layout.weave_figure import snub_under_points, weave_drawing
from .common import (
    CONTEXT,
    Length,
    complete_preset,
    flag_nonconvex,
    input_argument,
    page_option,
    reports_errors,
    write_drawing,
)
from .mesh_commands import project_option, run_scheme, scheme_options

DRAWINGS = ("svg", "pdf", "png", "dxf")


@click.command("weave", context_settings=CONTEXT)
@input_argument
@scheme_options
@project_option
@click.option("--palette", "palette_name", default="maritime-12", show_default=True,
              shell_complete=complete_preset("palettes"), help="Palette preset (templates/palettes) or a .toml file.")
@click.option("--outline-level", type=click.IntRange(1, 40), default=None,
              help="Draw the octagons (tiles) of this coarser level over the picture.")
@click.option("--middle-edges", is_flag=True, help="Highlight the Z middle edges (snub).")
@click.option("--crossings", is_flag=True, help="Mark at each crossing which strand is on top.")
@click.option("--style", type=click.Choice(["tiles", "ribbons"]), default="tiles",
              show_default=True, help="Tiles coloured by strand, or knotwork ribbons.")
@click.option("--face-split", is_flag=True,
              help="Use the general face-split weave instead of the scheme's own.")
@click.option("--size", type=Length(), default="200mm", show_default=True,
              help="Longer side of the picture, without margins.")
@page_option
@click.option("--json", "as_json", is_flag=True, help="Print the counts per level as JSON.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default=None,
              help="Picture: .svg, .pdf, .png or .dxf.")
@reports_errors
def weave_command(input_mesh, levels, scheme, no_smooth, chirality, centre, allow_nonconvex,
                  project, palette_name, outline_level, middle_edges, crossings, style,
                  face_split, size, page, as_json, output) -> None:
    """Weave INPUT after N subdivision steps: strands, over/under crossings and lineage.

    \b
    Examples:
      weave-cut weave square-grid --levels 2 --outline-level 1 -o square-weave.svg
      weave-cut weave pentagon --levels 4 --outline-level 3 --palette puzzle -o pentagon.png
      weave-cut weave square-grid --levels 2 --page letter -o square-weave.pdf
      weave-cut weave square-grid:3x3 --levels 2 --json
      weave-cut weave triangle-grid --scheme loop --levels 2 --style ribbons -o loop.svg
      weave-cut weave dodecahedron --levels 2 --project sphere --json
    """
    if output is None and not as_json:
        raise click.UsageError("give -o OUTPUT for a picture, or --json for the counts")
    if output and Path(output).suffix.lower().lstrip(".") not in DRAWINGS:
        raise click.BadParameter(f"unknown format {Path(output).suffix!r}; use "
                                 + ", ".join("." + d for d in DRAWINGS), param_hint="'-o'")
    if levels < 1 and scheme == "snub":
        raise click.BadParameter("the snub weave needs --levels 1 or more", param_hint="'--levels'")
    if outline_level is not None and outline_level >= levels:
        raise click.BadParameter(f"must be below --levels {levels}", param_hint="'--outline-level'")
    pal = palette(palette_name)
    hierarchy = run_scheme(input_mesh, levels, scheme, no_smooth, chirality, centre,
                           allow_nonconvex, project, flat=output and "a drawing")
    nonconvex = flag_nonconvex(hierarchy)
    what = f"the {scheme} weave of {input_mesh} at level {levels}"
    try:
        weaves = scheme_weaves(hierarchy, scheme, face_split)
        weaves[-1].mesh.topology  # noqa: B018  (a face-split mesh can pinch at a vertex)
    except MeshError as exc:
        raise click.ClickException(f"{what} cannot be built: {exc}") from exc
    if weaves[-1].n_tiles == 0:
        raise click.ClickException(f"{what} has no tiles: no two faces glue into one; try "
                                   "--face-split or another scheme")
    if as_json:
        first = levels - len(weaves) + 1
        click.echo(json.dumps({"input": input_mesh, "scheme": scheme, **nonconvex, "levels": [
            {"level": first + i, **s} for i, s in enumerate(weave_summaries(weaves))]}, indent=2))
    if output:
        snub = scheme == "snub" and not face_split
        outline = None
        if outline_level is not None:
            outline = weaves[outline_level - (levels - len(weaves) + 1)]
        drawing = weave_drawing(
            weaves, strand_colours(weaves, pal), size, outline=outline,
            middle_edges=middle_edges and snub, crossings=crossings, ribbons=style == "ribbons",
            under_points=snub_under_points(weaves[-1]) if snub else None,
            title=f"{input_mesh}, {scheme} weave, level {levels}")
        write_drawing(drawing, output, page)
