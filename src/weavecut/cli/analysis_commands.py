"""``weave-cut fractal``, ``levels``, ``convexity`` and ``figure``."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import click
import numpy as np
from click.shell_completion import CompletionItem

from .. import export
from ..text import nearest
from ..analysis import convexity as cv
from ..analysis import deepzoom
from ..analysis import fractal as fr
from ..analysis import levels as lv
from .common import (
    CONTEXT,
    input_title,
    force_option,
    input_argument,
    load_mesh,
    page_option,
    reports_errors,
    summary,
    write_drawing,
    write_png,
)
from .mesh_commands import level_options, run_scheme
from .outputs import check_suffix


snub_options = level_options(6, with_scheme=False)


def _hierarchy(input_mesh, levels, no_smooth, chirality, centre, allow_nonconvex):
    return run_scheme(input_mesh, levels, "snub", no_smooth, chirality, centre, allow_nonconvex,
                      flat=f"weave-cut {click.get_current_context().info_name}")


def _suffix_check(output: str | None, allowed: tuple[str, ...]) -> None:
    if output is not None:
        check_suffix(output, ("." + a for a in allowed))


class CurveType(click.ParamType):
    """LEVEL:EDGE, an edge of a level whose curve to box-count."""

    name = "level:edge"

    def convert(self, value, param, ctx):
        if isinstance(value, tuple):
            return value
        try:
            level, edge = (int(p) for p in value.split(":"))
        except ValueError:
            self.fail(f"{value!r} is not LEVEL:EDGE like 1:17", param, ctx)
        if level < 0 or edge < 0:
            self.fail(f"{value!r}: level and edge must be >= 0", param, ctx)
        return level, edge


class WindowType(click.ParamType):
    """X0,Y0,X1,Y1 in model units."""

    name = "x0,y0,x1,y1"

    def convert(self, value, param, ctx):
        if isinstance(value, tuple):
            return value
        try:
            box = tuple(float(p) for p in value.split(","))
        except ValueError:
            box = ()
        if len(box) != 4 or not all(math.isfinite(v) for v in box):
            self.fail(f"{value!r} is not four numbers X0,Y0,X1,Y1", param, ctx)
        if max(map(abs, box)) > 1e9:
            self.fail(f"{value!r}: coordinates beyond +-1e9 (meshes stay within it)", param, ctx)
        if not (box[0] < box[2] and box[1] < box[3]):
            self.fail(f"{value!r}: need X0 < X1 and Y0 < Y1", param, ctx)
        return box


def _output_option(suffixes: str):
    return click.option("-o", "--output", type=click.Path(dir_okay=False),
                        help=f"Also write a picture ({suffixes}).")


@click.command("fractal", context_settings=CONTEXT)
@input_argument
@snub_options
@click.option("--curve", type=CurveType(), default=None,
              help="Box-count the curve grown from this LEVEL:EDGE [default: the longest "
                   "inner edge of level --born with an outer end].")
@click.option("--born", type=click.IntRange(0, 40), multiple=True, default=(1, 2),
              show_default=True, help="Levels whose edges start the inner-curve table "
              "(repeat the option for several).")
@click.option("--json", "as_json", is_flag=True, help="Print JSON (all numbers, all boxes).")
@_output_option(".svg, .dxf, .pdf or .png")
@page_option
@force_option
@reports_errors
def fractal_command(input_mesh, levels, no_smooth, chirality, centre, allow_nonconvex, curve,
                    born, as_json, output, page) -> None:
    """The boundary L-system, dimensions and inner-curve growth of INPUT refined --levels times.

    \b
    Examples:
      weave-cut fractal pentagon --levels 7
      weave-cut fractal pentagon --levels 8 --json
      weave-cut fractal pentagon --levels 5 -o fractal.svg
      weave-cut fractal square-grid:3x3 --levels 6 --curve 2:40
    """
    from ..figures import fractal as figures

    _suffix_check(output, tuple(export.formats()))
    if curve is not None and curve[0] > levels:
        raise click.BadParameter(f"level {curve[0]} is beyond --levels {levels}",
                                 param_hint="'--curve'")
    h = _hierarchy(input_mesh, levels, no_smooth, chirality, centre, allow_nonconvex)
    try:
        report = fr.fractal_report(h, chirality, curve, born)
    except ValueError as exc:
        raise click.ClickException(str(exc)) from exc
    report = {"input": input_title(input_mesh), "smooth": not no_smooth, "centre": centre,
              "chirality": chirality, **report}
    if output:
        drawing = figures.fractal_drawing(h, min(min(born, default=1), levels))
        write_drawing(drawing, output, page)
    if as_json:
        click.echo(json.dumps(report, indent=2, allow_nan=False))
        return
    _print_fractal(report)


def _fixed(value: float | None) -> str:
    """Four decimals, or "-" for a figure too few box sizes leave undefined."""
    return "-" if value is None else f"{value:.4f}"


def _print_box(title: str, box: dict) -> None:
    if "skipped" in box:
        click.echo(f"{title}: not measured ({box['skipped']})")
        return
    s = box["sizes"]
    stderr, halves = (_fixed(box["stderr"]), [_fixed(h) for h in box["halves"]])
    click.echo(f"{title}: D = {box['dimension']:.4f} \u00b1 {stderr} (least-squares "
               f"slope of log N against log 1/eps and its standard error, r2 = {box['r2']:.5f}, "
               f"{len(s)} box sizes {s[0]:.4g} .. {s[-1]:.4g}, counts averaged over "
               f"{box['grids']} shifted grids; the coarser and finer half of the sizes alone "
               f"give {halves[0]} and {halves[1]})")
    click.echo("  box size     " + " ".join(f"{x:9.3g}" for x in s[::4]))
    click.echo("  boxes        " + " ".join(f"{x:9.1f}" for x in box["counts"][::4]))


def _print_fractal(r: dict) -> None:
    click.echo(f"alpha = atan(sqrt(3)/5) = {r['alpha_rad']:.9f} rad = {r['alpha_deg']:.6f} deg "
               f"(from the Z-triplet: {r['alpha_from_z_triplet_deg']:.6f} deg)")
    ls = r["lsystem"]
    click.echo(f"L-system: {ls['rule']}   v: rot(+alpha)  ^: rot(-alpha)  +: rot(+pi/3)  "
               f"-: rot(-pi/3); every step scales edges by 1/sqrt(7) = {ls['scale']:.6f}")
    err = r["boundary_lsystem_max_error"]
    click.echo(f"boundary = L-system curve at levels 0..{r['levels']}: largest deviation "
               f"{max(err):.2e}")
    click.echo(f"dimension (analytic): log 3 / log sqrt 7 = {r['analytic_dimension']:.6f}")
    if "boundary_box_counting" in r:
        _print_box(f"box counting, boundary at level {r['levels']}", r["boundary_box_counting"])
    if "inner_curve" in r:
        c = r["inner_curve"]
        _print_box(f"box counting, curve from level {c['level']} edge {c['edge']}", c)
    for m in r.get("growth_monotonicity", []):
        click.echo(f"  {m['kind']:12} born {m['born']}: {m['curves']} curves; growth per curve "
                   f"from level {m['levels'][0]} to {m['levels'][1]}: {m['constant']} constant, "
                   f"{m['rising']} rising, {m['falling']} falling, {m['turning']} turning")
    if "inner_curves" in r:
        click.echo("curves born as one edge at level 'born' "
                   "(growth = L(t)/L(t-1); boundary: 3/sqrt7 = 1.133893):")
        click.echo(f"  {'kind':12} {'born':>4} {'level':>5} {'curves':>7} {'edges':>6} {'mean length':>12} "
                   f"{'mean chord':>11} {'growth':>8} {'min':>8} {'median':>8} {'max':>8} {'log3/log(3/g)':>13}")
        for row in r["inner_curves"]:
            g = (f"{row['growth']:8.4f} {row['growth_min']:8.4f} {row['growth_median']:8.4f} "
                 f"{row['growth_max']:8.4f} {row['implied_dimension']:13.4f}"
                 if "growth" in row else "")
            click.echo(f"  {row['kind']:12} {row['born']:4} {row['level']:5} {row['curves']:7} "
                       f"{row['edges_each']:6} {row['mean_length']:12.6f} "
                       f"{row['mean_chord']:11.6f} {g}")


@click.command("levels", context_settings=CONTEXT)
@input_argument
@snub_options
@click.option("--size", type=click.IntRange(1, 1 << 20), default=1024, show_default=True,
              help="Pixels along the longer side (at most 16384 for one PNG; more with --tiles).")
@click.option("--window", type=WindowType(), default=None,
              help="Zoom window X0,Y0,X1,Y1 in mesh units; only faces near it are refined.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default=None,
              help="Output .png file.")
@click.option("--tiles", type=click.Path(file_okay=False), default=None,
              help="Write a DeepZoom tile pyramid (levels.dzi, levels_files/) into this folder "
                   "instead of one PNG; tiles render in parallel.")
@click.option("--tile-size", type=click.IntRange(16, 4096), default=256, show_default=True,
              help="Tile side in pixels (with --tiles).")
@click.option("--jobs", "-j", type=click.IntRange(1, 256), default=None,
              help="Processes rendering tiles (with --tiles; default: one per core).")
@click.option("--json", "as_json", is_flag=True, help="Print pixels reached per level as JSON.")
@force_option
@reports_errors
def levels_command(input_mesh, levels, no_smooth, chirality, centre, allow_nonconvex, size,
                   window, output, tiles, tile_size, jobs, as_json) -> None:
    """Colour every pixel by the first refinement step with a vertex in it (Figure colorLevels).

    Levels 0-9 get brighter (black, purple, orange, pale yellow), 10-12 turn green; pixels no
    vertex reached stay white. With --window only the faces that can influence the window are
    refined, so deep zooms (level 12 and beyond) stay fast. With --tiles the image becomes a
    DeepZoom pyramid for OpenSeadragon and other deep-zoom viewers: every full-resolution tile
    is refined on its own, in parallel, and equals its part of the single image.

    \b
    Examples:
      weave-cut levels pentagon --levels 9 --size 2048 -o levels.png
      weave-cut levels pentagon --levels 12 --size 1024 --window 0.05,0.25,0.2,0.4 -o zoom.png
      weave-cut levels pentagon --levels 12 --size 16384 --tiles poster/
    """
    if (output is None) == (tiles is None):
        raise click.UsageError("give either -o FILE.png or --tiles FOLDER")
    _suffix_check(output, ("png",))
    if output is not None and size > 16384:
        raise click.BadParameter("at most 16384 pixels for one PNG; use --tiles",
                                 param_hint="'--size'")
    if not levels < lv.UNSET:
        raise click.BadParameter(f"at most {lv.UNSET - 1}", param_hint="'--levels'")
    mesh = load_mesh(input_mesh, allow_nonconvex, flat="weave-cut levels")
    options = {"smooth": not no_smooth, "centre": centre, "chirality": chirality}
    grid = lv.Grid.fit(lv.default_window(mesh) if window is None else window, size)
    if tiles is not None:
        lv.check_tiles_memory(mesh, levels, grid, tile_size, jobs or os.cpu_count() or 1)
        made = deepzoom.write_pyramid(mesh, levels, grid, tiles, tile_size=tile_size,
                                      jobs=jobs, **options)
        if as_json:
            click.echo(json.dumps({"input": input_title(input_mesh),
                                   "levels": levels, "tiles": tiles,
                                   **made}, indent=2, allow_nan=False))
        else:
            summary(f"{tiles}/{deepzoom.NAME}.dzi: {grid.width} x {grid.height} px, "
                    f"{made['tiles']:,} tiles in {made['pyramid_levels']} levels "
                    f"({made['full_resolution_tiles']:,} rendered by {made['jobs']} "
                    f"process{'es' if made['jobs'] > 1 else ''} in "
                    f"{made['render_seconds']:.1f} s)")
        return
    lv.check_memory(mesh, levels, grid, windowed=window is not None)
    image, grid = lv.level_image(mesh, levels, size, window, **options)
    title = f"{input_title(input_mesh)}: first level per pixel, to level {levels}"
    write_png(lv.png_bytes(lv.colour(image)), output, title)
    hit = image != lv.UNSET
    if as_json:
        per_level = np.bincount(image[hit].ravel().astype(np.int64), minlength=levels + 1)
        click.echo(json.dumps({"input": input_title(input_mesh), "levels": levels, "output": output,
                               "width": grid.width, "height": grid.height,
                               "window": list(grid.window), "pixels_reached": int(hit.sum()),
                               "pixels_per_level": per_level.tolist()}, indent=2,
                               allow_nan=False))
        return
    summary(f"{output}: {grid.width} x {grid.height} px over "
            f"{', '.join(f'{v:g}' for v in grid.window)}; {int(hit.sum()):,} pixels reached, "
            f"the last at level {int(image[hit].max()) if hit.any() else '-'}")


def _levels_beside(values: dict) -> list[Path]:
    """The existing files a run with ``values`` writes into its ``--tiles`` folder (the
    descriptor and the pyramid's tiles), and any symlink there: ``build`` checks them before
    the first job runs."""
    if values.get("tiles") is None:
        return []
    folder = Path(values["tiles"])
    tiles = folder / f"{deepzoom.NAME}_files"
    return [p for p in (folder / f"{deepzoom.NAME}.dzi", tiles, *tiles.rglob("*"))
            if p.is_symlink() or p.is_file()]


levels_command.beside = _levels_beside


@click.command("convexity", context_settings=CONTEXT)
@input_argument
@snub_options
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
@_output_option(".svg, .dxf, .pdf or .png: the last level, non-convex faces red")
@page_option
@force_option
@reports_errors
def convexity_command(input_mesh, levels, no_smooth, chirality, centre, allow_nonconvex,
                      as_json, output, page) -> None:
    """Where non-convex faces occur at every level: inner or boundary faces, and at which kind
    of vertex (input vertex, Z vertex or face centre; inner or outer; its degree).

    The paper asks whether smoothing always keeps tiles convex; this answers it for INPUT.

    \b
    Examples:
      weave-cut convexity pentagon --levels 6 --no-smooth -o nonconvex.svg
      weave-cut convexity ngon:24 --levels 4 --centre area
    """
    from ..figures import subdivision as figures

    _suffix_check(output, tuple(export.formats()))
    h = _hierarchy(input_mesh, levels, no_smooth, chirality, centre, allow_nonconvex)
    rows = cv.convexity_report(h)
    if output:
        title = f"{input_title(input_mesh)}, level {levels}: non-convex faces"
        drawing = figures.convexity_drawing(h[-1].mesh, title=title)
        write_drawing(drawing, output, page)
    if as_json:
        click.echo(json.dumps({"input": input_title(input_mesh),
                               "smooth": not no_smooth, "centre": centre,
                               "chirality": chirality, "levels": rows}, indent=2, allow_nan=False))
        return
    click.echo(f"{input_mesh} ({'smoothed' if not no_smooth else 'not smoothed'}, "
               f"{centre} centres)")
    click.echo(f"{'level':>5} {'faces':>10} {'non-convex':>10} {'inner':>7} {'boundary':>8} "
               f"{'max angle':>9}  reflex corners at")
    for r in rows:
        at = ", ".join(f"{k}: {v}" for k, v in r["reflex_at"].items()) or "-"
        deg = ", ".join(f"{k}: {v}" for k, v in r["reflex_vertex_degrees"].items())
        click.echo(f"{r['level']:5} {r['faces']:10,} {r['nonconvex_faces']:10,} "
                   f"{r['nonconvex_inner_faces']:7,} {r['nonconvex_boundary_faces']:8,} "
                   f"{r['max_angle_deg']:9.2f}  {at}" + (f" (degrees {deg})" if deg else ""))
    total = sum(r["nonconvex_faces"] for r in rows)
    click.echo("all faces convex at every level" if total == 0 else
               f"first non-convex face at level "
               f"{next(r['level'] for r in rows if r['nonconvex_faces'])}")


def _complete_figures(ctx, param, incomplete: str) -> list[CompletionItem]:
    from ..figures import gallery

    return [CompletionItem(n) for n in gallery.FIGURES if n.startswith(incomplete)]


@click.command("figure", context_settings=CONTEXT)
@click.argument("name", required=False, shell_complete=_complete_figures)
@click.option("--list", "list_all", is_flag=True, help="List the figures.")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Output file (.svg, .dxf, .pdf, .png; .png for raster figures).")
@page_option
@force_option
@reports_errors
def figure_command(name, list_all, output, page) -> None:
    """Reproduce one of the paper's figures.

    \b
    Examples:
      weave-cut figure --list
      weave-cut figure edge-renders -o edges.svg
      weave-cut figure level-image -o levels.png
    """
    from ..figures import gallery

    if list_all or name is None:
        if name is None and not list_all:
            raise click.UsageError("give a figure NAME, or --list")
        width = max(len(n) for n in gallery.FIGURES)
        for key, (description, _) in gallery.FIGURES.items():
            click.echo(f"{key:{width}}  {description}")
        return
    if name not in gallery.FIGURES:
        raise click.BadParameter(f"unknown figure {name!r}{nearest(name, gallery.FIGURES)}; "
                                 "see weave-cut figure --list", param_hint="'NAME'")
    if output is None:
        raise click.UsageError("give an output file with -o")
    _suffix_check(output, ("png",) if gallery.is_picture(name) else tuple(export.formats()))
    result = gallery.FIGURES[name][1]()  # (checked first: a picture takes seconds)
    if isinstance(result, bytes):
        write_png(result, output, gallery.FIGURES[name][0])
    else:
        write_drawing(result, output, page)

