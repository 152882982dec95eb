"""``weave-cut strands``: printable paper strips for the weave (paper section 5.2)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click
import numpy as np

from .. import export
from ..subdivision import snub, subdivide
from ..text import counted
from ..weave.colour import palette
from .common import (CONTEXT, Choice, Finite, Length, PageSize, complete_preset,
                     flag_nonconvex, force_option, formats_option, input_argument, input_title,
                     load_mesh, option_key, provenance, reports_errors, html_option, summary)
from .mesh_commands import project_option
from .outputs import OutputPath, check_suffix

FORMATS = ("pdf", "svg")
BY_HAND = "a ball's strips are printed and cut by hand so far"
KIT_REFUSES = {  # an input's kind -> (what the options are for, {option: why a kit of that kind
    # refuses it}): set away from its default, it is refused (``refuse_for_kit``); the web
    # form does not offer it for that kind of input
    "surface": ("flat models", {"layout": "a ball prints every strip once",
                                "turn": "a ball prints every strip once",
                                "cutter": BY_HAND, "laser-card": BY_HAND}),
    "flat": ("surfaces in space", {"project": ""}),
}


@click.command("strands", context_settings=CONTEXT)
@input_argument
@click.option("--levels", "-n", type=click.IntRange(1, 8), default=None,
              help="Snub steps [default: 2; pentagon-flower 3].")
@click.option("--page", type=PageSize(), default="a4", show_default=True,
              help="a4, letter, a3 or WxH like 300x200mm (with --laser-card: the "
                   "instructions' pages; --material sets the card's).")
@click.option("--tile-size", type=Length(), default=None,
              help="Distance across an octagon, with a unit: the print's true scale "
                   "[default: 20mm]. Strips under 8 mm wide are refused (they tear).")
@click.option("--size", "model_size", type=Length(), default=None,
              help="Width of the finished model, with a unit (e.g. 23cm); sets the tile size. "
                   "A ball's diameter [default: octagons 40 mm across].")
@click.option("--layout", type=Choice(("mixed", "module")), default="mixed", show_default=True,
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
@click.option("--chirality", type=Choice(snub.CHIRALITIES), default="left",
              show_default=True, help="Side the first Z edge turns to.")
@project_option
@click.option("--cutter", "cutter_name", default=None, shell_complete=complete_preset("cutters"),
              help="Print-and-cut: lay the strips out for this cutter (templates/cutters: "
                   "silhouette, cricut, scanncut, or a .toml file), print its registration "
                   "marks and write a cut file per strip page beside -o (PAGE-cut.svg, .dxf; "
                   "a Cricut's print image too, PAGE-print.svg: Design Space prints its own "
                   "marks).")
@click.option("--laser-card", is_flag=True,
              help="Laser-cut the strips from coloured card instead: -o is a folder of cut "
                   "sheets (strands-card-*.svg, .dxf), one set per strand colour, and "
                   "strands-assembly.pdf, the card's instructions on --page.")
@click.option("--material", default=None, shell_complete=complete_preset("materials"),
              help="With --laser-card: the card (templates/materials) [default: card-300gsm, "
                   "A4 sheets; card-300gsm-letter, card-300gsm-12in].")
@click.option("--laser", "laser_name", default="lightburn", show_default=True,
              shell_complete=complete_preset("laser"),
              help="With --laser-card: colour conventions (templates/laser).")
@formats_option
@click.option("-o", "--output", type=OutputPath(folder_with="laser_card"), required=True,
              help="Output: .pdf (one page per sheet) or .svg (a layer per page); with "
                   "--laser-card a folder (made if it is not there).")
@click.option("--json", "as_json", is_flag=True,
              help="Print the plan and the page checks (ink, smallest label) as JSON.")
@click.option("--preview", is_flag=True,
              help="Only draw the finished pattern in the strips' colours into -o (.svg, .pdf "
                   "or .png): no strips, no pages, in a fraction of a second; a ball from the "
                   "front and the back.")
@force_option
@reports_errors
@html_option
def strands_command(input_mesh, levels, page, tile_size, model_size, layout, margin,
                    palette_name, turn, chirality, project, cutter_name, laser_card, material,
                    laser_name, formats, output, as_json, preview) -> None:
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
      weave-cut strands square-grid --size 27cm --cutter silhouette -o square-cut.pdf
      weave-cut strands square-grid --size 27cm --laser-card --palette maritime-4 -o card/
      weave-cut strands pentagon-flower --preview -o look.svg
    """
    from ..papermodel.assembly import finished_size
    from ..papermodel.book import preset_for, strand_book, tile_size_for
    from ..papermodel.checks import report
    from ..weave.snub_weave import snub_weaves

    if preview and (cutter_name is not None or laser_card or as_json):
        raise click.BadParameter("--preview draws the pattern only; give it without --cutter, "
                                 "--laser-card and --json", param_hint="'--preview'")
    if not laser_card:
        check_suffix(output, ("." + f for f in FORMATS + (("png",) if preview else ())))
    if cutter_name is not None and laser_card:
        raise click.BadParameter("give --cutter (print and cut) or --laser-card, not both",
                                 param_hint="'--cutter'")
    if material is not None and not laser_card:
        raise click.BadParameter("--material goes with --laser-card", param_hint="'--material'")
    if formats is not None and not laser_card:
        raise click.BadParameter("--formats goes with --laser-card (a cutter's cut files are "
                                 "SVG and DXF)", param_hint="'--formats'")
    if laser_card and layout != "mixed":
        raise click.BadParameter("--layout module prints the module's pages once per "
                                 "direction; --laser-card cuts every strip once: leave --layout "
                                 "out", param_hint="'--layout'")
    if tile_size is not None and model_size is not None:
        raise click.BadParameter("give --tile-size or --size, not both", param_hint="'--size'")
    preset = preset_for(input_mesh)
    levels = preset["levels"] if levels is None else levels
    pal = palette(palette_name or preset["palette"])
    from ..validation import check_layout

    mesh = load_mesh(input_mesh)
    refuse_for_kit(kit_kind(mesh), input_mesh)
    if mesh.dim == 3:
        return ball(mesh, input_mesh, levels, page, tile_size, model_size, margin, pal,
                    chirality, project, output, as_json, preview)
    turn = preset["turn"] if turn is None else math.radians(turn)
    hierarchy = subdivide(check_layout(mesh, "the paper model"), levels, chirality=chirality)
    weaves = snub_weaves(hierarchy)
    title = f"weave-cut strands: {input_title(input_mesh)}, level {levels}"
    if preview:
        from ..papermodel.preview import pattern_preview

        export.write(pattern_preview(weaves, pal, turn, layout, f"{title}: preview")
                     .with_metadata(**provenance()), output)
        return summary(f"{output}: the pattern of {counted(weaves[-1].n_strands, 'strand')}, "
                       "as the strips are coloured")
    nonconvex = flag_nonconvex(hierarchy)
    if model_size is not None:
        tile_size = tile_size_for(weaves[-1], model_size)
    if laser_card:
        return _laser_card(weaves, palette_name or preset["palette"], material, laser_name,
                           formats, page,
                           margin, tile_size or 20.0, turn, title, output, as_json)
    limit, machine, words = None, None, {}
    if cutter_name is not None:
        from ..papermodel.cutter_words import cut_file_note, cutter_words
        from ..papermodel.printcut import BLEED, WASTE, cutter

        machine = cutter(cutter_name)
        machine.check(*page)
        margin, limit = max(margin, machine.margin), machine.limit(*page)
        words = {"words": cutter_words(machine, Path(output)),
                 "page_note": cut_file_note(Path(output), machine), "gap": WASTE,
                 "bleed": BLEED}
    try:
        book = strand_book(weaves, pal, page, tile_size or 20.0, margin, turn, title=title,
                           layout=layout, limit=limit, **words)
    except ValueError as exc:
        raise click.ClickException(str(exc)) from exc
    for warning in book.warnings:
        click.echo(f"weave-cut: warning: {warning}", err=True)
    extra = {}
    if machine is not None:
        extra = _print_and_cut(book, machine, output)
    else:
        export.write(book.drawing.with_metadata(**_said(book)), output)
    write_woven_model(weaves[-1], book, output)
    plan = book.plan
    if as_json:
        click.echo(json.dumps({"input": input_title(input_mesh), "levels": levels, "output": output,
                               "layout": layout, **report(book),
                               "rotation_order": plan.k, "copies": plan.k,
                               "module_strips": int(plan.copies.shape[1]),
                               "extra_strips": len(plan.extras),
                               "strands": int(weaves[-1].n_strands),
                               "model_mm": [round(float(v), 1)
                                            for v in finished_size(weaves[-1], book)],
                               **nonconvex, **extra},
                              indent=2, allow_nan=False))
    else:
        summary(f"{output}: {counted(len(book.drawing.sheets), 'page')} "
                f"({len(book.strip_pages)} of strips, {100 * book.ink:.0f} % ink); C{plan.k}, "
                f"{counted(plan.k, 'copy')} of a {plan.copies.shape[1]}-strip module"
                + (f" + {counted(len(plan.extras), 'extra')}" if len(plan.extras) else "")
                + (f"; {counted(len(book.strip_pages), 'cut file')} for {machine.title}, "
                   f"{extra['cutter']['cut_length_mm'] / 1000:.1f} m of cuts, smallest "
                   f"feature {extra['cutter']['min_feature_mm']:.1f} mm" if extra else ""))


def _beside(values: dict) -> list[Path]:
    """The existing files a run with ``values`` may replace besides a file -o: the cut files
    beside it (--cutter), the cut sheets and assembly in the -o folder (--laser-card);
    checked before any work (``outputs.may_replace``)."""
    output = Path(values["output"])
    if values.get("laser_card") not in (None, False, "false"):
        return sorted(output.glob("strands-*"))
    model = [model_path(output)] if values.get("preview") in (None, False, "false") else []
    if values.get("cutter_name") is None:
        return model
    from ..papermodel.printcut import existing_cut_files

    return existing_cut_files(output) + model


strands_command.beside = _beside

MODEL_THICKNESS = 0.5  # mm: the strips of the 3-D model (as weave --thickness)


def model_path(output) -> Path:
    """Where the woven 3-D model of the strips at ``output`` goes: OUTPUT-3d.glb beside it."""
    output = Path(output)
    return output.with_name(f"{output.stem}-3d.glb")


def write_woven_model(weave, book, output) -> None:
    """The woven model of ``book``'s strips, as glTF binary beside ``output``."""
    from ..export.gltf import glb_bytes
    from ..fileio import write_atomic
    from ..weave.woven import woven_mm

    model = woven_mm(weave, book.colours, book.scale, MODEL_THICKNESS)
    write_atomic(model_path(output), glb_bytes(model, name=Path(output).stem))


def kit_kind(mesh) -> str:
    """The kind of kit ``mesh`` makes (a key of ``KIT_REFUSES``): "surface" (in space: a
    woven ball) or "flat"."""
    return "surface" if mesh.dim == 3 else "flat"


def refuse_for_kit(kind: str, input_mesh: str) -> None:
    """BadParameter naming the options given away from their defaults that a kit of ``kind``
    ("surface": a ball; "flat") refuses, with why (``KIT_REFUSES``)."""
    ctx = click.get_current_context()
    meant, why = KIT_REFUSES[kind]
    given = [p for p in ctx.command.params if isinstance(p, click.Option)
             and option_key(p) in why and ctx.params[p.name] != p.get_default(ctx)]
    if given:
        names = " and ".join(f"--{option_key(p)}" for p in given)
        reasons = "".join(f"; {r}" for r in dict.fromkeys(why[option_key(p)] for p in given) if r)
        raise click.BadParameter(
            f"{f'{input_mesh} is flat; ' if kind == 'flat' else ''}{names} "
            f"{'is' if len(given) == 1 else 'are'} for {meant}{reasons}",
            param_hint=f"'--{option_key(given[0])}'")


BALL_TILE = 40.0  # mm across an octagon: a ball's default size


def ball(mesh, input_mesh, levels, page, tile_size, diameter, margin, pal, chirality, project,
         output, as_json, preview=False) -> None:
    """``strands`` of a surface in space: a woven ball's strips, ``diameter`` mm across (with
    ``preview``: the ball from the front and the back only)."""
    from ..papermodel.ball import ball_book, ball_preview
    from ..papermodel.checks import report
    from ..weave.snub_weave import snub_weaves

    hierarchy = subdivide(mesh, levels, chirality=chirality, project=project)
    weaves = snub_weaves(hierarchy)
    weave = weaves[-1]
    title = (f"weave-cut strands: {input_title(input_mesh)}, level {levels}"
             + (f", projected to the {project}" if project else ""))
    if preview:
        export.write(ball_preview(weaves, pal, f"{title}: preview")
                     .with_metadata(**provenance()), output)
        return summary(f"{output}: the ball from the front and the back, its "
                       f"{weave.n_strands} strands as the strips are coloured")
    book = ball_book(weaves, pal, page, diameter, margin, title=title,
                     tile_size=tile_size or BALL_TILE)
    for warning in book.warnings:
        click.echo(f"weave-cut: warning: {warning}", err=True)
    export.write(book.drawing.with_metadata(**_said(book)), output)
    write_woven_model(weave, book, output)
    if as_json:
        click.echo(json.dumps({"input": input_title(input_mesh),
                               "levels": levels, "project": project,
                               "output": output, **report(book), **book.flattening(),
                               "strands": int(weave.n_strands),
                               "strand_lengths_mm": np.round(weave.strand_lengths()
                                                             * book.scale, 1).tolist()},
                              indent=2, allow_nan=False))
    else:
        summary(f"{output}: {counted(len(book.drawing.sheets), 'page')} "
                f"({len(book.strip_pages)} of strips, {100 * book.ink:.0f} % ink); "
                f"{counted(weave.n_strands, 'strip')} in {counted(len(book.pieces), 'piece')}, "
                f"a ball {book.diameter / 10:.1f} cm across; "
                f"unfolded edges change by at most {100 * book.stretch:.2f} %, pentagons are at most "
                f"{100 * float(book.non_planarity.max()):.1f} % off their planes")


def _said(book) -> dict[str, str]:
    """A strand book's metadata: its provenance, and its colours in a maker's words (the kit
    page's card shows them, not every fill the pages hold)."""
    from ..papermodel.wording import colours_said

    return {**provenance(), "colours": colours_said(book.colours)}


def _print_and_cut(book, machine, output: str) -> dict:
    """Write the strip pages with the cutter's marks to ``output`` and a cut file per strip
    page beside it (SVG and DXF); return the --json figures."""
    from ..papermodel.printcut import (cut_file_paths, cut_files, cut_report, print_file_path,
                                       print_files, with_marks)

    marked = with_marks(book, machine)
    export.write(marked.drawing.with_metadata(**_said(book)), output)
    base = Path(output)
    files, report = [], cut_report([])
    for n, drawing in cut_files(marked):
        report = report + cut_report([p.cut for k, p in book.pieces if k == n])
        for path in cut_file_paths(base, n):
            export.write(drawing.with_metadata(**provenance()), path)
            files.append(str(path))
    prints = []  # the images a cutter's software prints with its own marks (Cricut)
    for n, drawing in print_files(marked) if machine.own_marks else ():
        export.write(drawing.with_metadata(**provenance()), print_file_path(base, n))
        prints.append(str(print_file_path(base, n)))
    if report.min_feature < machine.min_feature:
        click.echo(f"weave-cut: warning: features down to {report.min_feature:.2f} mm: a drag "
                   f"knife tears below {machine.min_feature:g} mm", err=True)
    return {"cutter": {"name": machine.name, "marks": machine.marks, "cut_files": files,
                       **({"print_images": prints} if prints else {}),
                       **report.as_dict()}}


def _laser_card(weaves, pal_name: str, material: str | None, laser_name: str, formats, page,
                margin, tile_size: float, turn: float, title: str, out_dir: str,
                as_json: bool) -> None:
    """Write the card sheets (an SVG and a DXF each, or ``formats``) and strands-assembly.pdf,
    the kit's own instructions, into ``out_dir``."""
    from ..fileio import make_folder
    from ..layout.lasersetup import kerf_note, laser, laser_job, material as card, output_formats
    from ..papermodel.cardkit import card_kit
    from ..papermodel.checks import report

    mat = card(material or "card-300gsm")
    try:
        kit = card_kit(weaves, pal_name, mat, laser(laser_name), page, margin, tile_size, turn,
                       title)
    except ValueError as exc:
        raise click.ClickException(str(exc)) from exc
    for warning in kit.warnings:
        click.echo(f"weave-cut: warning: {warning}", err=True)
    cut = kit.cut
    folder = make_folder(out_dir)
    export.write(kit.instructions.with_metadata(**provenance()), folder / "strands-assembly.pdf")
    files = []
    job = laser_job(mat, kerf_note(mat["kerf"], "the strips' outlines"))
    for drawing, name in zip(cut.sheets, kit.files):
        for fmt in output_formats(formats, laser_name):
            export.write(drawing.with_metadata(**provenance()), folder / f"{name}.{fmt}", job=job)
            files.append(str(folder / f"{name}.{fmt}"))
    n_colours = len(set(cut.colours))
    n_pieces = sum(len(p) for p in cut.pieces)
    minutes = cut.report.length / mat["cut_speed"] / 60  # cutting only, at the material's speed
    pages = len(kit.instructions.sheets)
    if as_json:
        click.echo(json.dumps({"output": out_dir, "material": mat["name"],
                               "sheet_mm": list(mat["sheet"]), "sheets": len(cut.sheets),
                               "card_colours": n_colours, "strips": n_pieces,
                               "sheet_fill": round(cut.fill, 3),
                               "fewer_colours": dict(kit.fewer),
                               "instruction_pages": pages,
                               "score_lines": sum(len(s) for s in cut.scores),
                               "engraved_dots": sum(len(d) for d in cut.dots),
                               **{k: v for k, v in report(kit.book).items() if k in (
                                   "smallest_text_mm", "smallest_contrast", "min_label_contrast",
                                   "min_label_gap_mm", "label_violations", "slimmest_piece_mm",
                                   "names_left_out")},
                               "warnings": list(kit.warnings),
                               "smallest_label_mm": round(cut.smallest_label, 2),
                               "cut_minutes": round(minutes, 1), "files": files,
                               **cut.report.as_dict()}, indent=2, allow_nan=False))
    else:
        fewer = kit.fewer and (f"; sheets {100 * cut.fill:.0f} % covered: --palette "
                               f"{kit.fewer[0][0]} needs {kit.fewer[0][1]} card colours")
        summary(f"{out_dir}: {counted(len(cut.sheets), 'sheet')} of {mat['name']} in "
                f"{counted(n_colours, 'card colour')}, {counted(n_pieces, 'strip piece')}, "
                f"{cut.report.length / 1000:.1f} m of "
                f"cuts (about {minutes:.0f} min), smallest feature "
                f"{cut.report.min_feature:.1f} mm{fewer or ''}; strands-assembly.pdf "
                f"({counted(pages, 'page')}): what to cut from which card, how to weave")
