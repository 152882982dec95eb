"""The schema's list, table and recipe-value checks that no test failed without (each disabled
once by ``tests/hand_audit/guards.py``, #34): a document a preset or recipe file could hold,
refused naming the file, the key and what is wrong, and the same document mended accepted."""

from __future__ import annotations

import pytest

from weavecut import presets
from weavecut.presets import PresetError
from weavecut.schema import RECIPE, SchemaError

from .helpers import files_under, refused, run

JOB = {"command": "stats", "input": "pentagon"}

# kind ("recipe" or a preset kind), a bad document, what the error says, the mended document
CASES = [
    ("palettes", {"colours": "#ffffff"}, "p.toml: colours: expected a list, got a string",
     {"colours": ["#ffffff"]}),
    ("palettes", {"colours": []}, "p.toml: colours: needs 1 to 256 items, has 0",
     {"colours": ["#000000"]}),
    ("palettes", {"colours": ["#ffffff", "white"]},
     "p.toml: colours: item 2: 'white' is not a #rrggbb colour",
     {"colours": ["#ffffff", "#000000"]}),
    ("palettes", {"colours": ["#ffffff"], "families": [["#ffffff"]]},
     "p.toml: needs exactly one of 'colours' or 'families'", {"families": [["#ffffff"]]}),
    ("palettes", {"name": "two colours"}, "p.toml: needs exactly one of 'colours' or 'families'",
     {"name": "two colours", "colours": ["#ffffff"]}),
    ("laser", {r: {"colour": "#000000"} for r in ("cut", "score")} | {"engrave": "#000000"},
     "p.toml: [engrave] expected a table, got a string",
     {r: {"colour": "#000000"} for r in ("cut", "score", "engrave")}),
    ("recipe", {"job": {"command": "stats"}}, "r.toml: job: expected [[job]] tables",
     {"job": [JOB]}),
    ("recipe", {"job": [JOB, "stats"]}, "r.toml: job 2: expected a [[job]] table, got a string",
     {"job": [JOB, JOB]}),
    ("recipe", {"job": [{"input": "pentagon"}]}, 'r.toml: job 1: needs command = "NAME"',
     {"job": [JOB]}),
    ("recipe", {"job": [{**JOB, "input": "pen\x00tagon"}]},
     "r.toml: job 1 input: contains a NUL character", {"job": [JOB]}),
    ("recipe", {"job": [{**JOB, "levels": {"a": 1}}]},
     "r.toml: job 1 levels: expected a string, number or boolean, got a table",
     {"job": [{**JOB, "levels": 1}]}),
    ("recipe", {"job": [{**JOB, "formats": ["svg"] * 101}]},
     "r.toml: job 1 formats: needs 0 to 100 items, has 101",
     {"job": [{**JOB, "formats": ["svg"] * 100}]}),
    ("recipe", {"job": [{**JOB, "formats": ["svg", {"a": 1}]}]},
     "r.toml: job 1 formats: item 2: expected a string, number or boolean, got a table",
     {"job": [{**JOB, "formats": ["svg", "dxf"]}]}),
]


def check(kind: str, doc: dict) -> None:
    if kind == "recipe":
        RECIPE.check(doc, "r.toml")
    else:
        presets.schemas()[kind].check(doc, "p.toml", PresetError)


@pytest.mark.parametrize("kind, doc, says, mended", CASES,
                         ids=[f"{k}-{s.split(': ', 1)[1][:30]}" for k, _, s, _ in CASES])
def test_a_bad_document_is_refused_by_file_key_and_problem(kind, doc, says, mended):
    with pytest.raises(SchemaError) as caught:
        check(kind, doc)
    assert str(caught.value) == says or str(caught.value).startswith(says)
    check(kind, mended)  # the same document, mended: accepted


@pytest.mark.parametrize("line, says", [
    ('input = "pen\\u0000tagon"', "job 1 input: contains a NUL character"),
    ("levels = {deep = 1}", "job 1 levels: expected a string, number or boolean, got a table"),
])
def test_a_recipe_value_no_option_takes_is_one_line_and_writes_nothing(tmp_path, line, says):
    recipe = tmp_path / "r.toml"
    input_ = "" if line.startswith("input") else 'input = "pentagon"\n'
    recipe.write_text(f'[[job]]\ncommand = "stats"\n{input_}{line}\n')
    refused(run("build", recipe, "-o", tmp_path / "out"), "r.toml", says)
    assert files_under(tmp_path) == {"r.toml"}
