"""``weave-cut weave``: the weaving pattern of a subdivision, drawn or counted."""

from __future__ import annotations

import json
from pathlib import Path

import click
import numpy as np

from ..errors import MeshError
from ..weave.colour import palette, strand_colours
from ..weave.report import weave_summaries
from .common import (
    CONTEXT,
    input_title,
    Choice,
    Length,
    complete_preset,
    flag_nonconvex,
    force_option,
    input_argument,
    page_option,
    html_option,
    provenance,
    reports_errors,
    write_drawing,
    write_png,
)
from .mesh_commands import project_option, run_scheme, scheme_options
from .outputs import check_suffix

DRAWINGS = ("svg", "pdf", "png", "dxf")
MODELS = ("obj", "glb", "png")  # of a weave on a surface in space


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
@click.option("--style", type=Choice(["tiles", "ribbons"]), default="tiles",
              show_default=True, help="Tiles coloured by strand, or knotwork ribbons.")
@click.option("--face-split", is_flag=True,
              help="Use the general face-split weave instead of the scheme's own.")
@click.option("--size", type=Length(), default="200mm", show_default=True,
              help="Longer side of the picture, without margins.")
@page_option
@click.option("--thickness", type=Length(), default="0.5mm", show_default=True,
              help="Paper thickness: in a 3-D model the strip on top lies this far over "
                   "the surface and the one below as far under it.")
@click.option("--json", "as_json", is_flag=True, help="Print the counts per level as JSON.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default=None,
              help="Picture: .svg, .pdf, .png or .dxf; of a surface (a woven ball): a 3-D "
                   "model, .obj or .glb, or .png views (--size is then its diameter).")
@force_option
@reports_errors
@html_option
def weave_command(input_mesh, levels, scheme, no_smooth, chirality, centre, allow_nonconvex,
                  project, palette_name, outline_level, middle_edges, crossings, style,
                  face_split, size, page, thickness, as_json, output) -> None:
    """Weave INPUT after N subdivision steps: strands, over/under crossings and lineage.

    \b
    Examples:
      weave-cut weave square-grid --levels 2 --outline-level 1 -o square-weave.svg
      weave-cut weave pentagon --levels 4 --outline-level 3 --palette puzzle -o pentagon.png
      weave-cut weave square-grid --levels 2 --page letter -o square-weave.pdf
      weave-cut weave square-grid:3x3 --levels 2 --json
      weave-cut weave triangle-grid --scheme loop --levels 2 --style ribbons -o loop.svg
      weave-cut weave dodecahedron --levels 2 --project sphere --json
      weave-cut weave dodecahedron --levels 1 --size 150mm -o ball.glb
    """
    from ..layout.weave_figure import snub_under_points, weave_drawing
    from ..weave.schemes import scheme_weaves

    if output is None and not as_json:
        raise click.UsageError("give -o OUTPUT for a picture, or --json for the counts")
    suffix = check_suffix(output, ("." + d for d in DRAWINGS + MODELS[:2])).lstrip(".") \
        if output else ""
    if levels < 1 and scheme == "snub":
        raise click.BadParameter("the snub weave needs --levels 1 or more", param_hint="'--levels'")
    if outline_level is not None and outline_level >= levels:
        raise click.BadParameter(f"must be below --levels {levels}", param_hint="'--outline-level'")
    pal = palette(palette_name)
    hierarchy = run_scheme(input_mesh, levels, scheme, no_smooth, chirality, centre,
                           allow_nonconvex, project,
                           flat=suffix not in MODELS and output and f"a .{suffix} drawing")
    surface = hierarchy[0].mesh.dim == 3
    if suffix in MODELS and not surface and suffix != "png":
        raise MeshError(f"{input_mesh} is flat; a .{suffix} woven model needs a surface in space "
                        "(draw a flat weave as .svg, .pdf, .png or .dxf)")
    nonconvex = flag_nonconvex(hierarchy)
    kind = "face-split" if face_split else scheme  # the weave's own name
    what = f"the {kind} weave of {input_mesh} at level {levels}"
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
        click.echo(json.dumps({"input": input_title(input_mesh), "scheme": scheme, **nonconvex, "levels": [
            {"level": first + i, **s} for i, s in enumerate(weave_summaries(weaves))]},
            indent=2, allow_nan=False))
    if output and surface:
        write_model(weaves, strand_colours(weaves, pal), size, thickness, output,
                    f"{input_title(input_mesh)}, {kind} weave, level {levels}")
    elif output:
        snub = scheme == "snub" and not face_split
        outline = None
        if outline_level is not None:
            outline = weaves[outline_level - (levels - len(weaves) + 1)]
        drawing = weave_drawing(
            weaves, strand_colours(weaves, pal), size, outline=outline,
            middle_edges=middle_edges and snub, crossings=crossings, ribbons=style == "ribbons",
            under_points=snub_under_points(weaves[-1]) if snub else None,
            title=f"{input_title(input_mesh)}, {kind} weave, level {levels}")
        write_drawing(drawing, output, page)


RIBBON_WIDTH = 0.55  # of the mean distance between the centres of consecutive tiles


def write_model(weaves, colours, diameter: float, thickness: float, output: str,
                title: str) -> None:
    """The last weave, on a surface, as strips in space (.obj, .glb) or PNG views, scaled to
    ``diameter`` (mm), the strips ``thickness`` over and under each other: a snub weave's
    strips are its tiles (:mod:`weavecut.weave.woven`), any other weave's ribbons run through
    its tile centres (:mod:`weavecut.weave.ribbons`)."""
    from ..export import gltf, model3d
    from ..fileio import write_atomic
    from ..weave.ribbons import mean_step, ribbons
    from ..weave.woven import Model, smooth_normals, woven_mm, woven_model

    weave = weaves[-1]
    try:
        flat = woven_model(weave, colours, 0.0).vertices  # the strips' own size sets the scale
        centre = flat.mean(axis=0)
        scale = diameter / (2 * np.linalg.norm(flat - centre, axis=1).max())  # mm per unit
        model = woven_mm(weave, colours, scale, thickness)
    except MeshError:  # not a snub weave: ribbons through the tile centres
        width = RIBBON_WIDTH * mean_step(weave)
        flat = ribbons(weave, width, 0.0).vertices
        centre = flat.mean(axis=0)
        scale = diameter / (2 * np.linalg.norm(flat - centre, axis=1).max())
        band = ribbons(weave, width, thickness / 2 / scale)
        vertices = (band.vertices - centre) * scale
        model = Model(vertices, smooth_normals(vertices, band.triangles), band.triangles,
                      band.strand, tuple(colours), tuple(f"strand {s + 1}"
                                                         for s in range(weave.n_strands)))
    rgb = np.array([[int(c[i:i + 2], 16) for i in (1, 3, 5)] for c in model.colours],
                   dtype=np.uint8)
    vertex_rgb = np.zeros((len(model.vertices), 3), dtype=np.uint8)
    vertex_rgb[model.triangles] = rgb[model.part][:, None]
    args = (model.vertices, model.triangles, vertex_rgb)
    suffix = Path(output).suffix.lower()
    if suffix == ".png":
        write_png(model3d.png_bytes(*args, normals=model.normals), output, title)
    elif suffix == ".glb":
        write_atomic(output, gltf.glb_bytes(model, name=title))
    else:
        write_atomic(output, model3d.obj_bytes(*args, comments=[title, *(
            f"{k}: {v}" for k, v in provenance().items())]))
