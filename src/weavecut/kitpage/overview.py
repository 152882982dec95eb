"""A kit in one card, for the page of all builds (``make run``'s ``build/index.html``): what
kind of thing it makes, its first picture and its figures (pages, cut sheets, cut length, laser
time, size). Every kit page carries them as a JSON data block (no script runs); the index of
builds reads them back from the pages it links."""

from __future__ import annotations

import json
import re
from pathlib import Path
from urllib.parse import unquote

from ..layout.drawing import Drawing

BLOCK = re.compile(r'<script type="application/json" id="weave-cut-kit">(.*?)</script>', re.S)
FIRST_IMAGE = re.compile(r'<img src="([^"]+)" alt="([^"]*)"')
COMMANDS = {"puzzle": "two-sided jigsaw puzzle to laser-cut", "figure": "figures of the paper",
            "weave": "weaving patterns", "subdivide": "subdivided meshes"}
MAX_PAGE = 64 * 2**20  # bytes of a kit page read for its card (pages embed their pictures)


def block(runs, body: str, cut_length) -> str:
    """The data block of a kit page made of ``runs`` whose HTML body is ``body``;
    ``cut_length(shape)`` measures a cut in mm."""
    images = FIRST_IMAGE.findall(body)
    front = [src for src, alt in images if "front-guide" in alt]  # a puzzle: its painted face
    data = {"items": items(runs, cut_length),
            "picture": (front or [src for src, _ in images] or [""])[0]}
    text = json.dumps(data, sort_keys=True, ensure_ascii=False, allow_nan=False).replace(
        "<", "\\u003c")
    return f'<script type="application/json" id="weave-cut-kit">{text}</script>'


def read(page: Path) -> dict:
    """The card data of a kit page ({} when it has none or cannot be read); a relative picture
    is made relative to the page's folder."""
    try:
        if page.stat().st_size > MAX_PAGE:
            return {}
        found = BLOCK.search(page.read_text(encoding="utf-8", errors="replace"))
        data = json.loads(found.group(1)) if found else {}
    except (OSError, ValueError):
        return {}
    if not isinstance(data, dict):
        return {}
    picture = data.get("picture")
    if isinstance(picture, str) and picture and not picture.startswith("data:"):
        data["picture"] = (page.parent / unquote(picture)).as_posix()
    return data


def kind(run) -> str:
    """What one command makes, in a few words."""
    words, name = run.command.split(), run.name
    if name == "strands":
        return ("strips cut from card by a laser" if "--laser-card" in words else
                "paper model for a desktop cutter" if "--cutter" in words else
                "woven paper ball" if "--project" in words else "woven paper model")
    if name == "weave" and "--project" in words:
        return "views and 3-D model of the woven solid"
    return COMMANDS.get(name, "")


def items(runs, cut_length) -> list[dict]:
    """Per kind of product (in the order first made): the figures a maker plans with —
    printed pages, cut sheets and their length (the puzzle's two ways of cutting each on its
    own, with its laser time), the finished size."""
    totals: dict[str, dict] = {}
    for run in runs:
        t = totals.setdefault(kind(run), {"pages": 0, "sheets": 0, "cut": 0.0, "more": []})
        figures = run_figures(run)
        modes = {m: f for m, f in sorted((figures.get("modes") or {}).items())
                 if isinstance(f, dict)}
        for mode, f in modes.items():
            n = f.get("sheets", 0)
            t["more"].append(f"{mode} cut: {f.get('cut_length_m', 0):.1f} m on {n} "
                             f"sheet{'s' * (n != 1)}, about {f.get('time_min', 0):.0f} min")
        frame = figures.get("frame_mm")
        if isinstance(frame, list) and len(frame) == 2:
            t["more"].append(f"{frame[0]:.0f} × {frame[1]:.0f} mm finished")
        stems: set[Path] = set()
        for path, drawing in run.files.items():
            if not isinstance(drawing, Drawing):
                continue
            if path.suffix.lower() == ".pdf":
                t["pages"] += len(drawing.sheets)
            elif _cut_file(drawing) and path.with_suffix("") not in stems:  # x.svg, x.dxf: once
                stems.add(path.with_suffix(""))
                t["sheets"] += len(drawing.sheets)
                t["cut"] += sum(cut_length(s) for sheet in drawing.sheets
                                for layer in sheet.layers if layer.role == "cut"
                                for s in layer.shapes)
    return [{"kind": k, "facts": _facts(t)} for k, t in totals.items()]


def _cut_file(drawing: Drawing) -> bool:
    """A sheet for a cutting machine: card for a laser or a printed page for a cutter."""
    meta = dict(drawing.metadata)
    return "card" in meta or "printed_page" in meta


def _facts(t: dict) -> list[str]:
    p, n = t["pages"], t["sheets"]
    return ([f"{p} printed page{'s' * (p != 1)}"] if p else []) + (
        [f"{n} cut sheet{'s' * (n != 1)}, {t['cut'] / 1000:.1f} m of cuts"] if n else []
    ) + t["more"]


def run_figures(run) -> dict:
    """The figures a command wrote as JSON (the puzzle's laser, speed, modes), merged."""
    figures = {}
    for path in run.files:
        if path.suffix.lower() == ".json" and path.is_file() and path.stat().st_size < 2**20:
            try:
                doc = json.loads(path.read_bytes())
            except ValueError:
                continue
            figures.update(doc if isinstance(doc, dict) else {})
    return figures
