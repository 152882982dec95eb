"""The kit's formats: the file format of a command that writes a file (``format``: the
suffixes its -o takes, as its --help names them) and the files per sheet of one that writes a
folder (``formats``, the CLI's --formats), carried in the link; the ZIP holds the CLI's files
for those options, byte for byte, and the command line shown is the one that writes them."""

from __future__ import annotations

import io
import re
import zipfile

import pytest

from weavecut.web import forms

from tests.web.test_app_forms import help_options
from tests.web_app import cli_files

pytestmark = pytest.mark.slow  # whole kits in every format, against the command line's files


@pytest.mark.parametrize("name", forms.COMMANDS)
def test_the_formats_offered_are_the_ones_the_help_names(name):
    options, _ = help_options(name)
    field = forms.format_field(name)
    meta, line = options["output"]
    if meta == "DIRECTORY":
        assert field is None
        return
    offered = [c.value for c in field.choices]
    named = re.findall(r"\.([a-z0-9]+)\b", line.split("; with")[0])
    assert set(offered) == set(named) - {"lbrn2"}, (offered, line)


def name_has_html(url: str) -> bool:
    return not url.startswith(("subdivide", "figure"))


def _kit(client, url: str) -> dict[str, bytes]:
    response = client.get(url)
    assert response.status_code == 200, response.text
    with zipfile.ZipFile(io.BytesIO(response.content)) as kit:
        return {n: kit.read(n) for n in kit.namelist()}


KITS = [  # (query, a file the kit holds, a suffix it must not hold)
    ("strands.zip?input=square-grid&size=27cm&format=svg", "strands.svg", ".pdf"),
    ("subdivide.zip?input=pentagon&levels=2&format=dxf", "subdivide.dxf", ".svg"),
    ("strands.zip?input=square-grid&laser-card=on&palette=maritime-4&formats=dxf"
     "&formats=lbrn2", "strands/strands-card-01-0b3c5d.lbrn2", "0b3c5d.svg"),
    ("puzzle.zip?levels=2&formats=lbrn2", "puzzle/puzzle-shared-cut.lbrn2", "cut.dxf"),
]


@pytest.mark.parametrize(("url", "holds", "not_held"), KITS, ids=[k[1] for k in KITS])
def test_the_kit_is_the_clis_files_in_the_formats_chosen(served, tmp_path, url, holds,
                                                         not_held):
    files = _kit(served, "/" + url)
    assert holds in files, sorted(files)
    assert not any(n.endswith(not_held) for n in files), sorted(files)
    out = tmp_path / "cli"
    out.mkdir()
    made = cli_files(files["index.html"].decode(), out)
    if not name_has_html(url):  # no --html: the job writes the page (test_jobs_kitpage)
        made["index.html"] = files["index.html"]
    assert made == files
    name, _, query = url.partition(".zip?")
    shown = served.get(f"/{name}/check?{query}").json()["command_line"]
    assert shown.split(" -o ")[1] == holds.split("/")[0]  # the command line says the same file


@pytest.mark.parametrize(("url", "field", "says"), [
    ("/strands/check?input=square-grid&format=dxf", "format", "unknown format 'dxf'"),
    ("/strands/check?input=square-grid&laser-card=on&format=svg", "format", "formats"),
    ("/figure/check?name=level-image&format=svg", "format", "use png"),
    ("/puzzle/check?format=svg", "form", "unknown parameter 'format'"),
])
def test_a_format_the_kit_cannot_have_is_refused_next_to_its_field(recording, url, field,
                                                                   says):
    response = recording.get(url)
    assert response.status_code == 400
    assert says in response.json()["errors"][field]


def test_files_per_sheet_without_the_laser_card_get_the_commands_message(served):
    response = served.get("/strands/summary.json?input=square-grid&formats=svg")  # the kit
    assert response.status_code == 400
    assert "“Laser-cut card” ticked" in response.text and response.headers["x-field"] == "formats"


def test_a_raster_figure_is_png_and_the_link_keeps_the_choice(recording):
    found = recording.get("/figure/check?name=level-image").json()
    assert found["command_line"].endswith("-o level-image.png")
    page = recording.get("/weave?input=square-grid&format=pdf").text
    assert re.search(r'<option value="pdf"[^>]*selected', page)
    # the file format is hidden with the laser card, its files per sheet without it
    card = recording.get("/strands?input=square-grid&laser-card=on").text
    assert re.search(r'data-needs="!laser-card" hidden data-key="format"', card)
    assert re.search(r'data-needs="laser-card" data-key="formats"', card)
    paper = recording.get("/strands?input=square-grid").text
    assert re.search(r'data-needs="laser-card" hidden data-key="formats"', paper)


def test_a_format_the_input_cannot_take_is_refused_next_to_the_format(served):
    response = served.get("/weave/summary.json?input=square-grid&levels=1&format=obj")
    assert response.status_code == 422 and "needs a surface in space" in response.text
    assert response.headers["x-field"] == "format"


def test_the_default_format_beside_the_laser_card_is_no_choice(recording):
    # a form sent without its script sends the hidden select's default too
    found = recording.get("/strands/check?input=square-grid&laser-card=on&format=pdf").json()
    assert found["ok"] and found["command_line"].endswith("--laser-card -o strands")


CLI_RUNS = {  # a form with a formats field: the CLI run without --formats, and its files' stem
    "puzzle": (["puzzle", "--levels", "2", "--mode", "shared"], "puzzle-shared-cut"),
    "strands": (["strands", "square-grid", "--laser-card"], "strands-card-01-"),
}


@pytest.mark.parametrize("name", sorted(CLI_RUNS))
def test_the_formats_ticked_at_first_are_what_the_cli_writes_without_them(recording, tmp_path,
                                                                          name):
    """The form starts from the command's own defaults (issue 29: all boxes unticked while
    the CLI writes svg and dxf): the boxes ticked on a fresh page are the suffixes the CLI
    writes when --formats is not given, and each box says what its file is for."""
    from click.testing import CliRunner

    from weavecut import presets
    from weavecut.cli import cli

    from tests.web.test_app_forms import fields, page, text

    field = fields(page(recording, name))["formats"]
    boxes = [e for e in field.iter("input") if e.get("type") == "checkbox"]
    ticked = {e.get("value") for e in boxes if e.get("checked") is not None}
    args, stem = CLI_RUNS[name]
    result = CliRunner().invoke(cli, [*args, "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    written = {p.suffix[1:] for p in (tmp_path / "out").iterdir() if p.name.startswith(stem)}
    assert ticked == written & set(presets.LASER_FORMATS) and ticked
    labels = [text(e) for e in field.iter("label")]
    assert len(labels) == len(boxes) and all(":" in t or "(." in t for t in labels)
