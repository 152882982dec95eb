"""``weave-cut puzzle``: the laser-cut two-sided jigsaw puzzle of the paper's section 6."""

from __future__ import annotations

import json
from pathlib import Path

import click

from .. import export
from ..puzzle import files as pf
from ..puzzle.pieces import build_puzzle, colour_puzzle
from ..layout.tiling import tile
from ..units import PAPER_SIZES
from ..weave.colour import palette
from ..fileio import write_atomic
from .common import (CONTEXT, Length, PageSize, drawing_options, load_mesh, provenance,
                     reports_errors)


@click.command("puzzle", context_settings=CONTEXT)
@click.argument("input_mesh", metavar="[INPUT]", default="pentagon")
@drawing_options
@click.option("-o", "--output", "out_dir", required=True,
              type=click.Path(file_okay=False), help="Folder for the files (created).")
@click.option("--levels", "-n", type=click.IntRange(2, 7), default=4, show_default=True,
              help="Refinement level t of the pieces (the front shows t-1).")
@click.option("--size", type=Length(), default="50cm", show_default=True,
              help="Diagonal of the input pentagon (largest vertex distance).")
@click.option("--mode", type=click.Choice(["shared", "separate", "both"]), default="both",
              show_default=True, help="shared: one sheet, shared edges cut once (no kerf "
              "compensation possible); separate: kerf-offset pieces nested on sheets.")
@click.option("--material", default=pf.DEFAULT_MATERIAL, show_default=True,
              help="Material preset (templates/materials): kerf, sheet, speed.")
@click.option("--kerf", type=Length(inclusive=True), default=None,
              help="Beam width (default: the material's); 0 leaves it to the laser software.")
@click.option("--sheet", type=PageSize(), default=None, help="Sheet WxH, e.g. 1000x700mm "
              "(default: the material's).")
@click.option("--laser", "laser_name", default=pf.DEFAULT_LASER, show_default=True,
              help="Colour conventions (templates/laser): lightburn, epilog-uls, ponoko.")
@click.option("--frame", "frame_width", type=Length(), default="20mm", show_default=True,
              help="Frame width beyond the hexagon ring.")
@click.option("--numbers", is_flag=True, help="Engrave piece numbers (engrave layer).")
@click.option("--speed", type=click.FloatRange(min=0, min_open=True), default=None,
              help="Cutting speed in mm/s for the time estimate (default: the material's).")
@click.option("--page", type=click.Choice(sorted(PAPER_SIZES)), default="a4",
              show_default=True, help="Printer page for the tiled PDF guides.")
@click.option("--palette", "palette_name", default="puzzle", show_default=True)
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
    mat = pf.material(material)
    kerf = mat["kerf"] if kerf is None else kerf
    sheet = mat["sheet"] if sheet is None else sheet
    speed = mat["cut_speed"] if speed is None else speed
    las = pf.laser(laser_name)
    puzzle = build_puzzle(load_mesh(input_mesh), levels, size, frame_width)
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
    folder = Path(out_dir)
    folder.mkdir(parents=True, exist_ok=True)
    meta = provenance()
    for name, drawing in files.items():
        export.write(drawing.with_metadata(**meta), folder / name)
    written = list(files)
    info = pf.summary(puzzle, results, speed, colouring)
    info.update(material=mat["name"], kerf_mm=kerf, sheet_mm=list(sheet), laser=las.name,
                files=sorted(written + ["puzzle-summary.json"]))
    text = json.dumps(info, indent=2)
    write_atomic(folder / "puzzle-summary.json", (text + "\n").encode("utf-8"))
    click.echo(text if as_json else pf.summary_text(info))
