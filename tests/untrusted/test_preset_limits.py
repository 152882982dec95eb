"""Every preset key against the README's table "What a preset may hold" (the published limits:
a power is a per cent of the laser's, in (0, 100]; a stroke is 0 to 10 mm wide; a pass count is
whole, ...). Each limit is held at its edges through ``presets.load``, the reader of
``--material``, ``--laser``, ``--palette``, ``--page`` and ``--cutter``: the value at a closed
end is taken, a value just past either end is refused with the limit and its unit (#34: a
power of 0 % or over 100 % and a stroke over 10 mm wide passed every test)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from weavecut import presets
from weavecut.presets import PresetError

README = Path(__file__).resolve().parents[2] / "README.md"
KINDS = ("palettes", "materials", "laser", "pages", "cutters")
ROLES = ("cut", "score", "engrave")

# a valid document of each kind, every optional key present (the rows change one value)
BASE = {
    "palettes": {"name": "p", "description": "d", "colours": ["#ffffff"]},
    "materials": {"name": "m", "description": "d", "thickness": "3mm", "kerf": "0.15mm",
                  "sheet": "1300x900mm", "cut_speed": 20.0,
                  "cut": {"power": 50, "passes": 1},
                  "score": {"speed": 100, "power": 20, "passes": 1},
                  "engrave": {"speed": 150, "power": 15, "passes": 1}},
    "laser": {"name": "l", "description": "d", "formats": ["svg"],
              **{r: {"colour": "#000000", "width": "0mm"} for r in ROLES}},
    "pages": {"name": "p", "description": "d", "width": "100mm", "height": "200mm"},
    "cutters": {"name": "c", "description": "d", "marks": "corners", "inset": "10mm",
                "length": "20mm", "thickness": "1mm", "clearance": "1mm",
                "min_feature": "1mm", "max_width": "300mm", "max_height": "300mm"},
}
# what a list of each kind holds, one item
ITEM = {"colours": "#ffffff", "families": ["#ffffff"], "family_names": "f", "colour_names": "f",
        "formats": "svg"}


def rows() -> list[dict]:
    """The README table's rows: kind(s), table(s), key, value, range, note."""
    text = README.read_text(encoding="utf-8")
    section = text.split("### What a preset may hold", 1)[1].split("\n## ", 1)[0]
    out = []
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 5 or cells[0] in ("kind", "---"):
            continue
        kind, key_cell, value, limits, note = cells
        names = re.findall(r"`([^`]+)`", key_cell)
        out.append({"kinds": KINDS if kind == "every kind" else (kind,),
                    "tables": [n.strip("[]") for n in names if n.startswith("[")] or [None],
                    "key": names[-1], "value": value, "range": limits, "note": note})
    return out


ROWS = rows()


def toml_value(v) -> str:
    if isinstance(v, str):
        return '"' + v + '"'
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    return repr(v)


def load(kind: str, doc: dict, tmp_path: Path) -> dict:
    """``doc`` written as a TOML file and read back through ``presets.load``."""
    flat = "".join(f"{k} = {toml_value(v)}\n" for k, v in doc.items() if not isinstance(v, dict))
    tables = "".join(f"[{k}]\n" + "".join(f"{kk} = {toml_value(vv)}\n" for kk, vv in v.items())
                     for k, v in doc.items() if isinstance(v, dict))
    path = tmp_path / f"{kind}.toml"
    path.write_text(flat + tables, encoding="utf-8")
    return presets.load(kind, str(path))


def changed(kind: str, table: str | None, key: str, value) -> dict:
    """The base document of ``kind`` with ``[table] key`` set to ``value`` (removed: None)."""
    doc = {k: dict(v) if isinstance(v, dict) else v for k, v in BASE[kind].items()}
    where = doc[table] if table else doc
    if value is None:
        where.pop(key, None)
    else:
        where[key] = value
    return doc


def cases(pred) -> list[tuple]:
    return [(kind, table, row) for row in ROWS if pred(row) for kind in row["kinds"]
            for table in row["tables"]]


def case_id(case) -> str:
    kind, table, row = case
    return f"{kind}-{table + '-' if table else ''}{row['key']}"


def refuses(kind, doc, tmp_path, *needles):
    with pytest.raises(PresetError) as caught:
        load(kind, doc, tmp_path)
    for needle in needles:
        assert needle in str(caught.value), (needle, str(caught.value))


INTERVAL = re.compile(r"^([\[(])(\d+), (\d+)([\])])\s*(.*)$")
NUMERIC = cases(lambda r: r["value"] in ("length", "number", "whole"))


@pytest.mark.parametrize("case", NUMERIC, ids=map(case_id, NUMERIC))
def test_each_number_is_held_at_the_edges_the_readme_states(case, tmp_path):
    kind, table, row = case
    lo_bracket, lo, hi, hi_bracket, unit = INTERVAL.match(row["range"]).groups()
    lo, hi = int(lo), int(hi)
    assert hi_bracket == "]"  # every upper limit is taken
    if row["value"] == "whole":
        shown, inside, past_hi, past_lo = (lambda x: x), None, hi + 1, lo - 1
    else:
        if row["value"] == "length":
            def shown(x):
                return f"{x}{unit}"
        else:
            def shown(x):
                return float(x)
        inside, past_hi, past_lo = lo + 1e-6, hi * (1 + 1e-6), lo - 1e-6
    label = f"[{table}] " if table else ""
    key = row["key"]
    load(kind, changed(kind, table, key, shown(hi)), tmp_path)
    refuses(kind, changed(kind, table, key, shown(past_hi)), tmp_path,
            f"{label}{key}: ", f"must be <= {hi}{' ' + unit if unit else ''}")
    if lo_bracket == "(":
        refuses(kind, changed(kind, table, key, shown(lo)), tmp_path,
                f"{label}{key}: ", f"must be > {lo}{' ' + unit if unit else ''}")
        load(kind, changed(kind, table, key, shown(inside)), tmp_path)
    else:
        load(kind, changed(kind, table, key, shown(lo)), tmp_path)
        refuses(kind, changed(kind, table, key, shown(past_lo)), tmp_path,
                f"{label}{key}: ", f"must be >= {lo}{' ' + unit if unit else ''}")


REQUIRED = cases(lambda r: r["note"].startswith("required"))


@pytest.mark.parametrize("case", REQUIRED, ids=map(case_id, REQUIRED))
def test_each_required_key_is_required(case, tmp_path):
    kind, table, row = case
    label = f"[{table}] " if table else ""
    refuses(kind, changed(kind, table, row["key"], None), tmp_path,
            f"{label}missing key {row['key']!r}")
    if table and "as are the three tables" in row["note"]:
        refuses(kind, changed(kind, None, table, None), tmp_path, f"missing key {table!r}")


def test_every_key_of_every_kind_is_in_the_table():
    """The table names every key the schemas take, and no other (a key of the table the code
    does not know would be refused as unknown: the numbers above would fail first)."""
    listed = {(kind, table, row["key"]) for kind, table, row in cases(lambda r: True)}
    known = set()
    for kind, schema in presets.schemas().items():
        for key, field in schema.fields.items():
            sub = getattr(field, "fields", None)
            known |= ({(kind, key, k) for k in sub} if sub else {(kind, None, key)})
    assert listed == known


TEXTS = cases(lambda r: r["value"] == "text")


@pytest.mark.parametrize("case", TEXTS, ids=map(case_id, TEXTS))
def test_each_text_is_held_at_its_length(case, tmp_path):
    kind, table, row = case
    longest = int(re.fullmatch(r"at most (\d+) characters", row["range"]).group(1))
    load(kind, changed(kind, table, row["key"], "x" * longest), tmp_path)
    refuses(kind, changed(kind, table, row["key"], "x" * (longest + 1)), tmp_path,
            f"{row['key']}: longer than {longest} characters")


LISTS = cases(lambda r: r["value"].startswith("list"))


@pytest.mark.parametrize("case", LISTS, ids=map(case_id, LISTS))
def test_each_list_is_held_at_its_counts(case, tmp_path):
    kind, table, row = case
    key = row["key"]
    shortest, longest = map(int, re.match(r"(\d+) to (\d+)", row["range"]).groups())
    base = changed(kind, None, "colours", None) if key == "families" else BASE[kind]
    for n, ok in ((shortest, True), (longest, True), (shortest - 1, False), (longest + 1, False)):
        doc = {**base, key: [ITEM[key]] * n}
        if ok:
            load(kind, doc, tmp_path)
        else:
            refuses(kind, doc, tmp_path, f"{key}: needs {shortest} to {longest} items")
    inner = re.search(r"of (\d+) to (\d+)$|of at most (\d+) characters$", row["range"])
    if inner and inner.group(2):  # a family: 1 to 16 colours
        lo, hi = int(inner.group(1)), int(inner.group(2))
        load(kind, {**base, key: [["#ffffff"] * hi]}, tmp_path)
        for n in (lo - 1, hi + 1):
            refuses(kind, {**base, key: [["#ffffff"] * n]}, tmp_path,
                    f"{key}: item 1: needs {lo} to {hi} items")
    elif inner:
        longest = int(inner.group(3))
        load(kind, {**base, key: ["f" * longest]}, tmp_path)
        refuses(kind, {**base, key: ["f" * (longest + 1)]}, tmp_path,
                f"{key}: item 1: longer than {longest} characters")


def test_a_palette_has_colours_or_families_and_not_both(tmp_path):
    both = {**BASE["palettes"], "families": [["#000000"]]}
    refuses("palettes", both, tmp_path, "exactly one of 'colours' or 'families'")
    refuses("palettes", changed("palettes", None, "colours", None), tmp_path, "exactly one of")


def test_the_cut_runs_at_cut_speed_and_has_no_speed_of_its_own(tmp_path):
    refuses("materials", changed("materials", "cut", "speed", 50), tmp_path,
            "[cut] unknown key 'speed'")


CHOICES = cases(lambda r: r["key"] in ("marks", "colour"))


@pytest.mark.parametrize("case", CHOICES, ids=map(case_id, CHOICES))
def test_each_choice_takes_what_the_table_names(case, tmp_path):
    kind, table, row = case
    label = f"[{table}] " if table else ""
    named = re.findall(r"`([^`]+)`", row["value"])
    for value in (["#00ff80", "#A0b0C0"] if named == ["#rrggbb"] else named):
        load(kind, changed(kind, table, row["key"], value), tmp_path)
    bad = "#00ff8" if named == ["#rrggbb"] else "circles"
    refuses(kind, changed(kind, table, row["key"], bad), tmp_path, f"{label}{row['key']}: ")


def test_a_sheet_side_is_held_at_10_m(tmp_path):
    row = next(r for r in ROWS if r["key"] == "sheet")
    assert "each side (0, 10000] mm" in row["range"]
    for size in ("10000x10000mm", "1000cm x 1mm".replace(" ", ""), "a4"):
        load("materials", changed("materials", None, "sheet", size), tmp_path)
    refuses("materials", changed("materials", None, "sheet", "10000.01x100mm"), tmp_path,
            "sheet: ", "larger than 10 m")
    refuses("materials", changed("materials", None, "sheet", "0x100mm"), tmp_path,
            "sheet: ", "must be positive")
