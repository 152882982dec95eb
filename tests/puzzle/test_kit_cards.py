"""The kit page of a puzzle build says of each laser file what its layers hold (issue 29: "cut
red, score blue, engrave black at 20 mm/s" gave the cut's speed for all three, and named a
score layer the separate sheet lacks) and counts a guide's paints, not the bare wood beside
them ("21 colours" for 20 paints). Oracles: the layers of each written SVG, the settings of the
written LightBurn project (its CutSettings), the colour key's paints in the summary."""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from click.testing import CliRunner

from weavecut.cli import cli

from tests.test_kitpage import cards

RECIPES = Path(__file__).resolve().parents[2] / "templates" / "recipes"
WORDS = {"#ff0000": "red", "#0000ff": "blue", "#000000": "black"}


@pytest.fixture(scope="module")
def heart(tmp_path_factory):
    folder = tmp_path_factory.mktemp("kit") / "heart"
    result = CliRunner().invoke(cli, ["build", str(RECIPES / "heart-puzzle.toml"), "-o",
                                      str(folder)])
    assert result.exit_code == 0, result.output
    return folder, cards((folder / "index.html").read_text(encoding="utf-8"))


def _project(path: Path) -> list[tuple[str, str]]:
    """(role word, settings) of every layer of a LightBurn project, in the order it runs:
    the SVG's colour of that layer, with the project's speed and power."""
    root = ET.parse(path).getroot()
    out = []
    for s in sorted(root.iter("CutSetting"), key=lambda s: int(s.find("priority").get("Value"))):
        name = s.find("name").get("Value")
        out.append((name, f"at {float(s.find('speed').get('Value')):g} mm/s, "
                          f"{float(s.find('maxPower').get('Value')):g} %"))
    return out


@pytest.mark.parametrize("stem", ["puzzle-shared-cut", "puzzle-separate-sheet-1"])
def test_each_laser_card_gives_each_of_its_layers_own_settings(heart, stem):
    folder, found = heart
    said = found[stem]["for"]
    svg = (folder / f"{stem}.svg").read_text(encoding="utf-8")
    groups = re.findall(r'<g id="(engrave|score|cut)-[^"]*" inkscape:groupmode="layer" '
                        r'inkscape:label="([^"]+)">.*?stroke="(#[0-9a-f]{6})"', svg)
    roles = {role: WORDS[colour] for role, _, colour in groups}
    settings = {name: text for name, text in _project(folder / f"{stem}.lbrn2")}
    expected = []
    for role in ("engrave", "score", "cut"):
        if role in roles:
            names = [name for r, name, _ in groups if r == role]
            assert len({settings[n] for n in names}) == 1  # a role's layers share settings
            expected.append(f"{role} {roles[role]} {settings[names[0]]}")
    assert said.split(": ", 1)[1].split(" (")[0] == "; ".join(expected)
    assert ("score" in said) == ("score" in roles)


def test_a_guide_card_counts_its_paints(heart):
    folder, found = heart
    summary = json.loads((folder / "puzzle-summary.json").read_text(encoding="utf-8"))
    for side in ("front", "back"):
        paints = summary[f"{side}_colours"]
        for name in (f"puzzle-{side}-guide", f"puzzle-{side}-guide-a4"):
            facts = found[name]["facts"]
            assert f"{paints} paints" in facts and not any("colours" in f for f in facts)
