"""Every figure the README states about an output is what the command makes now: each claim
finds its sentence or table row in the README (exactly once: a reworded claim fails here
until this file follows), runs the command with ``--json`` and compares the figures as the
README rounds them. ``test_findings.py`` does the same for the paper's numbers."""

from __future__ import annotations

import contextlib
import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import pytest
from click.testing import CliRunner

from weavecut.cli import cli

from .once import once, session_root

ROOT = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.slow  # whole commands, the 8-4 level 4 puzzle among them


@dataclass(frozen=True)
class Claim:
    name: str
    pattern: str  # a regex with named groups: the figures as the README writes them
    args: tuple[str, ...]  # the command, run with -q ... --json in an empty folder
    figures: Callable[[dict], dict[str, str]]  # the same groups, from the command's JSON


def paper(pages: str) -> Callable[[dict], dict[str, str]]:
    """A paper model's pages (total, or strip pages with ``pages="strip"``), copies, strips."""
    return lambda j: {"pages": str(j["pages"][pages]), "copies": str(j["copies"]),
                      "strips": str(j["module_strips"])}


def solid(j: dict, flat: dict) -> dict[str, str]:
    """A row of the solids table: on the sphere, and (in brackets) without projecting."""
    loop = lambda d: f"{d['strand_lengths_mm'][0] / d['diameter_mm']:.2f}"  # noqa: E731
    return {"strands": str(j["strands"]), "loop": loop(j), "loop0": loop(flat),
            "edge": f"{j['largest_edge_change_pct']:.2f}",
            "edge0": f"{flat['largest_edge_change_pct']:.2f}",
            "flat": f"{j['largest_non_planarity_pct']:.1f}",
            "flat0": f"{flat['largest_non_planarity_pct']:.1f}",
            "pages": str(j["pages"]["total"]), "pieces": str(j["pieces"]),
            "pages0": str(flat["pages"]["total"])}


def puzzle(j: dict) -> dict[str, str]:
    """A row of the puzzle table: pieces, sizes across, cut lengths, sheets, times."""
    shared, separate = j["modes"]["shared"], j["modes"]["separate"]
    lo, hi = j["piece_across_mm"][:2]
    return {"pieces": str(j["pieces"]), "oct": str(j["pieces_by_type"]["octagon"]),
            "enn": str(j["pieces_by_type"]["enneagon"]), "lo": f"{lo:.1f}", "hi": f"{hi:.1f}",
            "shared": f"{shared['cut_length_m']:.1f}", "separate": f"{separate['cut_length_m']:.1f}",
            "sheets": str(separate["sheets"]), "t1": f"{shared['time_min']:.0f}",
            "t2": f"{separate['time_min']:.0f}"}


def puzzle_row(j: dict) -> dict[str, str]:
    """A row of the puzzle table in any of its forms: the groups a row states (pieces, kinds,
    sizes across, narrowest, shared and separate cut, sheets, times), from the JSON."""
    modes = j["modes"]
    lo, hi = j["piece_across_mm"][:2]
    out = {"pieces": str(j["pieces"]), "oct": str(j["pieces_by_type"]["octagon"]),
           "enn": str(j["pieces_by_type"]["enneagon"]), "lo": f"{lo:g}", "hi": f"{hi:g}",
           "narrow": f"{j['piece_width_min_mm']:g}",
           "separate": f"{modes['separate']['cut_length_m']:.1f}",
           "sheets": str(modes["separate"]["sheets"]),
           "t2": f"{modes['separate']['time_min']:.0f}"}
    if "shared" in modes:
        out.update(shared=f"{modes['shared']['cut_length_m']:.1f}",
                   t1=f"{modes['shared']['time_min']:.0f}")
    return out


def row(label: str, frame: str) -> str:
    """The pattern of a puzzle table row: ``label`` and ``frame`` cells as regexes."""
    return (rf"\| {label} \| (?P<pieces>\d+)(?: \((?P<oct>\d+) octagons, (?P<enn>\d+) "
            r"enneagons\))? \| (?P<lo>[\d.]+)–(?P<hi>[\d.]+) mm(?:, narrowest "
            r"(?P<narrow>[\d.]+) mm)?[^|]* \| " + frame + r" \| (?:(?P<shared>[\d.]+) m|–[^/]*) / "
            r"(?P<separate>[\d.]+) m on (?P<sheets>\d+) sheets?[^|]* \| (?:(?P<t1>\d+)|–) / "
            r"(?P<t2>\d+) min \|")


def kit_row(command: str, unit: str, key: Callable[[dict], int]) -> Claim:
    """A row of the kits' speed table: its pages or sheets (its last cell), from the command
    the row names (run as written, with --json)."""
    args = tuple(command.split())
    return Claim(f"kits table: {command}",
                 rf"\| `{re.escape(command)}` \|[^\n]*\| (?P<n>\d+) {unit}s?\b[^|\n]*\|\n",
                 args, lambda j: {"n": str(key(j))})


def cutter_figures(j: dict) -> dict[str, str]:
    """Print and cut: strip pages, all pages, metres of cuts, the smallest feature."""
    return {"strip": str(j["pages"]["strip"]), "total": str(j["pages"]["total"]),
            "m": f"{j['cutter']['cut_length_mm'] / 1000:.1f}",
            "f": f"{j['cutter']['min_feature_mm']:.2f}"}


def strips_ink(decimals: str) -> Callable[[dict], dict[str, str]]:
    """A paper model's strip pages and its ink (per cent, to ``decimals`` places as the README
    writes it)."""
    return lambda j: {"strip": str(j["pages"]["strip"]),
                      "ink": f"{100 * j['ink_fraction']:.{decimals}f}"}


SQUARE_4 = ("strands", "square-grid", "--size", "27cm", "--palette", "maritime-4")
FLOWER_OKABE = ("strands", "pentagon-flower", "--size", "23cm", "--palette", "okabe-ito")
BALL = ("strands", "dodecahedron", "--levels", "1", "--project", "sphere", "--size", "12cm")
HEART = str(ROOT / "templates" / "recipes" / "heart.svg")
CLAIMS = [
    Claim("square grid paper model",
          r"`weave-cut strands square-grid -o square\.pdf` \((?P<pages>\d+) A4 pages, "
          r"(?P<copies>\d+) copies of a (?P<strips>\d+)-strip module\)",
          ("strands", "square-grid", "-o", "square.pdf"), paper("total")),
    Claim("pentagon paper model",
          r"`weave-cut strands pentagon-flower -o pentagon\.pdf` \((?P<pages>\d+) pages, "
          r"(?P<copies>\d+) copies of a (?P<strips>\d+)-strip module\)",
          ("strands", "pentagon-flower", "-o", "pentagon.pdf"), paper("total")),
    Claim("woven ball",
          r"--size 12cm -o ball\.pdf` \((?P<pages>\d+) A4 pages: (?P<strands>\d+) closed strips "
          r"in (?P<pieces>\d+) pieces\)",
          (*BALL, "-o", "ball.pdf"),
          lambda j: {"pages": str(j["pages"]["total"]), "strands": str(j["strands"]),
                     "pieces": str(j["pieces"])}),
    Claim("star paper model",
          r"makes the paper star \((?P<strips>\d+) strips on (?P<strip_pages>\w+) A4 strip pages?, "
          r"(?P<pages>\w+) pages in all, about\s+(?P<w>\d+) × (?P<h>\d+) cm\)",
          ("strands", str(ROOT / "examples" / "star.svg"), "--cell", "10mm", "--levels", "1",
           "--tile-size", "21mm", "-o", "star.pdf"),
          lambda j: {"strips": str(j["module_strips"]),
                     "strip_pages": NUMBER_WORDS[j["pages"]["strip"]],
                     "pages": NUMBER_WORDS[j["pages"]["total"]],
                     "w": f"{j['model_mm'][0] / 10:.0f}", "h": f"{j['model_mm'][1] / 10:.0f}"}),
    Claim("default puzzle",
          r"\| default \(`jigsaw-50cm-poplar`\) \| (?P<pieces>\d+) \((?P<oct>\d+) octagons, "
          r"(?P<enn>\d+) enneagons\) \| (?P<lo>[\d.]+)–(?P<hi>[\d.]+) mm \| 500 mm, one piece \| "
          r"(?P<shared>[\d.]+) m / (?P<separate>[\d.]+) m on (?P<sheets>\d+) sheets? of 800 × 500 "
          r"\| (?P<t1>\d+) / (?P<t2>\d+) min \|",
          ("puzzle", "--levels", "4", "--size", "50cm", "--material", "poplar-3mm",
           "--numbers", "-o", "pz"), puzzle),
    Claim("kit page: the jigsaw's guides",
          r"jigsaw build \([\d.]+ s; (?P<front>\d+) \+ (?P<back>\d+) PDF pages of painting "
          r"guides and",
          ("puzzle", "--levels", "4", "--size", "50cm", "--material", "poplar-3mm",
           "--numbers", "-o", "pz"), lambda j: {k: str(n) for k, n in j["guide_pages"].items()}),
    Claim("kit page: the pentagon paper model",  # recipe pentagon-paper-model
          r"each paper model \(the pentagon's (?P<pages>\d+) PDF pages, the square grid's",
          ("strands", "pentagon-flower", "--palette", "maritime-12", "--size", "23cm", "-o",
           "pf.pdf"), lambda j: {"pages": str(j["pages"]["total"])}),
    Claim("kit page: the square grid's module layout",  # recipe square-grid-paper-model
          r"the square grid's\s+(?P<pages>\d+) \+ \d+\),",
          ("strands", "square-grid", "--palette", "maritime-12", "--size", "27cm", "--layout",
           "module", "-o", "sq.pdf"), lambda j: {"pages": str(j["pages"]["total"])}),
    Claim("kit page: the square grid, mixed",
          r"the square grid's\s+\d+ \+ (?P<pages>\d+)\),",
          (*SQUARE_4, "-o", "sq.pdf"), lambda j: {"pages": str(j["pages"]["total"])}),
]
ROWS = [
    Claim("puzzle table: --size 30cm", row(r"`--size 30cm`", r"300 mm"),
          ("puzzle", "--size", "30cm", "-o", "pz"), puzzle_row),
    Claim("puzzle table: small sheets", row(r"`--sheet 600x400mm` \(`jigsaw-small-sheets`\)",
                                            r"2 dovetailed parts"),
          ("puzzle", "--levels", "4", "--size", "50cm", "--material", "poplar-3mm", "--sheet",
           "600x400mm", "--mode", "separate", "--numbers", "-o", "pz"), puzzle_row),
    Claim("puzzle table: 8-4 level 4", row(r"`tiling-8-4` \(level 4\)", r"500 × 500 mm"),
          ("puzzle", "tiling-8-4", "-o", "pz"), puzzle_row),
    Claim("puzzle table: 8-4 level 3", row(r"`tiling-8-4 --levels 3`", r"500 × 500 mm"),
          ("puzzle", "tiling-8-4", "--levels", "3", "-o", "pz"), puzzle_row),
    Claim("puzzle table: 8-4 level 2", row(r"`tiling-8-4 --levels 2`", r"500 × 500 mm"),
          ("puzzle", "tiling-8-4", "--levels", "2", "-o", "pz"), puzzle_row),
    Claim("puzzle table: heart", row(r"`heart-puzzle` \(`heart.svg`, level 2, `--size 30cm`, "
                                     r"birch\)", r"300 × 278.4 mm"),
          ("puzzle", HEART, "--cell", "39mm", "--levels", "2", "--size", "30cm", "--frame",
           "15mm", "--material", "birch-plywood-3mm", "--numbers", "-o", "pz"), puzzle_row),
    Claim("slimmest piece: star", r"\(`slimmest_piece_mm`: the narrowest neck, sliver or notch\): the star "
          r"(?P<s>[\d.]+) mm",
          ("strands", str(ROOT / "examples" / "star.svg"), "--cell", "10mm", "--levels", "1",
           "--tile-size", "21mm", "-o", "star.pdf"),
          lambda j: {"s": f"{j['slimmest_piece_mm']:g}"}),
    Claim("slimmest piece: pentagon flower",
          r"the pentagon flower at 23 cm\s+(?P<s>[\d.]+) mm,\s+the square grid",
          ("strands", "pentagon-flower", "--size", "23cm", "-o", "pf.pdf"),
          lambda j: {"s": f"{j['slimmest_piece_mm']:g}"}),
    Claim("slimmest piece: square grid", r"the square grid at 27 cm (?P<s>[\d.]+) mm\.",
          ("strands", "square-grid", "--size", "27cm", "-o", "sq.pdf"),
          lambda j: {"s": f"{j['slimmest_piece_mm']:g}"}),
    Claim("cut by machine: square grid, Silhouette",
          r"for a Silhouette, (?P<strip>\d+)\s+strip pages \((?P<total>\d+) with the assembly "
          r"and weaving pages\), on Letter for a Cricut \d+; (?P<m>[\d.]+) m of cuts,\s+"
          r"smallest feature (?P<f>[\d.]+) mm\. From card",
          (*SQUARE_4, "--cutter", "silhouette", "-o", "sq.pdf"), cutter_figures),
    Claim("cut by machine: square grid, Cricut", r"on Letter for a Cricut (?P<strip>\d+);",
          (*SQUARE_4, "--cutter", "cricut", "--page", "letter", "-o", "sq.pdf"),
          lambda j: {"strip": str(j["pages"]["strip"])}),
    Claim("cut by machine: square grid, card",
          r"From card: (?P<sheets>\d+) A4 sheets in (?P<colours>\d+) colours, (?P<m>[\d.]+) m "
          r"of cuts \(recipe\s+`square-grid-cut-by-machine`\)",
          (*SQUARE_4, "--laser-card", "--material", "card-300gsm", "-o", "card"),
          lambda j: {"sheets": str(j["sheets"]), "colours": str(j["card_colours"]),
                     "m": f"{j['cut_length_mm'] / 1000:.1f}"}),
    Claim("cut by machine: pentagon flower, Silhouette",
          r"its (?P<strands>\d+) strips: (?P<strip>\d+) strip pages for a Silhouette "
          r"\((?P<total>\d+) pages in all, 9\s+while a page named the strands page 1 has no "
          r"room for\), (?P<m>[\d.]+) m of cuts,\s+smallest feature (?P<f>[\d.]+) mm \(it was "
          r"1\.26 mm[\s\S]*?The (?P<tabs>\d+) label tabs",
          (*FLOWER_OKABE, "--cutter", "silhouette", "-o", "pf.pdf"),
          lambda j: {"strands": str(j["strands"]), "tabs": str(j["label_tabs"]),
                     **cutter_figures(j)}),
    Claim("cut by machine: pentagon flower, card",
          r"from card, one 12 x 12 in\s+sheet per colour, (?P<m>[\d.]+) m, smallest engraved "
          r"label (?P<label>[\d.]+) mm, (?P<dots>\d+) engraved dots, and (?P<pages>\d+) A4 pages",
          (*FLOWER_OKABE, "--laser-card", "--material", "card-300gsm-12in", "-o", "card"),
          lambda j: {"m": f"{j['cut_length_mm'] / 1000:.1f}",
                     "label": f"{j['smallest_label_mm']:.1f}", "dots": str(j["engraved_dots"]),
                     "pages": str(j["instruction_pages"])}),
    Claim("packing: pentagon flower on A4",
          r"the pentagon flower \(23 cm\) (?P<strip>\d+)\s+strip pages on A4 \((?P<ink>\d+) % ink\)",
          ("strands", "pentagon-flower", "--size", "23cm", "-o", "pf.pdf"), strips_ink("0")),
    Claim("packing: pentagon flower on Letter",
          r"the pentagon flower \(23 cm\) (?P<strip>\d+)\s+strip pages on A4 \(\d+ % ink\) and "
          r"on Letter \((?P<ink>\d+) %\)",
          ("strands", "pentagon-flower", "--size", "23cm", "--page", "letter", "-o", "pf.pdf"),
          strips_ink("0")),
    Claim("packing: square grid maritime-4 on A4",
          r"the square grid \(27 cm, `--palette\s+maritime-4`\) (?P<strip>\d+) on A4 "
          r"\((?P<ink>\d+) %;", (*SQUARE_4, "-o", "sq.pdf"), strips_ink("0")),
    Claim("packing: square grid maritime-4 on Letter",
          r"the square grid \(27 cm, `--palette\s+maritime-4`\) \d+ on A4 \(\d+ %;[^)]*\)\s+"
          r"and (?P<strip>\d+) on Letter \((?P<ink>\d+) %\)", (*SQUARE_4, "--page", "letter", "-o", "sq.pdf"),
          strips_ink("0")),
    Claim("packing: square grid at 16 cm",
          r"\(square grid 16 cm, pentagon flower 32 cm\) the strips take (?P<strip>\d+) and \d+ "
          r"A4 pages \((?P<ink>[\d.]+) % and",
          ("strands", "square-grid", "--size", "16cm", "-o", "sq.pdf"), strips_ink("0")),
    Claim("packing: pentagon flower at 32 cm",
          r"\(square grid 16 cm, pentagon flower 32 cm\) the strips take \d+ and (?P<strip>\d+) "
          r"A4 pages \([\d.]+ % and\s+(?P<ink>[\d.]+) % ink\)",
          ("strands", "pentagon-flower", "--size", "32cm", "-o", "pf.pdf"), strips_ink("1")),
    Claim("callouts: pentagon flower at 23 cm",
          r"\(the pentagon flower at 23 cm: (?P<names>\d+) names in its tiny[\s\S]*?\(the "
          r"pentagon flower at 23 cm:\s+(?P<n>\d+) callouts on pages (?P<first>\d+)-(?P<last>\d+), "
          r"so (?P<pages>\d+) pages in all\)",
          ("strands", "pentagon-flower", "--size", "23cm", "-o", "pf.pdf"),
          lambda j: {"names": str(j["names_left_out"]), "n": str(j["names_left_out"]),
                     **dict(zip(("first", "last"), next(
                         re.search(r"called out on pages (\d+)-(\d+)", w).groups()
                         for w in j["warnings"] if "called out on pages" in w))),
                     "pages": str(j["pages"]["total"])}),
    Claim("strand IDs: the module layout's pages",
          r"the module layout at 23 cm (?P<pages>\d+), not 5\)",
          ("strands", "pentagon-flower", "--size", "23cm", "--layout", "module", "-o", "pf.pdf"),
          lambda j: {"pages": str(j["pages"]["total"])}),
    kit_row("strands pentagon-flower --size 23cm -o pf.pdf", "page",
            lambda j: j["pages"]["total"]),
    kit_row("strands square-grid --size 27cm --laser-card -o card", "sheet",
            lambda j: j["sheets"]),
    kit_row("strands square-grid --size 27cm -o sq.pdf", "page", lambda j: j["pages"]["total"]),
    kit_row("puzzle --numbers -o pz", "sheet", lambda j: j["modes"]["separate"]["sheets"]),
    kit_row("strands dodecahedron --levels 1 --project sphere --size 12cm -o ball.pdf", "page",
            lambda j: j["pages"]["total"]),
]
NUMBER_WORDS = dict(enumerate(["no", "one", "two", "three", "four", "five", "six", "seven",
                               "eight", "nine", "ten"]))
SOLIDS = [(s, level) for s in ("dodecahedron", "cube") for level in (1, 2)]


@pytest.fixture(scope="session")
def run(tmp_path_factory) -> Callable[..., dict]:
    """``run(args)``: the JSON of ``weave-cut -q ARGS --json``, run in an empty folder once
    per session (several claims name one command; the xdist workers share it: once.py)."""
    root = session_root(tmp_path_factory)

    def make(args: tuple[str, ...]) -> dict:
        with contextlib.chdir(tmp_path_factory.mktemp("run")):
            result = CliRunner().invoke(cli, ["-q", *args, "--json"], catch_exceptions=False)
        assert result.exit_code == 0, result.output
        return json.loads(result.stdout)

    return lambda args: once(root, json.dumps(list(args)), lambda: make(tuple(args)))


def stated(pattern: str, readme: Path = ROOT / "README.md") -> dict[str, str]:
    """The groups of ``pattern`` in the README, which must hold it exactly once."""
    found = list(re.finditer(pattern, readme.read_text(encoding="utf-8")))
    assert len(found) == 1, f"the README states this {len(found)} times, not once: {pattern}"
    return found[0].groupdict()


@pytest.mark.parametrize("claim", CLAIMS, ids=lambda c: c.name)
def test_readme_figures_are_what_the_command_makes(claim, run):
    assert stated(claim.pattern) == claim.figures(run(claim.args))


@pytest.mark.parametrize("claim", ROWS, ids=lambda c: c.name)
def test_the_tables_rows_are_what_the_command_makes(claim, run):
    """The puzzle table's rows and the kits table's pages and sheets: the figures a row states
    (a row may leave some out: an empty cell, no breakdown of the pieces) are the command's."""
    said = {k: v for k, v in stated(claim.pattern).items() if v is not None}
    made = claim.figures(run(claim.args))
    assert said and said == {k: made[k] for k in said}


@pytest.mark.parametrize("name, level", SOLIDS, ids=lambda v: str(v))
def test_the_solids_table_is_what_the_command_makes(name, level, run):
    """A row of the table of woven solids: at 40 mm octagons, 1 m across (loop lengths per
    diameter), on the sphere and (in brackets) without."""
    row = (rf"\| {name} \| {level} \| (?P<strands>\d+) \| (?P<loop>[\d.]+) \((?P<loop0>[\d.]+)\)"
           r" \| (?P<edge>[\d.]+) % \((?P<edge0>[\d.]+) %\) \| (?P<flat>[\d.]+) % "
           r"\((?P<flat0>[\d.]+) %\) \| (?P<pages>\d+): (?P<pieces>\d+) pieces "
           r"\((?P<pages0>\d+)\) \|")
    base = ("strands", name, "--levels", str(level), "--tile-size", "40mm")
    on = run((*base, "--project", "sphere", "-o", "on.pdf"))
    off = run((*base, "-o", "off.pdf"))
    assert stated(row) == solid(on, off)


def test_a_changed_figure_fails(tmp_path, run):
    """The check itself: a README one page off is caught (the first claim, edited)."""
    claim = CLAIMS[0]
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    wrong = re.sub(claim.pattern, lambda m: m.group(0).replace(
        f"({m['pages']} A4", f"({int(m['pages']) + 1} A4"), text)
    (tmp_path / "README.md").write_text(wrong, encoding="utf-8")
    figures = claim.figures(run(claim.args))
    assert stated(claim.pattern) == figures
    assert stated(claim.pattern, tmp_path / "README.md") != figures


LIGHTBURN = [  # (the README table's first cell, the command it runs, the project it reads)
    ("`puzzle --numbers --formats lbrn2 -o pz`, shared cut",
     ("puzzle", "--numbers", "--formats", "lbrn2", "-o", "pz"), "pz/puzzle-shared-cut.lbrn2"),
    ("`puzzle --numbers --formats lbrn2 -o pz`, separate sheet 1",
     ("puzzle", "--numbers", "--formats", "lbrn2", "-o", "pz"),
     "pz/puzzle-separate-sheet-1.lbrn2"),
    ("the heart puzzle (recipe `heart-puzzle`), shared cut",
     ("build", str(ROOT / "templates" / "recipes" / "heart-puzzle.toml"), "-o", "pz"),
     "pz/puzzle-shared-cut.lbrn2"),
    ("the heart puzzle (recipe `heart-puzzle`), separate sheet 1",
     ("build", str(ROOT / "templates" / "recipes" / "heart-puzzle.toml"), "-o", "pz"),
     "pz/puzzle-separate-sheet-1.lbrn2"),
]


def project_layers(path: Path) -> str:
    """A LightBurn project's layers as the README's table states them, in the project's order:
    closed paths (a ``LineClosed`` primitive) + open ones (only the closed count where there
    are none open), and their length in m, the closing segments counted."""
    import xml.etree.ElementTree as ET

    import numpy as np

    root = ET.parse(path).getroot()
    names = {s.find("index").get("Value"): s.find("name").get("Value")
             for s in root.iter("CutSetting")}
    found: dict[str, list] = {}
    for shape in root.iter("Shape"):
        xy = np.array(re.findall(r"V(-?[\d.]+) (-?[\d.]+)", shape.find("VertList").text),
                      dtype=float)
        closed = shape.find("PrimList").text == "LineClosed"
        ring = np.vstack([xy, xy[:1]]) if closed else xy
        counts = found.setdefault(names[shape.get("CutIndex")], [0, 0, 0.0])
        counts[0 if closed else 1] += 1
        counts[2] += float(np.hypot(*np.diff(ring, axis=0).T).sum())
    return "; ".join(f"{name} {c}{f' + {o}' if o else ''}, {length / 1000:.2f} m"
                     for name, (c, o, length) in found.items())


@pytest.mark.parametrize("label, args, project", LIGHTBURN, ids=[r[0] for r in LIGHTBURN])
def test_the_lightburn_table_is_what_the_command_writes(label, args, project, tmp_path_factory):
    """The README's LightBurn table (issue 29: it said 137 + 1051 engraved paths where the
    project had 1219): each row is read off the project its command writes now."""
    root = session_root(tmp_path_factory)

    def make() -> dict[str, str]:  # every project the command writes, as a row
        folder = tmp_path_factory.mktemp("lbrn2")
        with contextlib.chdir(folder):
            result = CliRunner().invoke(cli, ["-q", *args], catch_exceptions=False)
        assert result.exit_code == 0, result.output
        return {p.relative_to(folder).as_posix(): project_layers(p)
                for p in folder.rglob("*.lbrn2")}

    rows = once(root, json.dumps(["lbrn2", *args]), make)
    said = stated(rf"\| {re.escape(label)} \| (?P<row>[^|\n]+) \|\n")
    assert said["row"] == rows[project]
