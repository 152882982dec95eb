"""``weave-cut inputs``, ``subdivide`` and ``stats``."""

from __future__ import annotations

import json
from collections import Counter

import click
import numpy as np

from .. import export, inputs
from ..errors import MeshError
from ..analysis.stats import level_stats, surface_stats
from ..subdivision import SCHEMES, snub, subdivide
from .common import (
    CONTEXT,
    input_title,
    Choice,
    Length,
    allow_nonconvex_option,
    force_option,
    check_levels,
    flag_nonconvex,
    input_argument,
    load_mesh,
    page_option,
    progress,
    provenance,
    reports_errors,
    write_drawing,
)
from .outputs import check_suffix

MESH_SUFFIXES = (".obj", ".json")


def level_options(default_levels: int = 1, with_scheme: bool = True):
    """Decorator adding --levels, --scheme (optional) and the snub step's options."""
    options = [
        click.option("--levels", "-n", type=click.IntRange(0, 40), default=default_levels,
                     show_default=True, help="Number of refinement steps."),
        click.option("--no-smooth", is_flag=True, help="Skip operation 4 (smoothing)."),
        click.option("--chirality", type=Choice(snub.CHIRALITIES), default="left",
                     show_default=True, help="Side the first Z edge turns to."),
        click.option("--centre", type=Choice(snub.CENTRES), default="vertex",
                     show_default=True, help="Face centre: vertex mean or area centroid."),
        allow_nonconvex_option,
    ]
    if with_scheme:
        options.insert(1, click.option("--scheme", type=Choice(sorted(SCHEMES)),
                                       default="snub", show_default=True,
                                       help="Subdivision scheme."))

    def decorate(f):
        for option in reversed(options):
            f = option(f)
        return f

    return decorate


scheme_options = level_options()
project_option = click.option(
    "--project", type=Choice(snub.PROJECTIONS), default=None,
    help="Snub on a surface: move every new vertex onto the input's circumsphere.")


def run_scheme(input_mesh: str, levels: int, scheme: str, no_smooth: bool, chirality: str,
               centre: str, allow_nonconvex: bool, project: str | None = None,
               flat: str | None = None):
    """Load INPUT and subdivide it; the snub options apply to the snub scheme only, which alone
    runs on surfaces in space so far; ``flat`` (what needs a flat mesh) refuses surfaces."""
    mesh = load_mesh(input_mesh, allow_nonconvex, flat)
    options = {}
    if scheme == "snub":
        options = {"smooth": not no_smooth, "chirality": chirality, "centre": centre,
                   "project": project}
    elif no_smooth or chirality != "left" or centre != "vertex" or project:
        raise click.UsageError("--no-smooth, --chirality, --centre and --project apply to "
                               "--scheme snub")
    if mesh.dim == 3 and scheme != "snub":
        raise MeshError(f"{input_mesh} is a surface in space; only --scheme snub subdivides "
                        "surfaces so far")
    with progress(range(levels), f"{scheme} levels") as steps, np.errstate(all="ignore"):
        hierarchy = subdivide(mesh, levels, scheme, steps=steps, **options)
    check_levels(hierarchy, f"{scheme} of {input_mesh}")
    return hierarchy


@click.command("inputs", context_settings=CONTEXT)
@click.option("--json", "as_json", is_flag=True, help="Print a JSON list.")
@reports_errors
def inputs_command(as_json: bool) -> None:
    """List the built-in input meshes with their vertex, edge and face counts.

    \b
    Example:
      weave-cut inputs
    """
    rows = []
    for name, entry in inputs.INPUTS.items():
        mesh = entry.build(None)
        spec = f"{name}[:{entry.parameter}]" if entry.parameter else name
        rows.append({"name": spec, "vertices": mesh.n_vertices, "edges": mesh.topology.n_edges,
                     "faces": mesh.n_faces, "description": entry.description})
    if as_json:
        click.echo(json.dumps(rows, indent=2, allow_nan=False))
        return
    click.echo(f"{'name':24} {'V':>5} {'E':>5} {'F':>5}  description")
    for r in rows:
        click.echo(f"{r['name']:24} {r['vertices']:5} {r['edges']:5} {r['faces']:5}  "
                   f"{r['description']}")


@click.command("subdivide", context_settings=CONTEXT)
@input_argument
@scheme_options
@project_option
@click.option("--size", type=Length(), default="200mm", show_default=True,
              help="Longer side of the drawing, without margins.")
@click.option("--earlier-levels", is_flag=True,
              help="Also draw the input and every level before the last, one layer each "
                   "(level-0, level-1, ...), under the cut lines.")
@page_option
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True,
              help="Output file: .svg, .dxf, .pdf, .png (drawings) or .obj, .json (the mesh).")
@force_option
@reports_errors
def subdivide_command(input_mesh, levels, scheme, no_smooth, chirality, centre,
                      allow_nonconvex, project, size, earlier_levels, page, output) -> None:
    """Subdivide INPUT (a built-in name or an .obj/.json file) and write the result.

    A drawing is cut-ready: the last level's edges each once, joined into trails, inner cuts
    before the outline.

    \b
    Examples:
      weave-cut subdivide pentagon --levels 4 -o pentagon.svg
      weave-cut subdivide tiling-8-4 --levels 3 -o tiling.dxf
      weave-cut subdivide pentagon --levels 3 --earlier-levels -o levels.svg
      weave-cut subdivide my-mesh.obj --levels 2 --no-smooth -o refined.obj
      weave-cut subdivide dodecahedron --levels 2 --project sphere -o ball.obj
    """
    from ..layout.mesh_figure import mesh_drawing
    from ..mesh_io import write_mesh

    suffix = check_suffix(output, [*MESH_SUFFIXES, *("." + f for f in export.formats())])
    hierarchy = run_scheme(input_mesh, levels, scheme, no_smooth, chirality, centre,
                           allow_nonconvex, project,
                           flat=None if suffix in MESH_SUFFIXES else f"a {suffix} drawing")
    flag_nonconvex(hierarchy)
    if suffix in MESH_SUFFIXES:
        write_mesh(hierarchy[-1].mesh, output, provenance())
        return
    title = f"{input_title(input_mesh)}, {scheme} level {levels}"
    drawing = mesh_drawing([lv.mesh for lv in hierarchy], size, title=title,
                           earlier=earlier_levels)
    write_drawing(drawing, output, page)


@click.command("stats", context_settings=CONTEXT)
@input_argument
@scheme_options
@project_option
@click.option("--json", "as_json", is_flag=True, help="Print JSON (a stable shape for scripts).")
@reports_errors
def stats_command(input_mesh, levels, scheme, no_smooth, chirality, centre, allow_nonconvex,
                  project, as_json) -> None:
    """Counts, degree histograms, angles and boundary of every level; on a surface in space
    also V - E + F, the counts of paper eq. (2), and the strands with their lengths.

    \b
    Examples:
      weave-cut stats pentagon --levels 6
      weave-cut stats square-grid:3x3 --levels 3 --json
      weave-cut stats dodecahedron --levels 2 --project sphere
    """
    hierarchy = run_scheme(input_mesh, levels, scheme, no_smooth, chirality, centre,
                           allow_nonconvex, project)
    rows = [level_stats(lv.mesh, t) for t, lv in enumerate(hierarchy)]
    if hierarchy[0].mesh.dim == 3:
        rows = [{**r, **more} for r, more in zip(rows, surface_stats(hierarchy))]
    if as_json:
        click.echo(json.dumps({"input": input_title(input_mesh),
                               "levels": rows}, indent=2, allow_nan=False))
        return
    click.echo(f"{input_mesh} ({scheme})")
    click.echo(f"{'level':>5} {'V':>10} {'E':>10} {'F':>10} {'non-convex':>10} "
               f"{'angles (deg)':>16} {'boundary':>9} {'length':>10}")
    for r in rows:
        click.echo(f"{r['level']:5} {r['vertices']:10,} {r['edges']:10,} {r['faces']:10,} "
                   f"{r['nonconvex_faces']:10} {r['min_angle_deg']:7.2f}-{r['max_angle_deg']:<7.2f} "
                   f"{r['boundary_edges']:10,} {r['boundary_length']:10.4f}")
    for r in rows:
        click.echo(f"level {r['level']}: inner degrees {_fmt(r['inner_vertex_degrees'])}; "
                   f"outer degrees {_fmt(r['outer_vertex_degrees'])}; "
                   f"faces {_fmt(r['face_degrees'])}")
    for r in rows:
        if "euler_characteristic" in r:
            line = f"level {r['level']}: V - E + F = {r['euler_characteristic']}"
            if "strands" in r:
                lengths = Counter(f"{x:.4g}" for x in r["strand_lengths"])
                line += (f"; eq. (2) {'holds' if r['eq2_holds'] else 'FAILS'}; "
                         f"{r['strands']} strands ({r['closed_strands']} closed), lengths "
                         + ", ".join(f"{k} x{n}" for k, n in lengths.items()))
            click.echo(line)


def _fmt(hist: dict[str, int]) -> str:
    return " ".join(f"{k}:{v}" for k, v in hist.items() if v) or "none"
