"""The command line's shared parts where they run, against what the README and the presets say
(#34: mutants no test killed). The option groups every command takes are built anew here: the
commands build theirs once, at import, where mutation testing cannot change them."""

from __future__ import annotations

import json
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.cli.common import (Length, complete_preset, drawing_options, html_option,
                                 reports_errors)
from weavecut.cli.mesh_commands import level_options

ROOT = Path(__file__).resolve().parents[1]


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def group(decorate) -> click.Command:
    return click.command("stub")(decorate(lambda **values: None))


def options(command: click.Command) -> dict[str, click.Option]:
    return {p.opts[0]: p for p in command.params}


@pytest.mark.parametrize("decorate", [drawing_options, html_option, level_options(),
                                      level_options(6, with_scheme=False)],
                         ids=["drawing", "html", "levels", "levels-no-scheme"])
def test_every_option_of_a_group_has_a_sentence_of_help_and_a_default_it_offers(decorate):
    command = group(decorate)
    for option in command.params:
        assert option.help and option.help[0].isupper() and option.help.endswith("."), \
            option.opts
        if isinstance(option.type, click.Choice):
            assert option.default in option.type.choices, option.opts


def test_the_drawing_options_are_the_readmes():
    """README "Drawings as input": --layer NAME, --flatten (default 0.2 mm), --mesh KIND (hex,
    quad, voronoi, tri) with about --cell (default: about 60 faces)."""
    found = options(group(drawing_options))
    assert [p.opts for p in found.values()] == [["--flatten"], ["--layer"], ["--mesh"],
                                                ["--cell"]]
    assert found["--flatten"].type.convert(found["--flatten"].default, None, None) == 0.2
    assert {"hex", "quad", "voronoi", "tri"} <= set(found["--mesh"].type.choices)
    assert all(p.help.startswith("Drawings: ") for p in found.values())
    assert found["--cell"].help.endswith("[default: about 60 faces].")
    assert not any(p.expose_value for p in found.values())  # they go to load_mesh


def test_the_html_option_says_what_the_page_shows():
    (option,) = group(html_option).params
    assert option.opts == ["--html"] and option.metavar == "PAGE"
    assert option.help.startswith("Also write an HTML page that shows every output")


def test_the_level_options_take_the_papers_levels_and_snub_choices():
    found = options(group(level_options(6, with_scheme=False)))
    assert list(found) == ["--levels", "--no-smooth", "--chirality", "--centre",
                           "--allow-nonconvex"]
    assert (found["--levels"].default, found["--chirality"].default,
            found["--centre"].default) == (6, "left", "vertex")
    levels = found["--levels"].type
    assert levels.convert("0", None, None) == 0 and levels.convert("40", None, None) == 40
    for refused in ("-1", "41"):
        with pytest.raises(click.BadParameter):
            levels.convert(refused, None, None)


@pytest.mark.parametrize("kind, start, names", [
    ("palettes", "mar", ["maritime-12", "maritime-4"]),
    ("materials", "card", ["card-300gsm", "card-300gsm-12in", "card-300gsm-letter"]),
])
def test_a_preset_completes_to_the_names_of_its_kind_then_files(kind, start, names):
    offered = complete_preset(kind)(None, None, start)
    assert sorted(p.stem for p in (ROOT / "templates" / kind).glob(f"{start}*.toml")) == names
    assert [(c.value, c.type) for c in offered] == [(n, "plain") for n in names] + [
        (start, "file")]


def test_a_geometry_error_from_shapely_is_a_one_line_error():
    from shapely.errors import GEOSException

    @reports_errors
    def command():
        raise GEOSException("TopologyException: side location conflict")

    with pytest.raises(click.ClickException) as error:
        command()
    assert error.value.message.startswith("the geometry cannot be laid out (TopologyException")


def test_the_web_apps_cache_is_under_xdg_cache_home_or_home(tmp_path, monkeypatch):
    from weavecut.cli.serve_command import default_cache

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert default_cache() == tmp_path / "weave-cut" / "web"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert default_cache() == tmp_path / "home" / ".cache" / "weave-cut" / "web"


def test_a_length_that_is_no_length_names_its_option_and_a_negative_kerf_shows_the_usage():
    option = click.Option(["--margin"], type=Length())
    with pytest.raises(click.BadParameter) as error:
        option.type.convert(True, option, None)
    assert error.value.format_message() == "Invalid value for '--margin': True is not a length"
    result = run("puzzle", "--levels", "2", "--kerf=-1mm", "-o", "kit")
    assert result.exit_code == 2 and result.output.startswith("Usage: cli puzzle [OPTIONS]")
    assert result.output.splitlines()[-1] == ("Error: Invalid value for '--kerf': '-1mm' must "
                                              "be >= 0 mm")


def test_a_single_format_is_named_alone_and_a_window_may_be_wider_than_high(tmp_path):
    from weavecut.cli.analysis_commands import WindowType

    result = run("levels", "pentagon", "-n", "1", "-o", tmp_path / "x.svg")
    assert result.output.splitlines()[-1] == ("Error: Invalid value for '-o': unknown format "
                                              "'.svg'; use .png")
    assert WindowType().convert("0,0,5,1", None, None) == (0.0, 0.0, 5.0, 1.0)
    with pytest.raises(click.BadParameter):
        WindowType().convert("0,2,1,1", None, None)


def test_a_builds_page_gives_each_job_as_its_recipe_says_it(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text('[[job]]\ncommand = "weave"\ninput = "square-grid"\nlevels = 1\n'
                      'palette = "okabe-ito"\noutput = "weave.svg"\n')
    result = run("build", recipe, "-o", tmp_path / "out")
    assert result.exit_code == 0, result.output
    page = (tmp_path / "out" / "index.html").read_text(encoding="utf-8")
    assert "<code>weave-cut weave square-grid --levels 1 --palette okabe-ito -o weave.svg" \
           "</code>" in page


def test_a_cricut_kits_json_names_its_cutter_and_the_print_images_it_wrote(tmp_path):
    out = tmp_path / "cc.pdf"
    result = run("strands", "square-grid:2x2", "--tile-size", "20mm", "--cutter", "cricut",
                 "--json", "-o", out)
    assert result.exit_code == 0, result.output
    cutter = json.loads(result.stdout)["cutter"]
    assert cutter["name"] == "cricut"
    assert sorted(cutter["print_images"]) == sorted(str(p) for p in
                                                    tmp_path.glob("cc-*-print.svg")) != []
