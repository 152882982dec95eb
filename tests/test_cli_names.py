"""What a person types is checked one way everywhere (issue #29, item 5), over every command,
option and preset kind found by walking them, so one added later is covered:

- a length carries its unit: every option of a length type (``Length``, ``PageSize``), the same
  options as recipe keys, and every length field of every preset kind; '300' is refused with
  the number shown with units ('300mm', '300cm', '300in'), zero alone is taken;
- every name gets a "did you mean": commands, options, the choices of every option, built-in
  inputs, figures, presets of every kind, page sizes, output formats, drawing layers.
"""

from __future__ import annotations

import re

import click
import pytest

from weavecut import inputs, presets
from weavecut.cli import cli
from weavecut.cli.common import Choice, Length, PageSize
from weavecut.cli.recipe import Planner
from weavecut.figures import gallery
from weavecut.schema import Length as LengthField
from weavecut.schema import Sheet, Table

from .test_cli_outputs import ALL
from .untrusted.helpers import files_under, refused, run
from .untrusted.strategies import toml_table

EXAMPLES = __import__("pathlib").Path(__file__).resolve().parents[1] / "examples"
LENGTH_TYPES = (Length, PageSize)
BARE = {Length: (300, "'300' has no unit: write it like '300mm', '300cm' or '300in'"),
        PageSize: ("600x400", "'600x400' has no unit: write it like '600x400mm'")}


def params(kind) -> list[tuple[str, click.Parameter]]:
    return [(n, p) for n in sorted(cli.commands) for p in cli.commands[n].params
            if isinstance(p.type, kind)]


LENGTH_OPTIONS = params(LENGTH_TYPES)
# a job of each command but the one key under test: (input, output)
JOBS = {"subdivide": ("pentagon", "s.svg"), "stats": ("pentagon", "s.txt"),
        "weave": ("pentagon", "w.svg"), "puzzle": ("pentagon", "kit"),
        "strands": ("square-grid", "s.pdf"), "fractal": ("pentagon", "f.svg"),
        "levels": ("pentagon", "l.png"), "convexity": ("pentagon", "c.svg"),
        "figure": ("z-triplet", "f.svg")}
# numeric options whose help speaks of sizes but which are no lengths
NOT_LENGTHS = {("levels", "size"): "pixels", ("levels", "tile_size"): "pixels",
               ("puzzle", "speed"): "a speed, mm/s"}


def bare(param) -> tuple[object, str]:
    return next(v for t, v in BARE.items() if isinstance(param.type, t))


@pytest.mark.parametrize("command,param", LENGTH_OPTIONS,
                         ids=[f"{n}-{p.name}" for n, p in LENGTH_OPTIONS])
def test_every_length_option_needs_its_unit(command, param):
    value, message = bare(param)
    with pytest.raises(click.BadParameter, match=re.escape(message)):
        param.type.convert(str(value), param, None)
    if isinstance(param.type, Length):
        assert param.type.convert("3cm", param, None) == 30.0
        assert param.type.convert("1.5in", param, None) == pytest.approx(38.1)
    else:
        assert param.type.convert("600x400mm", param, None) == (600.0, 400.0)
        assert param.type.convert("8.5x11in", param, None) == pytest.approx((215.9, 279.4))


@pytest.mark.parametrize("command,param", LENGTH_OPTIONS,
                         ids=[f"{n}-{p.name}" for n, p in LENGTH_OPTIONS])
def test_every_length_key_of_a_recipe_needs_its_unit(tmp_path, command, param):
    """A number in a recipe is as bare as one on the command line (TOML 300 or '600x400')."""
    key = next(k for k, p in Planner.options(cli.commands[command]).items() if p is param)
    source, output = JOBS[command]
    value, message = bare(param)
    (tmp_path / "r.toml").write_text("[[job]]\n" + toml_table(
        {"command": command, "input": source, "output": output, key: value}))
    refused(run("build", tmp_path / "r.toml", "-o", tmp_path / "out", "--dry-run"),
            "job 1", key, message)
    assert files_under(tmp_path) == {"r.toml"}


def test_the_issues_two_sizes_are_refused_alike(tmp_path):
    """Issue #29: `puzzle --size 300` was taken as 300 mm, `strands --size 23` refused."""
    for args in (["puzzle", "--size", "300", "-o", tmp_path / "p"],
                 ["strands", "square-grid", "--size", "23", "-o", tmp_path / "s.pdf"]):
        refused(run(*args), "Invalid value for '--size'", "has no unit", status=(2,))
    assert run("subdivide", "pentagon", "--size", "0", "-o", tmp_path / "x.svg").exit_code == 2
    assert files_under(tmp_path) == set()


def test_every_numeric_option_that_speaks_of_a_size_is_a_length_or_says_why_not():
    """A length typed as a plain number (a new --gap FLOAT "in mm") would take '3' as 3 mm:
    such an option is found by its help and fails here until it is a Length."""
    numeric = (click.types.IntParamType, click.types.FloatParamType)
    words = re.compile(r"\b(mm|cm|side|size|width|height|distance|margin|kerf|diameter|length|"
                       r"thickness|gap|radius|spacing|offset|frame)\b",
                       re.I)
    found = {(n, p.name) for n in cli.commands for p in cli.commands[n].params
             if isinstance(p.type, numeric) and words.search(getattr(p, "help", "") or "")}
    assert found == set(NOT_LENGTHS)


def length_fields(table: Table, where: str = ""):
    for key, field in table.fields.items():
        if isinstance(field, Table):
            yield from length_fields(field, f"{where}{key}.")
        elif isinstance(field, (LengthField, Sheet)):
            yield f"{where}{key}", field


PRESET_LENGTHS = [(kind, key, field) for kind, table in sorted(presets.schemas().items())
                  for key, field in length_fields(table)]


@pytest.mark.parametrize("kind,key,field", PRESET_LENGTHS,
                         ids=[f"{k}-{n}" for k, n, _ in PRESET_LENGTHS])
def test_every_length_of_every_preset_kind_needs_its_unit(kind, key, field):
    if isinstance(field, Sheet):
        assert "has no unit" in field.problem("600x400")
        assert field.problem("600x400mm") is None
    else:
        assert "has no unit" in field.problem(3)
        assert "has no unit" in field.problem("3")
        assert field.problem("1mm") is None and field.problem(0) in (None, field.bounds(0, "0"))


def test_the_walk_finds_the_lengths_of_nested_preset_tables():
    assert {("laser", "cut.width"), ("pages", "width"), ("materials", "kerf"),
            ("materials", "sheet"), ("cutters", "min_feature")} <= {
        (k, n) for k, n, _ in PRESET_LENGTHS}


def test_every_shipped_preset_and_recipe_reads_with_its_units(tmp_path):
    root = presets.templates_dir()
    for kind in sorted(p.name for p in root.iterdir() if p.is_dir() and p.name[0] != "_"):
        for name in presets.names(kind):
            presets.load(kind, name)
    for recipe in sorted([*(root / "recipes").glob("*.toml"), *EXAMPLES.glob("*.toml")]):
        result = run("build", recipe, "-o", tmp_path / recipe.stem, "--dry-run")
        assert result.exit_code == 0, (recipe, result.output)


# --- did you mean -----------------------------------------------------------------------------

def typo(word: str) -> str:
    """A slip of the finger: the last letter twice."""
    return word + word[-1]


def meant(text: str, word: str) -> bool:
    """Whether ``text`` suggests ``word`` (click's own 'Did you mean' or ours)."""
    return re.search(rf"did you mean[^\n]*{re.escape(word)}", text, re.I) is not None


@pytest.mark.parametrize("name", sorted(cli.commands))
def test_every_command_name(name):
    result = run(typo(name))
    assert result.exit_code == 2 and meant(result.output, name), result.output


OPTIONS = [(n, o) for n in sorted(cli.commands) for p in cli.commands[n].params
           for o in p.opts if o.startswith("--") and len(o) > 4]


@pytest.mark.parametrize("command,option", OPTIONS, ids=[f"{n}{o}" for n, o in OPTIONS])
def test_every_option_name(command, option):
    result = run(command, typo(option))
    assert result.exit_code == 2 and meant(result.output, option), result.output


CHOICES = [(n, p, c) for n, p in params(click.Choice) for c in p.type.choices]


@pytest.mark.parametrize("command,param,choice", CHOICES,
                         ids=[f"{n}-{p.name}-{c}" for n, p, c in CHOICES])
def test_every_choice_of_every_option(command, param, choice):
    assert isinstance(param.type, Choice)  # weave-cut's, which says the nearest
    with pytest.raises(click.BadParameter) as refusal:
        param.type.convert(typo(choice), param, None)
    assert meant(refusal.value.message, f"'{choice}'"), refusal.value.message


def test_a_choice_on_the_command_line():
    result = run("subdivide", "pentagon", "--scheme", "lop", "-o", "x.svg")
    refused(result, "'lop' is not one of", "(did you mean 'loop'?)", status=(2,))


@pytest.mark.parametrize("name", sorted(inputs.INPUTS))
def test_every_built_in_input(name):
    with pytest.raises(Exception) as refusal:
        inputs.get(typo(name))
    assert meant(str(refusal.value), f"'{name}'"), refusal.value


def test_the_issues_misspelt_input(tmp_path):
    refused(run("strands", "squre-grid", "-o", tmp_path / "s.pdf"),
            "unknown input 'squre-grid' (did you mean 'square-grid'?)")
    assert files_under(tmp_path) == set()


@pytest.mark.parametrize("name", sorted(gallery.FIGURES))
def test_every_figure(tmp_path, name):
    result = run("figure", typo(name), "-o", tmp_path / "f.svg")
    assert result.exit_code == 2 and meant(result.output, f"'{name}'"), result.output


PRESET_NAMES = [(kind, name) for kind in sorted(
    p.name for p in presets.templates_dir().iterdir() if p.is_dir() and p.name[0] != "_")
    for name in presets.names(kind)]


@pytest.mark.parametrize("kind,name", PRESET_NAMES, ids="-".join)
def test_every_preset_of_every_kind(kind, name):
    with pytest.raises(presets.PresetError) as refusal:
        presets.find(kind, typo(name))
    assert meant(str(refusal.value), f"'{name}'"), refusal.value


@pytest.mark.parametrize("name", ["a4", "a3", "letter", *presets.names("pages")])
def test_every_page_size_name(name):
    page = next(p for _, p in params(PageSize))
    with pytest.raises(click.BadParameter) as refusal:
        page.type.convert(typo(name), page, None)
    assert meant(refusal.value.message, f"'{name}'"), refusal.value.message


FORMATS = sorted(k for k in ALL if k[2] != "folder" and k[1] != "html")  # --html is HTML


@pytest.mark.parametrize("key", FORMATS, ids="-".join)
def test_every_output_format(tmp_path, key):
    name, args = ALL[key]
    (tmp_path / "t").mkdir()
    path = tmp_path / (name + name[-1])
    result = run(*[a.format(path=path, t=tmp_path / "t") for a in args])
    refused(result, f"(did you mean '{path.suffix[:-1]}'?)", status=(2,))
    assert files_under(tmp_path) == set()


@pytest.mark.parametrize("drawing,layer", [("plate.dxf", "GRID"), ("tiles.svg", "Triangles")])
def test_a_drawing_layer(tmp_path, drawing, layer):
    result = run("subdivide", EXAMPLES / drawing, "--layer", typo(layer), "-o",
                 tmp_path / "x.svg")
    assert result.exit_code == 1 and meant(result.output, f"'{layer}'"), result.output
