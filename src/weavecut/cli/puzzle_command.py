"""``weave-cut puzzle``: the laser-cut two-sided jigsaw puzzle of the paper's section 6."""

from __future__ import annotations

import json

import click

from .. import export
from ..units import PAPER_SIZES
from ..weave.colour import palette
from ..fileio import make_folder, write_atomic
from .common import (CONTEXT, Finite, Length, PageSize, check_layout, complete_inputs,
                     complete_preset, flag_nonconvex, load_mesh, provenance, reports_errors,
                     summary)


@click.command("puzzle", context_settings=CONTEXT)
@click.argument("input_mesh", metavar="[INPUT]", default="pentagon",
                shell_complete=complete_inputs)
@click.option("-o", "--output", "out_dir", required=True,
              type=click.Path(file_okay=False), help="Folder for the files (created).")
@click.option("--levels", "-n", type=click.IntRange(2, 7), default=4, show_default=True,
              help="Refinement level t of the pieces (the front shows t-1).")
@click.option("--size", type=Length(), default="50cm", show_default=True,
              help="Diagonal of the input pentagon (largest vertex distance).")
@click.option("--mode", type=click.Choice(["shared", "separate", "both"]), default="both",
              show_default=True, help="shared: one sheet, shared edges cut once (no kerf "
              "compensation possible); separate: kerf-offset pieces nested on sheets.")
@click.option("--material", default="poplar-3mm", show_default=True,
              shell_complete=complete_preset("materials"),
              help="Material preset (templates/materials): kerf, sheet, speed.")
@click.option("--kerf", type=Length(inclusive=True), default=None,
              help="Beam width (default: the material's); 0 leaves it to the laser software.")
@click.option("--sheet", type=PageSize(), default=None, help="Sheet WxH, e.g. 1000x700mm "
              "(default: the material's).")
@click.option("--laser", "laser_name", default="lightburn", show_default=True,
              shell_complete=complete_preset("laser"),
              help="Colour conventions (templates/laser): lightburn, epilog-uls, ponoko.")
@click.option("--frame", "frame_width", type=Length(), default="20mm", show_default=True,
              help="Frame width beyond the hexagon ring.")
@click.option("--numbers", is_flag=True, help="Engrave piece numbers (engrave layer).")
@click.option("--speed", type=Finite(min=0, min_open=True, max=10_000), default=None,
              help="Cutting speed in mm/s for the time estimate (default: the material's).")
@click.option("--page", type=click.Choice(sorted(PAPER_SIZES)), default="a4",
              show_default=True, help="Printer page for the tiled PDF guides.")
@click.option("--palette", "palette_name", default="puzzle", show_default=True,
              shell_complete=complete_preset("palettes"))
@click.option("--json", "as_json", is_flag=True, help="Print the summary as JSON.")
@reports_errors
def puzzle_command(input_mesh, out_dir, levels, size, mode, material, kerf, sheet, laser_name,
                   frame_width, numbers, speed, page, palette_name, as_json) -> None:
    """Write the jigsaw puzzle's cut files and painting guides to a folder.

    \b
    Files: puzzle-shared-cut.{svg,dxf}, puzzle-separate-sheet-N.{svg,dxf},
    puzzle-{front,back}-guide.svg (1:1) and .pdf (tiled on printer pages),
    puzzle-summary.json.
    \b
    Example:
      weave-cut puzzle -o build/puzzle --material poplar-3mm --numbers
    """
    from ..layout.tiling import tile
    from ..puzzle import files as pf
    from ..puzzle.pieces import build_puzzle, colour_puzzle

    mat = pf.material(material)
    kerf = mat["kerf"] if kerf is None else kerf
    sheet = mat["sheet"] if sheet is None else sheet
    speed = mat["cut_speed"] if speed is None else speed
    las = pf.laser(laser_name)
    puzzle = build_puzzle(check_layout(load_mesh(input_mesh), "the puzzle", connected=True),
                          levels, size, frame_width)
    pf.check_kerf(puzzle, kerf)
    colouring = colour_puzzle(puzzle, palette(palette_name))
    results, files = {}, {}  # everything is laid out before the first file is written
    if mode in ("shared", "both"):
        results["shared"] = pf.shared_cut(puzzle, las, numbers)
        for fmt in ("svg", "dxf"):
            files[f"puzzle-shared-cut.{fmt}"] = results["shared"].drawing
    if mode in ("separate", "both"):
        results["separate"] = pf.separate_cut(puzzle, las, kerf, sheet, numbers=numbers)
        for n, one in enumerate(pf.split_sheets(results["separate"].drawing), start=1):
            for fmt in ("svg", "dxf"):
                files[f"puzzle-separate-sheet-{n}.{fmt}"] = one
    for side in ("front", "back"):
        g = pf.guide(puzzle, colouring, side, numbers)
        files[f"puzzle-{side}-guide.svg"] = g
        files[f"puzzle-{side}-guide-{page}.pdf"] = tile(g, PAPER_SIZES[page])
    folder = make_folder(out_dir)
    meta = provenance()
    for name, drawing in files.items():
        export.write(drawing.with_metadata(**meta), folder / name)
    written = list(files)
    info = pf.summary(puzzle, results, speed, colouring)
    info.update(material=mat["name"], kerf_mm=kerf, sheet_mm=list(sheet), laser=las.name,
                **flag_nonconvex(puzzle.hierarchy),
                files=sorted(written + ["puzzle-summary.json"]))
    text = json.dumps(info, indent=2)
    write_atomic(folder / "puzzle-summary.json", (text + "\n").encode("utf-8"))
    if as_json:
        click.echo(text)
    else:
        summary(pf.summary_text(info))
