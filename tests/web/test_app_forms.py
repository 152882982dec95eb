"""Each command's form against the command's own ``--help`` (an independent listing: the help
text click prints, parsed, not the parameter objects the form is built from): the same
options less the ones the web hides, their help (in the form's words: no help on a page names
a flag), defaults and choices; every control has a label."""

from __future__ import annotations

import re

import html5lib
import pytest
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.web import forms
from weavecut.web.forms import COMMANDS, web_help

HIDDEN = {"help", "output", "force", "json", "preview", "html", "list"}  # the web's own policy
OPTION = re.compile(r"^  (?:-\w, )?--([a-z][a-z0-9-]*)(.*)$")


META = re.compile(r"^ (\[[^\]]*\]|[A-Z][A-Z_ ]*?)(?=\s{2,}|$)(.*)$")


def help_options(name: str) -> tuple[dict[str, tuple[str, str]], str]:
    """Long option name -> (metavar, help on one line) from ``--help``; and the usage line."""
    text = CliRunner().invoke(cli, [name, "--help"], terminal_width=100).output
    options, current = {}, None
    for line in text.splitlines():
        found = OPTION.match(line)
        if found:
            current = found.group(1)
            meta = META.match(found.group(2))
            options[current] = [meta.group(1), meta.group(2)] if meta else ["", found.group(2)]
        elif current and line.startswith("    "):
            options[current][1] += " " + line.strip()
        else:
            current = None
    return {k: (m, " ".join(h.split())) for k, (m, h) in options.items()}, text.splitlines()[0]


def page(client, name: str):
    response = client.get(f"/{name}")
    assert response.status_code == 200
    return html5lib.parse(response.text, namespaceHTMLElements=False)


def fields(doc) -> dict:
    return {e.get("data-key"): e for e in doc.iter() if e.get("data-key")}


def text(element) -> str:
    return " ".join("".join(element.itertext()).split())


@pytest.mark.parametrize("name", COMMANDS)
def test_the_form_has_every_option_of_the_command(recording, name):
    options, usage = help_options(name)
    expected = set(options) - HIDDEN
    expected |= {"input"} if "INPUT" in usage else set()
    expected |= {"name"} if "[NAME]" in usage else set()
    expected |= {"format"} if options.get("output", ("DIRECTORY",))[0] != "DIRECTORY" else set()
    assert set(fields(page(recording, name))) == expected


@pytest.mark.parametrize("name", COMMANDS)
def test_help_defaults_and_choices_come_from_the_command(recording, name):
    options, _ = help_options(name)
    found = fields(page(recording, name))
    for key, (meta, line) in options.items():
        if key in HIDDEN:
            continue
        field = found[key]
        shown = text(field)
        head = re.sub(r"\s*\[default:.*", "", web_help(line, name))[:30]
        assert head in shown, (key, head)
        note = re.search(r"\[([^\]]+)\]$", line)  # click's "[default: 4; 2<=x<=7]"
        for part in note.group(1).split("; ") if note else ():
            if "x" in part and re.search(r"[<>]=?", part):  # a range: its bounds are shown
                for bound in re.findall(r"-?\d+(?:\.\d+)?", part):
                    assert re.search(rf"(?<![\d.]){re.escape(bound)}(?![\d.])", shown), part
                continue
            value = part.removeprefix("default: ")
            places = [field.get("data-default")] + [e.get("placeholder") for e in field.iter()]
            assert value in places or value in shown, (key, part)
        choices = re.fullmatch(r"\[([a-z0-9-]+(?:\|[a-z0-9-]+)+)\]", meta)
        if choices:
            values = {e.get("value") for e in field.iter() if e.tag in ("option", "input")
                      and e.get("value")}
            assert values == set(choices.group(1).split("|")), key


@pytest.mark.parametrize("name", [*COMMANDS, ""])
def test_every_control_has_a_label(recording, name):
    doc = page(recording, name) if name else html5lib.parse(recording.get("/").text,
                                                             namespaceHTMLElements=False)
    labelled = {e.get("for") for e in doc.iter("label")}
    parents = {c: p for p in doc.iter() for c in p}
    for control in [*doc.iter("input"), *doc.iter("select")]:
        if control.get("type") == "hidden":
            continue  # no control: a ticked-at-first box's "off" (forms.TICKED)
        inside = control
        while inside is not None and inside.tag != "label":
            inside = parents.get(inside)
        assert (control.get("id") in labelled or control.get("aria-label")
                or inside is not None), control.attrib


def test_a_page_keeps_the_values_of_its_link(recording):
    doc = page(recording, "strands?input=square-grid:3x3&size=27cm&laser-card=on"
                          "&palette=maritime-4")
    found = fields(doc)
    assert [e.get("value") for e in found["size"].iter("input")] == ["27cm"]
    assert [e.get("value") for e in found["input"].iter("option") if e.get("selected")
            is not None] == ["square-grid"]
    assert found["input"].find(".//input[@id='f-input-param']").get("value") == "3x3"
    assert found["laser-card"].find(".//input").get("checked") is not None
    assert [e.get("value") for e in found["palette"].iter("input") if e.get("checked")
            is not None] == ["maritime-4"]



@pytest.mark.parametrize("query, key", [("strands?input=squre-grid", "input"),
                                        ("strands?input=squre-grid:3x3", "input"),
                                        ("strands?cutter=silhuette", "cutter"),
                                        ("strands?input=square-grid&palette=maritme", "palette"),
                                        ("puzzle?input=pentagn", "input")])
def test_a_link_with_an_unknown_item_keeps_it_chosen_with_its_refusal(recording, query, key):
    """A mistyped item of a list is the chosen option, as given, next to its refusal: the
    browser does not fall back on the list's first item (which the script would then make)."""
    response = recording.get("/" + query)
    assert response.status_code == 400
    found = fields(html5lib.parse(response.text, namespaceHTMLElements=False))[key]
    given = query.rpartition("=")[2]
    chosen = [e.get("value") for e in found.iter() if e.get("selected") is not None
              or e.get("checked") is not None]
    assert chosen == [given]
    assert "did you mean" in text(found.find(".//p[@class='error']"))


CLI_WORDS = re.compile(r"(?<![\w-])--?[a-z][a-z0-9-]*|templates/[a-z]+|\.toml\b")
PAGES = [*COMMANDS, "strands?input=square-grid&laser-card=on&cutter=silhouette",
         "strands?input=dodecahedron&levels=1&project=sphere"]


def cli_words(doc) -> list[str]:
    """Every CLI word (``--page``, ``-o``, a preset folder, a .toml file) in what a page says
    about its fields: the hints, the chosen item's description, the preset cards, the intro,
    and the descriptions the script shows when another item is chosen."""
    said = [text(e) for e in doc.iter() if {"hint", "about", "what", "intro"}
            & set((e.get("class") or "").split())]
    said += [e.get("data-description") for e in doc.iter() if e.get("data-description")]
    return [f"{found.group(0)!r} in {t!r}" for t in said for found in CLI_WORDS.finditer(t)]


@pytest.mark.parametrize("name", PAGES)
def test_no_help_on_a_form_page_names_a_cli_flag(recording, name):
    """A maker in a browser sees fields: a help names another option by its field's label."""
    assert cli_words(page(recording, name)) == []


def test_a_flag_planted_in_a_help_is_found_and_the_cli_keeps_its_words(recording, monkeypatch):
    """The check finds a flag with no field (``-q``, ``--json``); an option with a field is
    named by its label; ``--help`` at a terminal is click's own text, flags and all."""
    size = next(p for p in forms.command("strands").params if forms.key(p) == "size")
    monkeypatch.setattr(size, "help", size.help + " Quiet with -q; see --json and --page.")
    forms.fields.cache_clear()
    try:
        found = cli_words(page(recording, "strands"))
        assert [f.split(" in ")[0] for f in found] == ["'-q'", "'--json'"]
        assert "see --json and “Page”." in found[0]
    finally:
        monkeypatch.undo()
        forms.fields.cache_clear()
    terminal = " ".join(CliRunner().invoke(cli, ["strands", "--help"]).output.split())
    for words in ("(with --laser-card: the instructions' pages; --material sets the card's)",
                  "(templates/cutters: silhouette, cricut, scanncut, or a .toml file)",
                  "beside -o (PAGE-cut.svg, .dxf;", "-o is a folder of cut sheets"):
        assert words in terminal


def test_a_drawings_level_shows_no_default_the_command_does_not_use(served):
    """For an uploaded drawing the puzzle chooses the level: its field shows that, not the
    pentagon's default 4; for a built-in input it shows the default."""
    from pathlib import Path

    heart = Path(__file__).resolve().parents[2] / "templates" / "recipes" / "heart.svg"
    sent = served.post("/upload", content=heart.read_bytes())
    assert sent.status_code == 200, sent.text
    upload = "upload:" + sent.json()["id"]
    recording = served
    for query, shown in ((f"puzzle?input={upload}", "chosen for the drawing"),
                         ("puzzle", "4")):
        box = fields(page(recording, query))["levels"].find(".//input")
        assert box.get("placeholder") == shown, query
    field = fields(page(recording, "puzzle"))["levels"]
    assert field.get("data-drawing") == "chosen for the drawing"
