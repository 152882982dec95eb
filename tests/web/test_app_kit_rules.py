"""A page offers no option its command refuses for the kit chosen: on the ball's page (a
surface in space) no cutter, laser card, layout or turn; on a flat model's no projection. The
oracle is the command itself: each option of the form, given alone (with the flag it needs),
is shown on the page exactly when ``strands`` accepts it for that input (run up to where the
work would start)."""

from __future__ import annotations

import html5lib
import pytest
from click.testing import CliRunner

from weavecut.cli import cli, strands_command
from weavecut.web import forms

INPUTS = {"ball": ("dodecahedron", ["--project", "sphere"], "&project=sphere"),
          "flat": ("square-grid", [], ""), "cube": ("cube", [], "")}


class Accepted(Exception):
    """The command got past its checks: the work would start here."""


def sample(f: forms.Field) -> list[str]:
    """Arguments giving option ``f`` a value that is not its default."""
    flag = f"--{f.key}"
    if f.kind == "flag":
        return [flag]
    if f.kind in ("choice", "preset"):
        return [flag, next(c.value for c in f.choices if c.value != f.default)]
    return [flag, {"length": "15mm", "integer": str(int(f.minimum or 1)), "number": "10",
                   "page": "a3", "formats": "svg", "text": "cut"}[f.kind]]


def accepted(monkeypatch, tmp_path, name: str, extra: list[str]) -> bool:
    monkeypatch.setattr(strands_command, "ball", _stop)
    monkeypatch.setattr(strands_command, "subdivide", _stop)
    spec, args, _ = INPUTS[name]
    folder = "--laser-card" in extra
    out = tmp_path / ("kit" if folder else "kit.pdf")
    result = CliRunner().invoke(cli, ["strands", spec, *args, *extra, "-o", str(out)])
    assert isinstance(result.exception, Accepted) or result.exit_code == 2, result.output
    return isinstance(result.exception, Accepted)


def _stop(*args, **kwargs):
    raise Accepted


def shown(client, name: str, query: str) -> dict[str, bool]:
    spec, _, more = INPUTS[name]
    doc = html5lib.parse(client.get(f"/strands?input={spec}{more}{query}").text,
                         namespaceHTMLElements=False)
    return {e.get("data-key"): e.get("hidden") is None for e in doc.iter() if e.get("data-key")}


@pytest.mark.parametrize("name", INPUTS)
def test_a_page_shows_an_option_exactly_when_the_command_takes_it(recording, monkeypatch,
                                                                  tmp_path, name):
    checked = 0
    for f in forms.fields("strands"):
        if f.kind == "input" or f.needs.startswith("!"):
            continue
        with_flag = ["--" + f.needs] if f.needs else []
        page = shown(recording, name, f"&{f.needs}=on" if f.needs else "")
        takes = accepted(monkeypatch, tmp_path, name, [*with_flag, *sample(f)])
        assert page[f.key] == takes, (name, f.key, takes)
        checked += 1
    assert checked >= 15


def test_the_form_follows_the_commands_table():
    """Each field the table names carries the kind of input it is not for; the table's
    options are the command's."""
    keys = {forms.key(p) for p in forms.command("strands").params}
    for kind, (_, why) in strands_command.KIT_REFUSES.items():
        assert set(why) <= keys
        assert {f.key for f in forms.fields("strands") if f.not_for == kind} == set(why)


@pytest.mark.parametrize("query, says", [
    ([("input", "dodecahedron"), ("project", "sphere"), ("cutter", "silhouette")],
     "--cutter is for flat models; a ball's strips are printed and cut by hand"),
    ([("input", "cube"), ("laser-card", "on"), ("turn", "10")], "--turn and --laser-card are"),
    ([("input", "square-grid"), ("project", "sphere")], "square-grid is flat; --project is"),
])
def test_a_query_the_kit_refuses_is_refused_before_a_job_with_the_commands_words(
        query, says, tmp_path):
    with pytest.raises(forms.FormError) as refused:
        forms.parse("strands", query)
    spec = dict(query)["input"]
    args = [w for k, v in query[1:] for w in ([f"--{k}"] if v == "on" else [f"--{k}", v])]
    kit = tmp_path / ("kit" if "--laser-card" in args else "kit.pdf")
    out = CliRunner().invoke(cli, ["strands", spec, *args, "-o", str(kit)])
    assert out.exit_code == 2 and refused.value.message in " ".join(out.output.split())
    assert says in refused.value.message
