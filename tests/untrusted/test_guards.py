"""Guards for untrusted input that no other test failed without (each removed once, #34): the
schema's text, whole-number, choice and recipe bounds, the units' unknown unit, boolean and
page-size shape, the built-in inputs' grid size and parameter. Each case states the value a
file or an option could carry and what must be said about it."""

from __future__ import annotations

import pytest

from weavecut import inputs, presets, units
from weavecut.errors import MeshError
from weavecut.presets import PresetError
from weavecut.schema import RECIPE, SchemaError

from .helpers import refused, run

MATERIAL = {"thickness": "3mm", "kerf": "0.15mm", "sheet": "1300x900mm", "cut_speed": 20.0}
LASER = {r: {"colour": "#000000"} for r in ("cut", "score", "engrave")}
CUTTER = {"marks": "corners", "inset": "10mm", "length": "20mm", "thickness": "1mm",
          "clearance": "1mm", "min_feature": "1mm"}

# kind, a shipped-shaped document with one value changed, what the error says
PRESET_CASES = [
    ("palettes", {"colours": ["#ffffff"], "name": "n" * 81}, "name: longer than 80 characters"),
    ("palettes", {"families": [["#ffffff"]], "family_names": ["f" * 41]},
     "family_names: item 1: longer than 40 characters"),
    ("materials", {**MATERIAL, "cut": {"power": 50, "passes": 1.5}},
     "passes: expected a whole number, got a number"),
    ("materials", {**MATERIAL, "cut": {"power": 50, "passes": "2"}},
     "passes: expected a whole number, got a string"),
    ("laser", {**LASER, "formats": ["pdf"]}, "formats: item 1: 'pdf' is not one of svg, dxf"),
    ("cutters", {**CUTTER, "marks": "circles"}, "marks: 'circles' is not one of"),
    ("cutters", {**CUTTER, "marks": ["corners"]}, "marks: ['corners'] is not one of"),
]


@pytest.mark.parametrize("kind, doc, needle", PRESET_CASES,
                         ids=[f"{k}-{n.split(':')[0]}" for k, _, n in PRESET_CASES])
def test_preset_values_are_bounded(kind, doc, needle):
    with pytest.raises(PresetError, match=needle.replace("[", r"\[").replace("]", r"\]")):
        presets.schemas()[kind].check(doc, "p.toml", PresetError)
    fixed = {**doc}
    for key in ("name", "family_names"):
        fixed.pop(key, None)
    if kind == "materials":
        fixed["cut"] = {"power": 50, "passes": 2}
    if kind == "laser":
        fixed["formats"] = ["svg"]
    if kind == "cutters":
        fixed["marks"] = "corners"
    presets.schemas()[kind].check(fixed, "p.toml", PresetError)  # the same document, mended


def test_recipe_strings_and_job_counts_are_bounded():
    job = {"command": "stats", "input": "pentagon"}
    RECIPE.check({"job": [job] * 1000}, "r.toml")
    with pytest.raises(SchemaError, match="more than 1000 jobs"):
        RECIPE.check({"job": [job] * 1001}, "r.toml")
    RECIPE.check({"job": [{**job, "input": "p" * 1000}]}, "r.toml")
    with pytest.raises(SchemaError, match="job 1 input: longer than 1000 characters"):
        RECIPE.check({"job": [{**job, "input": "p" * 1001}]}, "r.toml")
    with pytest.raises(SchemaError, match="job 1 input: item 1: longer than 1000"):
        RECIPE.check({"job": [{**job, "input": ["p" * 1001]}]}, "r.toml")


@pytest.mark.parametrize("value", ["3ft", "2yd", "1km", "5pc"])
def test_an_unknown_unit_is_named(value):
    for read in (units.to_mm, units.length):
        with pytest.raises(ValueError, match=f"unknown unit '{value.lstrip('0123456789')}'"):
            read(value)


def test_an_unknown_unit_in_an_option_is_one_line(tmp_path):
    refused(run("subdivide", "pentagon", "--size", "3ft", "-o", tmp_path / "p.svg"),
            "unknown unit 'ft'", status=(2,))
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("value", [True, False])
def test_a_boolean_is_no_length(value):
    """TOML's ``kerf = false`` is no zero length (False == 0 in Python)."""
    with pytest.raises(ValueError, match="is not a length"):
        units.length(value)


@pytest.mark.parametrize("value, needle", [
    ("200x300x400mm", "'200x300x400mm' is not a page size"),
    ("1x2x3", "'1x2x3' is not a page size"),
    ("100x50", "'100x50' has no unit: write it like '100x50mm'"),
    ("100cmx50", "'100cmx50' has no unit: write it like '100cmx50mm'"),
])
def test_page_size_shapes(value, needle):
    with pytest.raises(ValueError, match=needle):
        units.page_size(value)


@pytest.mark.parametrize("spec", ["square-grid:0x3", "square-grid:3x0", "square-grid:2001x1",
                                  "triangle-grid:1x2001", "hex-grid:-1x2"])
def test_grid_sizes_are_bounded(spec):
    with pytest.raises(MeshError, match=r"size must be from 1x1 to 2000x2000"):
        inputs.get(spec)
    inputs.get(spec.split(":")[0] + ":2x2")


@pytest.mark.parametrize("spec", ["pentagon:5", "cube:2", "dodecahedron:x"])
def test_a_parameter_for_an_input_that_takes_none_is_refused(spec):
    name, _, param = spec.partition(":")
    assert not inputs.INPUTS[name].parameter
    with pytest.raises(MeshError, match=f"input '{name}' takes no parameter, got '{param}'"):
        inputs.get(spec)
