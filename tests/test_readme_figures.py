"""Every figure the README states about an output is what the command makes now: each claim
finds its sentence or table row in the README (exactly once: a reworded claim fails here
until this file follows), runs the command with ``--json`` and compares the figures as the
README rounds them. ``test_findings.py`` does the same for the paper's numbers."""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import pytest
from click.testing import CliRunner

from weavecut.cli import cli

ROOT = Path(__file__).resolve().parents[1]


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


BALL = ("strands", "dodecahedron", "--levels", "1", "--project", "sphere", "--size", "12cm")
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
          r"(?P<shared>[\d.]+) m / (?P<separate>[\d.]+) m on (?P<sheets>\d+) sheets of 800 × 500 "
          r"\| (?P<t1>\d+) / (?P<t2>\d+) min \|",
          ("puzzle", "--levels", "4", "--size", "50cm", "--material", "poplar-3mm",
           "--numbers", "-o", "pz"), puzzle),
]
NUMBER_WORDS = dict(enumerate(["no", "one", "two", "three", "four", "five", "six", "seven",
                               "eight", "nine", "ten"]))
SOLIDS = [(s, level) for s in ("dodecahedron", "cube") for level in (1, 2)]


def run(args, tmp_path) -> dict:
    result = CliRunner().invoke(cli, ["-q", *args, "--json"], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


def stated(pattern: str, readme: Path = ROOT / "README.md") -> dict[str, str]:
    """The groups of ``pattern`` in the README, which must hold it exactly once."""
    found = list(re.finditer(pattern, readme.read_text(encoding="utf-8")))
    assert len(found) == 1, f"the README states this {len(found)} times, not once: {pattern}"
    return found[0].groupdict()


@pytest.mark.parametrize("claim", CLAIMS, ids=lambda c: c.name)
def test_readme_figures_are_what_the_command_makes(claim, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert stated(claim.pattern) == claim.figures(run(claim.args, tmp_path))


@pytest.mark.parametrize("name, level", SOLIDS, ids=lambda v: str(v))
def test_the_solids_table_is_what_the_command_makes(name, level, tmp_path, monkeypatch):
    """A row of the table of woven solids: at 40 mm octagons, 1 m across (loop lengths per
    diameter), on the sphere and (in brackets) without."""
    monkeypatch.chdir(tmp_path)
    row = (rf"\| {name} \| {level} \| (?P<strands>\d+) \| (?P<loop>[\d.]+) \((?P<loop0>[\d.]+)\)"
           r" \| (?P<edge>[\d.]+) % \((?P<edge0>[\d.]+) %\) \| (?P<flat>[\d.]+) % "
           r"\((?P<flat0>[\d.]+) %\) \| (?P<pages>\d+): (?P<pieces>\d+) pieces "
           r"\((?P<pages0>\d+)\) \|")
    base = ("strands", name, "--levels", str(level), "--tile-size", "40mm")
    on = run((*base, "--project", "sphere", "-o", "on.pdf"), tmp_path)
    off = run((*base, "-o", "off.pdf"), tmp_path)
    assert stated(row) == solid(on, off)


def test_a_changed_figure_fails(tmp_path, monkeypatch):
    """The check itself: a README one page off is caught (the first claim, edited)."""
    claim = CLAIMS[0]
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    wrong = re.sub(claim.pattern, lambda m: m.group(0).replace(
        f"({m['pages']} A4", f"({int(m['pages']) + 1} A4"), text)
    (tmp_path / "README.md").write_text(wrong, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    figures = claim.figures(run(claim.args, tmp_path))
    assert stated(claim.pattern) == figures
    assert stated(claim.pattern, tmp_path / "README.md") != figures
