"""The kit page: one self-contained HTML5 file showing what a build or a command wrote.

For every output a picture first, then its name, what it is for ("print at 100 % on A4",
"cut: ..."), its size in mm, page count and figures; for every command its command line and
summary. No network, no script but the 3-D viewer of a ``.glb`` (:mod:`.viewer`, inlined): generated pictures are ``data:`` URIs, the outputs are
linked by relative paths, the style sheet is inline (screen, phones down to 390 px, and print).
A JSON data block (:mod:`.overview`) gives the index of builds the kit's card.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from html import escape
from pathlib import Path
from urllib.parse import quote

import numpy as np

from .. import __version__, presets
from ..layout.drawing import Drawing, Polygons, Polylines
from ..layout.lasersetup import ROLES
from ..text import clean
from ..units import PAPER_SIZES
from . import overview, previews, viewer

# colours of the page: (text, background) pairs the tests hold to WCAG contrast >= 4.5
INK, MUTED, LINK, PAPER, CARD = "#1a1a1a", "#52575c", "#0b57a4", "#ffffff", "#f3f4f5"
PAIRS = [(INK, PAPER), (INK, CARD), (MUTED, PAPER), (MUTED, CARD), (LINK, PAPER), (LINK, CARD)]

STYLE = f"""
*{{box-sizing:border-box}}
body{{margin:0 auto;max-width:80rem;padding:1rem;font:16px/1.45 system-ui,sans-serif;
color:{INK};background:{PAPER}}}
h1{{font-size:1.5rem;margin:0 0 .25rem}}
h2{{font-size:1.2rem;margin:1.5rem 0 .25rem;overflow-wrap:anywhere}}
h3{{font-size:1rem;margin:.5rem 0 .25rem;overflow-wrap:anywhere}}
p,ul{{margin:.25rem 0}}
a{{color:{LINK}}}
code{{font-size:.85rem;overflow-wrap:anywhere;color:{MUTED}}}
.said{{padding-left:1.2rem}}
main{{display:grid;gap:0 1rem;grid-template-columns:repeat(auto-fill,minmax(min(100%,20rem),1fr))}}
section.many{{grid-column:1/-1}}
.cards{{display:grid;gap:1rem;grid-template-columns:repeat(auto-fill,minmax(min(100%,18rem),1fr));
padding:0;list-style:none}}
.card{{background:{CARD};border-radius:.5rem;padding:.75rem;break-inside:avoid}}
.card.wide{{grid-column:1/-1}}
.card img{{display:block;max-width:100%;max-height:24rem;height:auto;margin:0 auto;
background:{PAPER};border:1px solid #d0d3d6}}
.pages{{display:flex;flex-wrap:wrap;gap:.4rem}}
.pages img{{width:6.5rem;margin:0}}
.for{{font-weight:600}}
.facts{{color:{MUTED};font-size:.9rem}}
figure.model3d{{margin:0}}
figure.model3d canvas{{display:block;width:100%;max-width:48rem;aspect-ratio:4/3;margin:0 auto;
background:{PAPER};border:1px solid #d0d3d6;touch-action:none;cursor:grab}}
figure.model3d figcaption{{color:{MUTED};font-size:.9rem}}
figure.model3d script{{display:none}}
@media print{{body{{max-width:none;padding:0;font-size:11pt}}main{{display:block}}
.cards{{grid-template-columns:repeat(2,1fr)}}.card{{background:none;border:1px solid #999}}
a{{color:{INK};text-decoration:none}}}}
""".replace("\n", "")

DXF_FOR = "CAD file in mm (LibreCAD, LightBurn)"
COLOUR_WORDS = {"#ff0000": "red", "#0000ff": "blue", "#000000": "black"}  # the laser presets'
HAIRLINE = 0.011  # mm: laser presets draw cuts 0.01 mm wide (or 0), for a laser, not an eye


@dataclass(frozen=True)
class Run:
    """One command and what it wrote: ``files`` maps each path to the Drawing it shows (None
    for other files), in the order written; ``said`` is the summary the command printed;
    ``name`` the command's name (``strands``, ``puzzle``, ...)."""

    command: str
    files: dict
    said: tuple[str, ...] = ()
    name: str = ""

    @classmethod
    def of(cls, record, command: str, name: str = "") -> Run:
        """A Run from a ``fileio.Record``."""
        return cls(command, dict(record.files), tuple(record.said), name)


def page(title: str, runs: list[Run], folder: Path) -> str:
    """The kit page of ``runs`` as HTML, linking outputs relative to ``folder`` (where the page
    is written). Same runs and files, same text."""
    n = sum(len(r.files) for r in runs)
    body = "".join(_run(k, r, Path(os.path.abspath(folder))) for k, r in enumerate(runs, 1))
    return _document(title, f"{n} file{'s' * (n != 1)} from {len(runs)} "
                     f"command{'s' * (len(runs) != 1)}, made by weave-cut {__version__}.",
                     body + viewer.scripts(body), overview.block(runs, body, _length))


def index(title: str, pages: list[Path], folder: Path) -> str:
    """A page of cards linking other kit pages (``make run``'s ``build/index.html``): each
    build's picture, what it makes and its figures, as its page's data block says."""
    cards = "".join(_build_card(p, overview.read(p), folder) for p in pages)
    return _document(title, f"{len(pages)} builds, one page each: open one to see its files.",
                     f'<section class="many" aria-labelledby="builds"><h2 id="builds">Builds'
                     f'</h2><ul class="cards">{cards}</ul></section>')


def _build_card(page: Path, data: dict, folder: Path) -> str:
    link = _href(page, folder)
    name = page.parent.name
    picture = data.get("picture") if isinstance(data.get("picture"), str) else ""
    if picture and not picture.startswith("data:"):
        picture = _href(Path(picture), folder)
    img = f'<a href="{link}">{_img(picture, f"{name}: its first picture")}</a>' if picture else ""
    items = [i for i in data.get("items", []) if isinstance(i, dict)]
    what = "".join(f'<p class="for">{_e(i.get("kind", ""))}</p>'
                   f'<p class="facts">{_e(" · ".join(map(str, i.get("facts", []))))}</p>'
                   for i in items)
    return f'<li class="card">{img}<h3><a href="{link}">{_e(name)}</a></h3>{what}</li>'



def _document(title: str, lead: str, body: str, data: str = "") -> str:
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width,initial-scale=1\">"
            f"<title>{_e(title)}</title><style>{STYLE}</style>{data}</head>\n<body><header>"
            f"<h1>{_e(title)}</h1><p>{_e(lead)}</p></header>\n<main>{body}</main></body></html>\n")


def _run(k: int, run: Run, folder: Path) -> str:
    figures = overview.run_figures(run)
    said = [_unprefixed(line, run.files) for text in run.said for line in text.splitlines()
            if line.strip() and not line.startswith("files: ")]  # the cards list the files
    groups: dict[Path, list[Path]] = {}
    for path in run.files:  # one card per file name stem: x.svg and x.dxf of one Drawing
        groups.setdefault(path.with_suffix(""), []).append(path)
    cards = [_card(paths, run.files, figures, folder) for paths in groups.values()]
    words = run.command.split()  # "weave-cut COMMAND INPUT ...": the command and the input
    heading = " ".join(Path(w).name for w in words[1:3] if not w.startswith("-")) or run.command
    said_html = (f'<ul class="said">{"".join(f"<li>{_e(s)}</li>" for s in said)}</ul>'
                 if said else "")
    many = ' class="many"' if len(cards) > 1 or any(wide for _, wide in cards) else ""
    return (f'<section{many} aria-labelledby="run-{k}"><h2 id="run-{k}">{_e(heading)}</h2>'
            f"<p><code>{_e(run.command)}</code></p>{said_html}"
            f'<ul class="cards">{"".join(html for html, _ in cards)}</ul></section>\n')


def _unprefixed(line: str, files: dict) -> str:
    """A summary line without its leading "OUTPUT: " (the cards show the file, or the files
    of an output folder such as the laser card's)."""
    head, sep, rest = line.partition(": ")
    if not sep:
        return line
    output = Path(os.path.abspath(head))
    return rest if output in files or any(output in f.parents for f in files) else line


def _card(paths: list[Path], files: dict, figures: dict, folder: Path) -> tuple[str, bool]:
    """A card of the files of one stem, and whether it is wide (a PDF of many pages)."""
    suffixes = [p.suffix.lower() for p in paths]
    pdf = [files[p] for p in paths if p.suffix.lower() == ".pdf"]
    drawing = next((d for d in pdf + [files[p] for p in paths] if d is not None), None)
    name = paths[0].with_suffix("").name
    picture, pages = _picture(paths, files, folder)
    made = ".pdf" in suffixes or "laser" in figures or bool(_cut_for(drawing))  # to be cut out
    facts = [*_sizes(drawing, pages), *_drawing_figures(drawing, made), _bytes(paths)]
    links = " · ".join(f'<a href="{_href(p, folder)}">{_e(p.suffix.lstrip(".").upper() or p.name)}'
                       "</a>" for p in paths)
    wide = pages > 4 or ".glb" in suffixes  # many pages, or a 3-D model to turn
    return (f'<li class="card{" wide" * wide}">{picture}<h3>{_e(name)}</h3>'
            f'<p class="for">{_e(_purpose(suffixes, drawing, figures))}</p>'
            f'<p class="facts">{_e(" · ".join(f for f in facts if f))}</p><p>{links}</p></li>',
            wide)


def _picture(paths: list[Path], files: dict, folder: Path) -> tuple[str, int]:
    """The card's picture and the page count of its PDF (0 without one)."""
    by = {p.suffix.lower(): p for p in paths}
    model = viewer.figure(by[".glb"], _href(by[".glb"], folder)) if ".glb" in by else ""
    if model:
        return model, 0
    if ".pdf" in by:
        pdf = by[".pdf"]
        thumbs, _ = previews.pdf_thumbnails(pdf, files[pdf])
        imgs = "".join(_img(previews.data_uri(t, "image/png"),
                            f"page {n} of {len(thumbs)} of {pdf.name}", previews.png_size(t))
                       for n, t in enumerate(thumbs, 1))
        return f'<a class="pages" href="{_href(pdf, folder)}">{imgs}</a>', len(thumbs)
    drawing = next((files[p] for p in paths if files[p] is not None), None)
    cut = _cut_png(drawing, files)
    if cut is not None:  # a cut file, shown as the cut comes out
        shown = by.get(".svg") or by.get(".dxf") or paths[0]
        img = _img(previews.data_uri(cut, "image/png"), f"{shown.name}: {_cut_for(drawing)}",
                   previews.png_size(cut))
        return f'<a href="{_href(shown, folder)}">{img}</a>', 0
    for suffix in (".png", ".svg"):  # the file itself, unless its lines are too thin to see
        path = by.get(suffix)
        if path is not None and (suffix == ".png" or not _hairlines(files[path])):
            return (f'<a href="{_href(path, folder)}">'
                    f"{_img(_href(path, folder), _alt(path, files[path]))}</a>", 0)
    if drawing is None:
        return "", 0
    shown = by.get(".svg") or by.get(".dxf") or paths[0]
    preview = previews.data_uri(previews.svg_preview(drawing), "image/svg+xml")
    return f'<a href="{_href(shown, folder)}">{_img(preview, _alt(shown, drawing))}</a>', 0


def _cut_for(drawing: Drawing | None) -> str:
    """What a cut file cuts, from its metadata: "page N as printed" (print and cut) or "card
    #rrggbb" (a laser sheet of coloured card); "" for any other drawing."""
    meta = dict(drawing.metadata) if drawing is not None and len(drawing.sheets) == 1 else {}
    if re.fullmatch(r"#[0-9a-fA-F]{6}", str(meta.get("card", ""))):
        return f"card {meta['card']}"
    if str(meta.get("printed_page", "")).isdigit():
        return f"page {int(meta['printed_page'])} as printed"
    return ""


def _cut_png(drawing: Drawing | None, files: dict) -> bytes | None:
    """A cut file's picture: its cuts over the printed page it belongs to (the page of that
    number and size in a PDF the same command wrote), or its lines on its card's colour."""
    what = _cut_for(drawing)
    if what.startswith("card"):
        return previews.card_png(drawing.sheets[0], what.removeprefix("card "))
    if not what:
        return None
    n, cut = int(dict(drawing.metadata)["printed_page"]), drawing.sheets[0]
    for path, pdf in files.items():
        if path.suffix.lower() == ".pdf" and pdf is not None and n <= len(pdf.sheets):
            page = pdf.sheets[n - 1]
            if np.allclose((page.width, page.height), (cut.width, cut.height)):
                return previews.overlay_png(page, cut)
    return None


def _alt(path: Path, drawing: Drawing | None) -> str:
    return f"{path.name}: {_title(drawing)}" if _title(drawing) else path.name


def _title(drawing: Drawing | None) -> str:
    """The drawing's title without "weave-cut " and without the folders of input paths."""
    if drawing is None:
        return ""
    return re.sub(r"(?<!\S)/\S*/", "", drawing.title.removeprefix("weave-cut ")).strip()


def _img(src: str, alt: str, size: tuple[int, int] | None = None) -> str:
    wh = f' width="{size[0]}" height="{size[1]}"' if size else ""
    return f'<img src="{src}" alt="{_e(alt)}"{wh}>'


def _hairlines(drawing: Drawing | None) -> bool:
    """Whether ``drawing`` has laser hairlines (too thin to see when it is shown small)."""
    if drawing is None:
        return False
    return any(s.style.stroke and s.style.stroke_width < HAIRLINE for sheet in drawing.sheets
               for layer in sheet.layers for s in layer.shapes
               if isinstance(s, (Polygons, Polylines)))


def _sizes(drawing: Drawing | None, pages: int) -> list[str]:
    if drawing is None:
        return []
    sizes = sorted({(round(s.width), round(s.height)) for s in drawing.sheets})
    n = len(drawing.sheets)
    what = "pages" if pages else "sheets"
    text = " or ".join(f"{w} × {h} mm" for w, h in sizes)
    return [f"{n} {what} of {text}" if n > 1 else text]


def _drawing_figures(drawing: Drawing | None, made: bool) -> list[str]:
    """Cut length (if ``made``: printed or lasered to be cut out) and number of fill colours
    of ``drawing`` (when it has them)."""
    if drawing is None:
        return []
    shapes = [(layer.role, s) for sheet in drawing.sheets for layer in sheet.layers
              for s in layer.shapes if layer.visible]
    cut = sum(_length(s) for role, s in shapes if role == "cut") if made else 0.0
    fills = {f for _, s in shapes if isinstance(s, Polygons)
             for f in (s.fills or (s.style.fill,)) if f}
    meta = dict(drawing.metadata)
    paints = meta.get("paints")  # a painting guide: its paints, not the bare wood or paper it
    # leaves white; a strand book: its strand colours ("6 strand colours, each with a light
    # tint"), not every fill its pages hold (the tints, the glue bands' grey)
    count = [f"{paints} paints"] if paints else [meta["colours"]] if "colours" in meta else (
        [f"{len(fills)} colours"] if len(fills) > 1 else [])
    return ([f"cut {cut / 1000:.2f} m"] if cut else []) + count


def _length(shape) -> float:
    """Stroked length in mm of a Polylines (open) or Polygons (closed rings)."""
    if isinstance(shape, Polylines):
        offsets, closed = np.asarray(shape.offsets), False
    elif isinstance(shape, Polygons):
        offsets, closed = np.asarray(shape.ring_offsets), True
    else:
        return 0.0
    c = shape.coords
    starts, ends = offsets[:-1], offsets[1:]
    step = np.hypot(*np.diff(c, axis=0).T)
    step[ends[:-1][(ends[:-1] > 0) & (ends[:-1] <= len(step))] - 1] = 0.0  # into the next line
    total = float(step.sum())
    if closed:
        full = ends > starts
        total += float(np.hypot(*(c[ends[full] - 1] - c[starts[full]]).T).sum())
    return total


def _bytes(paths: list[Path]) -> str:
    size = sum(p.stat().st_size for p in paths if p.is_file())
    return f"{size / 1e6:.1f} MB" if size >= 1e6 else f"{max(1, round(size / 1e3))} kB"


def _which(suffixes: list[str]) -> str:
    """' (SVG or DXF)', ' (SVG, DXF or LightBurn)': the laser files of a card, when several."""
    names = [name for suffix, name in ((".svg", "SVG"), (".dxf", "DXF"), (".lbrn2", "LightBurn"))
             if suffix in suffixes]
    if len(names) < 2:
        return ""
    return f" ({', '.join(names[:-1])} or {names[-1]})"


def _purpose(suffixes: list[str], drawing: Drawing | None, figures: dict) -> str:
    """What a card's files are for, in a few words."""
    if ".pdf" in suffixes:
        sheets = drawing.sheets if drawing is not None else ()
        size = {tuple(sorted((round(s.width, 1), round(s.height, 1)))) for s in sheets}
        names = [n for n, wh in PAPER_SIZES.items() if tuple(sorted(wh)) in size]
        paper = names[0].upper() if len(size) == 1 and names else "its page size"
        if names and names[0] == "letter":
            paper = "US Letter"
        return f"print at 100 % on {paper}"
    roles = {layer.role for sheet in (drawing.sheets if drawing else ()) for layer in sheet.layers}
    printed = dict(drawing.metadata).get("print_image") if drawing is not None else None
    if printed:  # a Cricut kit's (``printcut.print_files``)
        return (f"page {printed}'s strips for Cricut Design Space: upload, Flatten, Make it (it "
                "prints them with its sensor marks and cuts round them)")
    laser, speed = figures.get("laser"), figures.get("speed_mm_s")
    what = _cut_for(drawing)
    if what.startswith("card"):
        return f"laser-cut from {what}{_which(suffixes)}"
    if what:
        return f"the desktop cutter cuts this on {what} (SVG or DXF)"
    if "cut" in roles and isinstance(laser, str):  # a laser file of the puzzle
        return (f"{_laser_description(laser).split(':')[0]}: "
                f"{_layer_settings(drawing, figures.get('operations'), speed)}"
                f"{_which(suffixes)}")
    if ".dxf" in suffixes:
        return DXF_FOR
    if ".json" in suffixes:
        return "figures for scripts (JSON)"
    if ".glb" in suffixes:
        return "the finished model in 3-D (glTF, in metres): turn it here, or open it in Blender"
    if ".obj" in suffixes:
        return "the woven model in 3-D (OBJ, in mm, strands coloured): open it in Blender"
    what = f"{_title(drawing)}: " if _title(drawing) else ""
    if ".png" in suffixes:
        return f"{what}picture for a screen"
    if ".svg" in suffixes:
        return f"{what}1:1 in mm, to view, print or edit"
    return "text"


def _layer_settings(drawing: Drawing, operations, cut_speed) -> str:
    """'engrave black at 150 mm/s, 15 %; cut red at 20 mm/s, 100 %': each laser operation the
    file holds (a layer with shapes), in the order they run, in its colour and with its own
    settings (``operations``: the summary's, by role; without them the cut's ``cut_speed``)."""
    colours = {}
    for sheet in drawing.sheets:
        for layer in sheet.layers:
            if layer.role in ROLES and layer.shapes:
                colours.setdefault(layer.role, layer.shapes[0].style.stroke)
    out = []
    for role in sorted(colours, key=ROLES.index):
        op = operations.get(role) if isinstance(operations, dict) else None
        colour = COLOUR_WORDS.get(str(colours[role]).lower(), colours[role])
        if isinstance(op, dict):
            passes = op.get("passes", 1)
            out.append(f"{role} {colour} at {op.get('speed_mm_s'):g} mm/s, "
                       f"{op.get('power_pct'):g} %" + (f", {passes} passes" if passes != 1
                                                      else ""))
        elif role == "cut" and isinstance(cut_speed, (int, float)):
            out.append(f"{role} {colour} at {cut_speed:g} mm/s")
        else:
            out.append(f"{role} {colour}")
    return "; ".join(out)


def _laser_description(name: str) -> str:
    try:
        return str(presets.load("laser", name).get("description", name))
    except presets.PresetError:
        return name


def _href(path: Path, folder: Path) -> str:
    return quote(Path(os.path.relpath(path, folder)).as_posix())


def _e(text: str) -> str:
    return escape(clean(str(text)))
