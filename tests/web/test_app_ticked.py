"""A flag the web form ticks at first though the command's default is off (``forms.TICKED``:
the puzzle's Numbers, since a maker assembles the pieces by their numbers): the page shows it
ticked and says why, a kit asked with no value gets it, an unticked box is sent as "off" (by
the script, or by the form's hidden field without a script) and makes a kit without it; every
other flag starts as its command starts. Read from the page's HTML (html5lib) and from the
arguments of the jobs the app hands its queue."""

from __future__ import annotations

import html5lib
import pytest

from weavecut.web import forms, queries


def box(client, url: str):
    """The field of the page at ``url`` whose key is in its URL's path, and the page."""
    response = client.get(url)
    assert response.status_code == 200, response.text
    doc = html5lib.parse(response.text, namespaceHTMLElements=False)
    return doc


def field(doc, key: str):
    (found,) = [e for e in doc.iter() if e.get("data-key") == key]
    return found


def ticked(doc, key: str) -> bool:
    (checkbox,) = [e for e in field(doc, key).iter("input") if e.get("type") == "checkbox"]
    return checkbox.get("checked") is not None


def job_args(client, query: str) -> tuple[str, ...]:
    assert client.get(f"/puzzle/preview.svg?{query}").status_code == 200
    return client.queue.specs[-1].args


def test_the_puzzle_form_ticks_numbers_and_says_why(recording):
    doc = box(recording, "/puzzle")
    assert ticked(doc, "numbers")
    hint = " ".join("".join(field(doc, "numbers").itertext()).split())
    assert "Ticked at first here" in hint and "number" in hint
    cmdline = "".join(next(e for e in doc.iter() if e.get("id") == "cmdline").itertext())
    assert "--numbers" in cmdline.split()
    assert "--numbers" in job_args(recording, "")


@pytest.mark.parametrize("query, on", [("numbers=off", False), ("numbers=on", True),
                                       ("numbers=off&numbers=on", True), ("", True)])
def test_an_unticked_box_is_sent_as_off_and_makes_a_kit_without_numbers(recording, query, on):
    # "off, then on" is the form sent without its script with the box ticked: the hidden
    # field's "off" comes first, the box's "on" after it
    assert ("--numbers" in job_args(recording, query)) == on
    assert ticked(box(recording, f"/puzzle?{query}"), "numbers") == on
    assert ("--numbers" in queries.parse("puzzle", [tuple(p.split("=")) for p in
                                                  query.split("&") if p]).args) == on


def test_without_a_script_the_ticked_box_carries_its_off_before_it(recording):
    # the form's own fields in document order: a hidden "off", then the checkbox
    inputs = list(field(box(recording, "/puzzle"), "numbers").iter("input"))
    assert [(e.get("type"), e.get("name"), e.get("value")) for e in inputs][0] == \
        ("hidden", "numbers", "off")
    assert inputs[1].get("type") == "checkbox" and inputs[1].get("name") == "numbers"


@pytest.mark.parametrize("name", forms.COMMANDS)
def test_every_other_flag_starts_as_its_command_starts(recording, name):
    doc = box(recording, f"/{name}")
    for f in forms.fields(name):
        if f.kind != "flag":
            continue
        wanted = f.key in forms.TICKED.get(name, {})
        assert ticked(doc, f.key) == wanted, f.key
        hidden = [e for e in field(doc, f.key).iter("input") if e.get("type") == "hidden"]
        assert bool(hidden) == wanted, f.key
