"""Each command's form against the command's own ``--help`` (an independent listing: the help
text click prints, parsed, not the parameter objects the form is built from): the same
options less the ones the web hides, their help, defaults and choices; every control has a
label."""

from __future__ import annotations

import re

import html5lib
import pytest
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.web.forms import COMMANDS

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
        head = re.sub(r"\s*\[default:.*", "", line)[:30]
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
