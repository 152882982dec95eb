"""``weave-cut puzzle``: the laser-cut two-sided jigsaw puzzle of the paper's section 6."""

from __future__ import annotations

import functools

import json
import os

from pathlib import Path

import click
from click.core import ParameterSource
import numpy as np

from .. import export
from ..errors import WeaveCutError
from ..subdivision import subdivide
from ..units import PAPER_SIZES
from ..weave.colour import palette
from ..fileio import make_folder, write_atomic
from .common import (CONTEXT, DRAWING_KEY, Choice, Finite, Length, PageSize, complete_inputs,
                     complete_preset, drawing_options, flag_nonconvex, force_option,
                     formats_option, html_option, load_mesh, provenance, reports_errors,
                     summary)


@click.command("puzzle", context_settings=CONTEXT)
@click.argument("input_mesh", metavar="[INPUT]", default="pentagon",
                shell_complete=complete_inputs)
@drawing_options
@click.option("-o", "--output", "out_dir", required=True,
              type=click.Path(file_okay=False), help="Folder for the files (made if it is "
              "not there; the folder above it must exist).")
@click.option("--levels", "-n", type=click.IntRange(2, 7), default=4, show_default=True,
              help="Refinement level t of the pieces (the front shows t-1).")
@click.option("--size", type=Length(), default="50cm", show_default=True,
              help="Width of the finished puzzle (the frame's outer outline); for the "
              "pentagon its diagonal, the largest corner-to-corner distance (the paper's "
              "50 cm).")
@click.option("--mode", type=Choice(["shared", "separate", "both"]), default="both",
              show_default=True, help="shared: one board, shared edges cut once (no kerf "
              "compensation possible); separate: kerf-offset pieces nested on sheets, the frame "
              "split into dovetailed parts when it is larger than a sheet.")
@click.option("--material", default="poplar-3mm", show_default=True,
              shell_complete=complete_preset("materials"),
              help="Material preset (templates/materials): thickness, kerf, sheet, speed.")
@click.option("--kerf", type=Length(inclusive=True), default=None,
              help="Beam width (default: the material's); 0 leaves it to the laser software.")
@click.option("--sheet", type=PageSize(), default=None, help="Sheet WxH, e.g. 600x400mm "
              "(default: the material's).")
@click.option("--laser", "laser_name", default="lightburn", show_default=True,
              shell_complete=complete_preset("laser"),
              help="Colour conventions (templates/laser): lightburn, epilog-uls, ponoko.")
@formats_option
@click.option("--frame", "frame_width", type=Length(), default="20mm", show_default=True,
              help="Frame width beyond the hexagon ring.")
@click.option("--numbers", is_flag=True, help="Engrave piece numbers as single strokes "
              "(engrave layer); the guides always show them.")
@click.option("--speed", type=Finite(min=0, min_open=True, max=10_000), default=None,
              help="Cutting speed in mm/s for the time estimate (default: the material's).")
@click.option("--page", type=Choice(sorted(PAPER_SIZES)), default="a4",
              show_default=True, help="Printer page for the colour keys and tiled guides.")
@click.option("--palette", "palette_name", default="puzzle", show_default=True,
              shell_complete=complete_preset("palettes"),
              help="Paint families (templates/palettes); the default is the paper's green, "
              "blue and pink.")
@click.option("--json", "as_json", is_flag=True, help="Print the summary as JSON.")
@click.option("--preview", is_flag=True, help="Only draw the painted front and back "
              "(puzzle-preview.svg in -o): no cut files, guides or README, in a fraction of a "
              "second.")
@force_option
@reports_errors
@html_option
def puzzle_command(input_mesh, out_dir, levels, size, mode, material, kerf, sheet, laser_name,
                   formats, frame_width, numbers, speed, page, palette_name, as_json,
                   preview) -> None:
    """Write the jigsaw puzzle's workshop folder: cut files, painting guides, README.txt.

    \b
    Files: puzzle-shared-cut.{svg,dxf}, puzzle-separate-sheet-N.{svg,dxf} (and .lbrn2 with
    --formats),
    puzzle-{front,back}-guide.svg (1:1) and -PAGE.pdf (colour key, then tiled pages),
    puzzle-summary.json, README.txt (what goes where, the order of work).
    \b
    A drawing (.svg, .dxf) of one outline is meshed inside with its curves redrawn as
    straight runs of one length, so the hexagon ring along them keeps one size; --cell and
    --levels set how many pieces it makes. Without them the cell and level (3 or 2) with the
    most pieces that are all at least 15 mm across and 3 x the thickness wide at --size are
    chosen and reported. An outline with sharp tips (a star) needs --mesh tri: hexagons and
    squares there make pentagons that turn over.
    \b
    Examples:
      weave-cut puzzle -o puzzle --material poplar-3mm --numbers
      weave-cut puzzle heart.svg --cell 39mm --levels 2 --size 30cm -o heart
      weave-cut puzzle --levels 3 --palette puzzle --preview -o look
    """
    import shapely

    from ..mesh_io import read_valid_mesh
    from ..puzzle import files as pf
    from ..readers import SUFFIXES as DRAWINGS  # not the readers themselves: a mesh needs none
    from ..puzzle import workshop
    from ..puzzle.colouring import colour_puzzle, palette_names
    from ..puzzle.frame import fits, split_frame
    from ..puzzle.guides import colour_key, guide, printed
    from ..puzzle.guide_numbers import guide_numbers, warnings as number_warnings
    from ..layout.label_checks import figures as label_figures
    from ..puzzle.guides import preview as painted_preview
    from ..puzzle.pieces import build_puzzle
    from ..puzzle.model3d import puzzle_model
    from ..export.gltf import glb_bytes
    from ..layout.lasersetup import kerf_note, laser, laser_job, output_formats

    mat = workshop.material(material)
    kerf = mat["kerf"] if kerf is None else kerf
    sheet = mat["sheet"] if sheet is None else sheet
    speed = mat["cut_speed"] if speed is None else speed
    las = laser(laser_name)
    formats = output_formats(formats, laser_name)
    job = laser_job(mat, kerf_note(kerf, "the separate sheets' outlines (not the shared-edge "
                                   "cut's, whose edges are cut once)"))
    pal = palette(palette_name)
    from ..validation import check_layout

    # a drawn outline is meshed with straight runs of one length, so the ring keeps one size
    ctx = click.get_current_context()
    drawing = ctx.meta.setdefault(DRAWING_KEY, {})
    drawing["runs"] = True

    @functools.cache  # the defaults and the warnings try the same cells again
    def read_drawing(cell):
        return check_layout(read_valid_mesh(input_mesh, **{**drawing, "cell": cell}),
                            "the puzzle", connected=True)

    meshed = Path(input_mesh).suffix.lower() in DRAWINGS and drawing.get("mesh") != "none"
    read_at = read_drawing if meshed else None  # a drawing meshed at a cell size, or not
    if read_at is not None and drawing.get("cell") is None:
        given = ctx.get_parameter_source("levels") is not ParameterSource.DEFAULT
        cell, levels, puzzle = workshop.drawing_defaults(
            read_at, size, frame_width, mat["thickness"], (levels,) if given else None)
        reach = ("so pieces are at least" if workshop.comfortable(puzzle, mat["thickness"])
                 else "the coarsest tried; pieces still fall short of")
        chosen = {"cell_mm": cell, "levels": levels, "text": (
            f"chose --cell {cell:g}mm{'' if given else f' --levels {levels}'} "
            f"({puzzle.hierarchy[0].mesh.n_faces} faces, {puzzle.n_pieces} pieces) {reach} "
            f"{workshop.MIN_ACROSS:g} mm across and {workshop.MIN_WIDTH_X_THICKNESS:g} x "
            f"{mat['thickness']:g} mm wide at --size {size:g}mm; give --cell and --levels "
            "to choose")}
    else:
        cell, chosen = drawing.get("cell"), None
        mesh = check_layout(load_mesh(input_mesh), "the puzzle", connected=True)
        puzzle = build_puzzle(subdivide(mesh, levels), size, frame_width,
                              "diagonal" if input_mesh == "pentagon" else "width")
    if preview:
        colouring = colour_puzzle(puzzle, pal, palette_names(palette_name, pal))
        path = make_folder(out_dir) / PREVIEW
        export.write(painted_preview(puzzle, colouring).with_metadata(**provenance()), path)
        return summary(f"{path}: the front and back of {puzzle.n_pieces} pieces, painted")
    pf.check_kerf(puzzle, kerf)
    warnings = workshop.size_warnings(puzzle, mat["thickness"], read_at,
                                      cell if read_at is not None else None)
    colouring = colour_puzzle(puzzle, pal, palette_names(palette_name, pal))
    engraved = pf.piece_numbers(puzzle) if numbers else None
    if engraved is not None:
        warnings += pf.number_warnings(engraved)
    results, files = {}, {}  # everything is laid out before the first file is written
    frame_parts = None
    if mode in ("shared", "both"):
        board = pf.placement(puzzle)[:2]
        if fits(np.array([shapely.box(0, 0, *board)], dtype=object), sheet, 0.0)[0]:
            results["shared"] = pf.shared_cut(puzzle, las, engraved)
            for fmt in formats:
                files[f"puzzle-shared-cut.{fmt}"] = results["shared"].drawing
        else:
            note = (f"the shared-edge cut needs one {board[0]:.0f} x {board[1]:.0f} mm board, "
                    f"larger than the {sheet[0]:g} x {sheet[1]:g} mm sheet")
            if mode == "shared":
                raise WeaveCutError(f"{note}; use --mode separate (the frame is then split "
                                    "into parts) or a larger --sheet")
            warnings.append(f"{note}: only the separate sheets are written")
    if mode in ("separate", "both"):
        frame_parts = split_frame(puzzle.frame, puzzle.outer, sheet, 5.0, kerf)
        results["separate"] = pf.separate_cut(puzzle, las, kerf, sheet, numbers=engraved,
                                              frame_parts=frame_parts)
        for n, one in enumerate(pf.split_sheets(results["separate"].drawing), start=1):
            for fmt in formats:
                files[f"puzzle-separate-sheet-{n}.{fmt}"] = one
    guides = {}
    for side in ("front", "back"):
        numbers = guide_numbers(puzzle, colouring, side)
        warnings += number_warnings(numbers, side)
        guides[side] = g = guide(puzzle, colouring, side, numbers)
        files[f"puzzle-{side}-guide.svg"] = g
        files[f"puzzle-{side}-guide-{page}.pdf"] = printed(
            g, colour_key(puzzle, colouring, side, PAPER_SIZES[page]), PAPER_SIZES[page])
    nonconvex = flag_nonconvex(puzzle.hierarchy, into=warnings)  # README.txt carries them
    info = workshop.summary(puzzle, results, speed, colouring)
    info.update(label_figures([g.sheets[0] for g in guides.values()]))
    info.update(material=mat["description"], thickness_mm=mat["thickness"], kerf_mm=kerf,
                sheet_mm=list(sheet), laser=las.name,
                **({"chosen": chosen} if chosen else {}),
                frame_parts=1 if frame_parts is None else len(frame_parts), warnings=warnings,
                guide_pages={side: len(files[f"puzzle-{side}-guide-{page}.pdf"].sheets)
                             for side in guides},
                numbers=engraved is not None, **nonconvex,
                operations={role: {"speed_mm_s": op.speed, "power_pct": op.power,
                                   "passes": op.passes}
                            for role, op in job.operations.items()},
                files=sorted(list(files) + ["puzzle-summary.json", "README.txt", MODEL]))
    text = json.dumps(info, indent=2, allow_nan=False)
    folder = make_folder(out_dir)
    meta = provenance()
    for name, drawing in files.items():
        export.write(drawing.with_metadata(**meta), folder / name, job=job)
    write_atomic(folder / "README.txt", workshop.readme(info, page).encode("utf-8"))
    write_atomic(folder / "puzzle-summary.json", (text + "\n").encode("utf-8"))
    write_atomic(folder / MODEL, glb_bytes(puzzle_model(puzzle, colouring, mat["thickness"]),
                                           name="weave-cut puzzle"))
    for w in warnings:
        click.echo(f"weave-cut: warning: {w}", err=True)
    if as_json:
        click.echo(text)
    else:
        summary(workshop.summary_text(info))


MODEL = "puzzle-3d.glb"  # the finished puzzle in 3-D, painted, in its frame


WRITES = ("puzzle-shared-cut.*", "puzzle-separate-sheet-*.*", "puzzle-front-guide*.*",
          "puzzle-back-guide*.*", "puzzle-summary.json", MODEL, "README.txt")  # its names
PREVIEW = "puzzle-preview.svg"  # all that --preview writes


def _beside(values: dict) -> list[Path]:
    """The existing files a run may replace in its -o folder (only what it writes: the
    preview's one file with --preview, else WRITES): checked before any work
    (``outputs.may_replace``); the maker's other files there are no concern of the run."""
    folder = Path(values["out_dir"])
    names = (PREVIEW,) if values.get("preview") else WRITES
    return sorted({p for n in names for p in (folder.glob(n) if "*" in n else [folder / n])
                   if os.path.lexists(p)})


puzzle_command.beside = _beside
