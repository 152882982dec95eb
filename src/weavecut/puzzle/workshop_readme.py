"""README.txt of the puzzle's workshop folder: what goes to the laser (each file's layers in the
order they run, as the files hold them), what to print, the order of work, the run's warnings
and the summary's figures. It says only what the files allow: a layer a file lacks is not
named, the pieces are found by their numbers only when numbers are engraved, and a cut order
the .svg/.dxf cannot carry (their cut layers share one colour) is left to the .lbrn2 project or
to the laser program's own setting."""

from __future__ import annotations

import textwrap

from ..analysis.convexity import SEE
from ..presets import LASER_FORMATS
from ..text import counted

# the shared cut's layers as the README names them; a mode's "layers" in the summary says
# which of them its files hold (all of them when it does not say)
SHARED_LAYERS = ("engrave-numbers", "score-ring", "cut-1-inner", "cut-2-hole", "cut-3-outer")
SEPARATE_LAYERS = ("engrave-numbers", "cut-1-inner", "cut-2-outer")
SHARED_WORDS = {"engrave-numbers": "engrave-numbers (engrave, lowest power)",
                "score-ring": "score-ring (score: low power, fast)"}
SEPARATE_WORDS = {"engrave-numbers": "engrave-numbers (engrave)",
                  "cut-1-inner": "cut-1-inner (the pieces, then the frame's hole)",
                  "cut-2-outer": "cut-2-outer (cut)"}
# LightBurn's words (docs.lightburnsoftware.com, Optimization Settings): on by default
INNER_FIRST = ('in LightBurn keep "Optimize Cut Path" on, and "Cut inner shapes first" in its '
               "Optimization Settings (both on by default): it cuts a closed shape before the "
               "shape around it")


def frame_text(info: dict) -> str:
    """The frame's size as ``--size`` measured it: the pentagon's diagonal and its box, or,
    for any other shape (``--size`` is its width), its box alone."""
    (width, height) = info["frame_mm"]
    box = f"{width:g} x {height:g} mm"
    if info.get("frame_measure", "diagonal") == "diagonal":
        return f"{info['frame_diagonal_mm']:g} mm diagonal, {box}"
    return box


def readme(info: dict, page: str) -> str:
    """README.txt for the workshop folder: what goes to the laser, what to print, the order of
    work, the warnings a maker can act on (not the subdivision's non-convex faces: those stay
    in the terminal and the JSON) and the summary's figures."""
    modes = info["modes"]
    numbers = bool(info.get("numbers"))
    parts = info.get("frame_parts", 1)
    warnings = "".join(textwrap.fill(w, 92, initial_indent="  - ", subsequent_indent="    ",
                                     break_on_hyphens=False) + "\n"
                       for w in info.get("warnings", []) if not w.endswith(SEE)) or "  none\n"
    across = info["piece_across_mm"]
    intro = textwrap.fill(
        "The paper's two-sided puzzle (Lipschuetz, Reitebuch, Skrodzki, Polthier, section 6): "
        f"level {info['levels']} pieces of the pentagon snub subdivision; the front is painted "
        f"with the level {info['levels'] - 1} weave, the back with the level {info['levels']} "
        "weave.", 92)
    engraved = (textwrap.fill(
        "The piece numbers are engraved on the front (the face the front guide shows), where "
        "the paint covers them; the back has none: there the back guide shows which piece "
        "is where.", 92,
        initial_indent="  ", subsequent_indent="  ") + "\n") if numbers else ""
    files = info.get("files", [])
    return f"""weave-cut jigsaw puzzle: workshop folder
==========================================

{intro}

Material: {info.get('material', '?')}, kerf {info.get('kerf_mm', 0):g} mm.
Frame: {frame_text(info)}.
Pieces: {info['pieces']}, {across[0]:g}-{across[1]:g} mm across.
Paints: {info.get('front_colours', '?')} on the front, {info.get('back_colours', '?')} on the \
back (the same paints).
{_modes_text(info)}
1. To the laser
{chr(10).join(_laser(info))}
  Test first: cut a 20 mm square, measure it; kerf = 20 mm - its size. Rerun with
  --kerf if it differs from {info.get('kerf_mm', 0):g} mm.
{engraved}
2. To the printer (at 100 %, no scaling; check the 100 mm bar)
  puzzle-front-guide-{page}.pdf - colour key, then the front guide tiled on pages.
  puzzle-back-guide-{page}.pdf  - the same for the back (mirrored, as the flipped board).
  puzzle-front-guide.svg, puzzle-back-guide.svg - the same guides in one piece at 1:1.
  The colour key lists every paint: swatch, name, hex code, the pieces that carry it and the
  area it covers, so you know how much to buy.

3. Order of work
{_cut_step(modes, parts, numbers)}
  b. Sand the burr off lightly; prime both sides if the wood is porous.
  c. Paint the front from the front guide: bold lines are piece outlines, thin dashed
     lines split two-coloured pieces along the parent edge (the paper's diagonal) and
     split a ring piece's hexagon (white: bare wood, left unpainted) off its paint. Numbers
     tell you which piece is which; a number that reads as another one upside down (6, 9,
     16, 91, 86, 98, ...) is underlined, on the guides{' and on the wood' if numbers else ''}: \
the line goes
     under it. Single-coloured pieces sit at the centres of the large octagons of the
     coarser weave.
  d. Let it dry, turn the whole puzzle over in its frame, paint the back from the back guide.
  e. Seal. Paint swells the wood a little and closes the cutting gaps.

Warnings:
{warnings}
Files:
{''.join(f'  {name}{chr(10)}' for name in files)}"""


def _laser(info: dict) -> list[str]:
    """Section 1's paragraphs: each laser file with its layers in order, the LightBurn
    projects, how the .svg/.dxf keep the cut order, the frame's parts."""
    modes, files = info["modes"], info.get("files", [])
    out = []
    if "shared" in modes:
        layers = modes["shared"].get("layers", SHARED_LAYERS)
        words = [SHARED_WORDS[name] for name in SHARED_LAYERS[:2] if name in layers]
        cuts = [name for name in SHARED_LAYERS[2:] if name in layers]
        words.append(", ".join(cuts) + " (cut: full power)")
        out.append(_indented(f"puzzle-shared-cut{_suffixes(files, 'puzzle-shared-cut')} - "
                             "everything from one board, every shared edge cut once. Layers "
                             f"in order: {', '.join(words)}. Keep the order: the outline last, "
                             "so nothing shifts before its inner cuts are done.", "  "))
    if "separate" in modes:
        n = modes["separate"]["sheets"]
        layers = modes["separate"].get("layers", SEPARATE_LAYERS)
        words = [SEPARATE_WORDS[name] for name in SEPARATE_LAYERS if name in layers]
        out.append(_indented(f"puzzle-separate-sheet-1{f'..{n}' if n > 1 else ''}"
                             f"{_suffixes(files, 'puzzle-separate-sheet-1')} - pieces and "
                             f"frame nested on {counted(n, 'sheet')} (pieces in the frame's "
                             "hole too), each outline offset by half the kerf so the pieces "
                             f"fit snugly. Layers in order: {', '.join(words)}.", "  "))
    projects = [name for name in files if name.endswith(".lbrn2")]
    if projects:
        out.append("  The .lbrn2 files are LightBurn projects (File > Open) with these layers, "
                   "in this order,\n    each with the material's speed, power and passes; "
                   "a project's note says how it\n    was made. Test the settings on a "
                   "scrap first.")
    if not files or any(name.endswith((".svg", ".dxf")) and name.startswith("puzzle-s")
                        for name in files):
        order = (f"In the .svg and .dxf files every cut layer has the same colour, so a laser "
                 f"program that takes its layers from the colours (LightBurn) imports them "
                 f"as one layer and orders them itself: {INNER_FIRST}.")
        if "shared" in modes:
            order += (" The shared cut's cut-1-inner lines are open, not shapes, so it may cut "
                      "them after cut-2-hole: "
                      + ("open puzzle-shared-cut.lbrn2 instead, which keeps the order."
                         if "puzzle-shared-cut.lbrn2" in projects else
                         "write its LightBurn project (--formats svg,dxf,lbrn2), which keeps "
                         "the order."))
        out.append(_indented(order, "  "))
    parts = info.get("frame_parts", 1)
    if parts > 1:
        ring = "F1 and F2 join at both ends" if parts == 2 else ", ".join(
            f"F{k} joins F{k % parts + 1}" for k in range(1, parts + 1))
        names = ", ".join(f"F{k}" for k in range(1, parts + 1))
        out.append(_indented(f"The frame comes in {parts} parts ({names} engraved, "
                             f"counter-clockwise), joined by dovetails: {ring}. Glue them on a "
                             "flat surface.", "  "))
    return out


def _cut_step(modes: dict, parts: int, numbers: bool) -> str:
    """Step a. of the order of work: what each cut's files allow (the operations its layers
    hold; the pieces found by their engraved numbers, or by their shapes when none are)."""
    cuts = []
    if "shared" in modes:
        cuts.append(f"the shared cut: {_operations(modes['shared'], SHARED_LAYERS)} (outlines "
                    "last); the pieces stay in the frame.")
    if "separate" in modes:
        found = ("by their numbers, as the front guide shows them." if numbers else
                 "by their shapes, as the front guide shows them (no numbers are engraved: "
                 "--numbers engraves them).")
        cuts.append(f"the separate sheets: {_operations(modes['separate'], SEPARATE_LAYERS)} "
                    "(outlines last)"
                    + (f"; glue the frame's {parts} parts on a flat surface and let them dry"
                       if parts > 1 else "")
                    + f"; lay the pieces into the frame {found}")
    return textwrap.fill(("Cut " if len(cuts) == 1 else "Cut either ") + " Or ".join(cuts), 89,
                         initial_indent="  a. ", subsequent_indent="     ")


def _operations(mode: dict, every: tuple[str, ...]) -> str:
    """'engrave, score, then cut': the operations of a mode's layers, in the order they run."""
    layers = mode.get("layers", every)
    done = [word for name, word in (("engrave-numbers", "engrave"), ("score-ring", "score"))
            if name in layers]
    return ", ".join(done) + ", then cut" if done else "cut"


def _indented(text: str, first: str = "    ") -> str:
    """``text`` filled to 92 columns, its first line indented ``first``, the rest 4."""
    return textwrap.fill(text, 92, initial_indent=first, subsequent_indent="    ",
                         break_on_hyphens=False)


def _suffixes(files: list[str], stem: str) -> str:
    """'.svg / .dxf' and so on: the laser formats written of ``stem`` (svg and dxf when the
    file list is not given)."""
    written = [f for f in LASER_FORMATS if f"{stem}.{f}" in files] or ["svg", "dxf"]
    return "." + " / .".join(written)


def _modes_text(info: dict) -> str:
    lines = []
    for mode, m in info["modes"].items():
        lines.append(f"{mode.capitalize()} cut: {counted(m['sheets'], 'sheet')}, "
                     f"{m['cut_length_m']:.1f} m of cutting, about {m['time_min']:g} min at "
                     f"{info['speed_mm_s']:g} mm/s.")
    return "\n".join(lines) + "\n"
