"""README.txt says only what the files written beside it allow (issue 29): each laser file's
layers are the layers its SVG holds, in the order the laser runs them; the separate pieces are
laid in by their numbers only when numbers are engraved (else by their shapes), and the
engraved face is named only then; every warning the run gives is in its Warnings; the frame's
"diagonal" is named only for the pentagon, whose --size it is; the .svg/.dxf advice names the
.lbrn2 project only when it is written, and the project keeps the cut order the SVG's one cut
colour cannot. The oracles read the written files (SVG layers, stderr, the project's XML)."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from functools import lru_cache
from pathlib import Path

import pytest
from click.testing import CliRunner

from weavecut.cli import cli

RECIPES = Path(__file__).resolve().parents[2] / "templates" / "recipes"
LAYER = re.compile(r"\b(engrave-numbers|score-ring|cut-\d-[a-z]+)\b")


@lru_cache(maxsize=None)
def _run(folder: str, *args: str) -> tuple[str, str]:
    """README.txt and stderr of ``puzzle ARGS -o folder``."""
    result = CliRunner().invoke(cli, ["puzzle", *args, "-o", folder])
    assert result.exit_code == 0, result.output
    return (Path(folder) / "README.txt").read_text(encoding="utf-8"), result.stderr


def _flat(text: str) -> str:
    return " ".join(text.split())


def _svg_layers(path: Path) -> list[tuple[str, str]]:
    """(role, name) of every layer group of a written SVG, in file order."""
    return re.findall(r'<g id="(engrave|score|cut)-[^"]*" inkscape:groupmode="layer" '
                      r'inkscape:label="([^"]+)"', path.read_text(encoding="utf-8"))


def _paragraph(readme: str, stem: str) -> str:
    """The laser section's paragraph of the file named ``stem``, on one line."""
    lines = readme.splitlines()
    start = next(k for k, line in enumerate(lines) if line.startswith(f"  {stem}"))
    end = next(k for k in range(start + 1, len(lines)) if not lines[k].startswith("    "))
    return _flat(" ".join(lines[start:end]))


@pytest.mark.parametrize("numbers", [False, True])
def test_layers_numbers_and_engraved_face_are_what_the_files_hold(numbers, tmp_path_factory):
    folder = tmp_path_factory.mktemp("numbers")
    readme, _ = _run(str(folder), "--levels", "2", *(["--numbers"] if numbers else []))
    order = ("engrave", "score", "cut")
    for stem in ("puzzle-shared-cut", "puzzle-separate-sheet-1"):
        held = sorted(_svg_layers(folder / f"{stem}.svg"), key=lambda rn: order.index(rn[0]))
        named = LAYER.findall(_paragraph(readme, stem).split("Layers in order:")[1])
        assert named == [name for _, name in held]
    sheets = [_svg_layers(p) for p in sorted(folder.glob("puzzle-separate-sheet-*.svg"))]
    engraved = any(name == "engrave-numbers" for layers in sheets for _, name in layers)
    assert engraved == numbers  # one board's frame: no frame labels on the engrave layer
    flat = _flat(readme)
    assert ("lay the pieces into the frame by their numbers" in flat) == numbers
    assert ("lay the pieces into the frame by their shapes" in flat) == (not numbers)
    assert ("numbers are engraved on the front" in flat) == numbers
    assert ("on the guides and on the wood" in flat) == numbers


def test_every_warning_of_the_run_is_in_the_readme(tmp_path):
    """The heart at the recipe's cell and level warns of non-convex faces: README.txt lists
    every warning the run printed that a maker can act on, and "none" only when there is none;
    the non-convex faces (the subdivision's, no concern of the workshop: walk of issue #29)
    stay on the terminal and in the JSON, and no jargon reaches the sheet."""
    readme, err = _run(str(tmp_path / "heart"), str(RECIPES / "heart.svg"), "--cell", "39mm",
                       "--levels", "2", "--size", "30cm", "--frame", "15mm",
                       "--material", "birch-plywood-3mm")
    said = [line.removeprefix("weave-cut: warning: ") for line in err.splitlines()
            if line.startswith("weave-cut: warning: ")]
    assert any("non-convex" in w for w in said)
    listed = _flat(readme.split("\nWarnings:\n")[1].split("\nFiles:\n")[0])
    for_maker = [w for w in said if "non-convex" not in w]
    assert listed == (" ".join(f"- {_flat(w)}" for w in for_maker) or "none")
    assert not re.search(r"non-convex|weave-cut convexity|faces? (is|are)", readme)
    assert len(said) == len(set(said))  # each said once on stderr too


@pytest.mark.parametrize("shape, diagonal", [("pentagon", True), ("tiling-8-4", False)])
def test_the_frame_is_measured_as_size_measures_it(shape, diagonal, tmp_path):
    readme, _ = _run(str(tmp_path / shape), shape, "--levels", "2", "--size", "40cm")
    frame = next(line for line in readme.splitlines() if line.startswith("Frame: "))
    assert ("diagonal" in frame) == diagonal
    if diagonal:
        assert frame.startswith("Frame: 400 mm diagonal, ")
    else:  # --size is the width: the box's first figure
        assert frame.startswith("Frame: 400 x ")


@pytest.mark.parametrize("formats", ["svg,dxf", "svg,dxf,lbrn2", "lbrn2"])
def test_the_cut_order_advice_fits_the_formats_written(formats, tmp_path_factory):
    folder = tmp_path_factory.mktemp("formats")
    readme, _ = _run(str(folder), "--levels", "2", "--formats", formats)
    flat = _flat(readme)
    drawn = "svg" in formats or "dxf" in formats
    assert ("Cut inner shapes first" in flat) == drawn
    assert ("open puzzle-shared-cut.lbrn2 instead" in flat) == (drawn and "lbrn2" in formats)
    assert ("--formats svg,dxf,lbrn2" in flat) == (drawn and "lbrn2" not in formats)
    if "svg" in formats:  # what the advice rests on: the SVG's cut layers share one colour
        svg = (folder / "puzzle-shared-cut.svg").read_text(encoding="utf-8")
        cuts = re.findall(r'<g id="cut-[^>]*>(.*?)</g>', svg, re.S)
        colours = {c for body in cuts for c in re.findall(r'stroke="(#[0-9a-f]{6})"', body)}
        assert len(cuts) == 3 and len(colours) == 1
    if "lbrn2" in formats:  # the project runs them as layers of their own, inner to outer
        root = ET.parse(folder / "puzzle-shared-cut.lbrn2").getroot()
        settings = {s.find("name").get("Value"): (int(s.find("priority").get("Value")),
                                                  s.find("index").get("Value"))
                    for s in root.iter("CutSetting")}
        cuts = ["cut-1-inner", "cut-2-hole", "cut-3-outer"]
        assert sorted(cuts, key=lambda n: settings[n][0]) == cuts
        assert len({settings[n][1] for n in cuts}) == 3


def test_the_lightburn_recipes_write_the_project():
    """A puzzle recipe for LightBurn (its laser, the default) writes the .lbrn2 that keeps the
    cut order; the others need not."""
    import tomllib

    found = 0
    for path in sorted(RECIPES.glob("*.toml")):
        for job in tomllib.loads(path.read_text(encoding="utf-8")).get("job", []):
            if job.get("command") == "puzzle" and job.get("laser", "lightburn") == "lightburn":
                found += 1
                assert "lbrn2" in str(job.get("formats", "")).split(","), path.name
    assert found >= 2
