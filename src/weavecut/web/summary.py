"""The figures a kit's summary (what the CLI prints with --json) shows on the page: pages,
strands, strip width, pieces, cutting length and time, sheets, warnings, as label/text rows."""

from __future__ import annotations


def _n(x, unit: str = "", digits: int = 1) -> str:
    if isinstance(x, float):
        text = f"{x:,.{digits}f}".rstrip("0").rstrip(".") if digits else f"{x:,.0f}"
    else:
        text = f"{x:,}"
    return f"{text} {unit}".strip()


def _cut(mode: dict) -> str:
    sheets = mode.get("sheets")
    return (f"{_n(mode['cut_length_m'], 'm')} of cuts"
            + (f" on {sheets} sheet{'s' * (sheets != 1)}" if sheets else "")
            + (f", about {_n(mode['time_min'], 'min', 0)}" if "time_min" in mode else ""))


ROWS = [  # (key, label, text of the value); a row shows when its key is in the summary
    ("pages", "Pages", lambda v: f"{v['total']} ({v['strip']} of strips)"
     if isinstance(v, dict) else _n(v)),
    ("strands", "Strands", _n),
    ("module_strips", "Module", None),
    ("strip_width_mm", "Strip width", lambda v: _n(v, "mm")),
    ("tile_size_mm", "Octagons across", lambda v: _n(v, "mm")),
    ("ink_fraction", "Ink", lambda v: _n(100 * v, "%", 0)),
    ("chosen", "Chosen for the drawing", lambda v: f"{_n(v['cell_mm'], 'mm')} cells, "
     f"level {v['levels']}"),
    ("pieces", "Pieces", _n),
    ("piece_across_mm", "Pieces across", lambda v: f"{_n(v[0])}–{_n(v[1], 'mm')}"),
    ("frame_mm", "Frame", lambda v: f"{_n(v[0], '', 0)} × {_n(v[1], 'mm', 0)}"),
    ("sheets", "Sheets", _n),
    ("card_colours", "Card colours", _n),
    ("strips", "Strip pieces", _n),
    ("cut_minutes", "Cutting time", lambda v: f"about {_n(v, 'min', 0)}"),
    ("length_m", "Cutting length", lambda v: _n(v, "m")),
    ("material", "Material", str),
    ("kerf_mm", "Kerf", lambda v: _n(v, "mm", 2)),
    ("smallest_label_mm", "Smallest label", lambda v: _n(v, "mm")),
]


def figures(summary: dict) -> list[tuple[str, str]]:
    """Label/text rows of ``summary``, in a fixed order; keys it does not know are left out."""
    rows = []
    for k, label, text in ROWS:
        if k not in summary:
            continue
        if k == "module_strips":
            rows.append((label, f"{summary.get('copies', 1)} copies of {summary[k]} strips"))
            continue
        try:
            rows.append((label, text(summary[k])))
        except (KeyError, IndexError, TypeError, ValueError):
            continue
    for mode, label in (("shared", "Shared-edge cut"), ("separate", "Separate pieces")):
        if mode in summary.get("modes", {}):
            rows.append((label, _cut(summary["modes"][mode])))
    cutter = summary.get("cutter")
    if isinstance(cutter, dict) and "cut_length_mm" in cutter:
        rows.append((f"Cuts ({cutter.get('name', 'cutter')})",
                     _n(cutter["cut_length_mm"] / 1000, "m")))
    levels = summary.get("levels")
    if isinstance(levels, list) and levels and isinstance(levels[-1], dict):
        last = levels[-1]
        for k in ("tiles", "strands", "crossings"):
            if k in last:
                rows.append((f"{k.capitalize()} at level {last.get('level', '')}", _n(last[k])))
    return rows


def warnings(summary: dict) -> list[str]:
    found = summary.get("warnings", [])
    return [str(w) for w in found] if isinstance(found, list) else []
