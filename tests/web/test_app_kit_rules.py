"""A page offers no option its command refuses for the kit chosen: on the ball's page (a
surface in space) no cutter, laser card, layout or turn; on a flat model's no projection. The
oracle is the command itself: each option of the form, given alone (with the flag it needs),
is shown on the page exactly when ``strands`` accepts it for that input (run up to where the
work would start)."""

from __future__ import annotations

import html5lib
import pytest
from click.testing import CliRunner

from weavecut import inputs, mesh_io
from weavecut.cli import cli, strands_command
from weavecut.web import forms, queries

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
        queries.parse("strands", query)
    spec = dict(query)["input"]
    args = [w for k, v in query[1:] for w in ([f"--{k}"] if v == "on" else [f"--{k}", v])]
    kit = tmp_path / ("kit" if "--laser-card" in args else "kit.pdf")
    out = CliRunner().invoke(cli, ["strands", spec, *args, "-o", str(kit)])
    assert out.exit_code == 2 and refused.value.message in " ".join(out.output.split())
    assert says in refused.value.message


def uploaded(client, tmp_path, spec: str) -> tuple[str, dict, str]:
    """Built-in input ``spec`` written as an OBJ file and uploaded: (the file, the upload's
    answer, its ``input=`` value)."""
    path = tmp_path / f"{spec}.obj"
    mesh_io.write_mesh(inputs.get(spec), path)
    answer = client.post("/upload", content=path.read_bytes())
    assert answer.status_code == 200, answer.text
    return str(path), answer.json(), "upload:" + answer.json()["id"]


@pytest.mark.parametrize("name", INPUTS)
def test_an_uploaded_mesh_is_offered_exactly_what_the_command_takes_for_it(
        recording, monkeypatch, tmp_path, name):
    """The same oracle for an OBJ file of the input: a closed surface in space uploaded is a
    ball on the page as the CLI makes a ball of the file."""
    spec, args, more = INPUTS[name]
    path, _, value = uploaded(recording, tmp_path, spec)
    monkeypatch.setitem(INPUTS, "file", (path, args, more))
    for f in forms.fields("strands"):
        if f.kind == "input" or f.needs.startswith("!"):
            continue
        doc = html5lib.parse(recording.get(f"/strands?input={value}{more}"
                                           + (f"&{f.needs}=on" if f.needs else "")).text,
                             namespaceHTMLElements=False)
        page = {e.get("data-key"): e.get("hidden") is None for e in doc.iter()
                if e.get("data-key")}
        takes = accepted(monkeypatch, tmp_path, "file",
                         [*(["--" + f.needs] if f.needs else []), *sample(f)])
        assert page[f.key] == takes, (name, f.key, takes)
        if not takes:  # and refused before a job, as for a built-in input
            given = sample(f)[1] if len(sample(f)) > 1 else "on"
            refused = recording.get(f"/strands/check?input={value}{more}&{f.key}={given}"
                                    + (f"&{f.needs}=on" if f.needs else "")).json()
            assert not refused["ok"], (name, f.key)


@pytest.mark.parametrize("spec", sorted(inputs.INPUTS))
def test_an_upload_is_the_kind_of_kit_the_cli_makes_of_the_file(recording, monkeypatch,
                                                                tmp_path, spec):
    """Every built-in input as an OBJ file: the kind the upload answers (and its option on the
    page) is a ball exactly when ``strands FILE --cutter silhouette`` is refused as one."""
    path, answer, value = uploaded(recording, tmp_path, spec)
    monkeypatch.setitem(INPUTS, "file", (path, [], ""))
    ball = not accepted(monkeypatch, tmp_path, "file", ["--cutter", "silhouette"])
    assert answer["kind"] == ("surface" if ball else "flat")
    doc = html5lib.parse(recording.get(f"/strands?input={value}").text,
                         namespaceHTMLElements=False)
    option, = [e for e in doc.iter("option") if e.get("value") == value]
    assert option.get("data-kind") == answer["kind"]


@pytest.mark.parametrize("name", ["ball", "flat"])
def test_no_help_names_a_field_the_page_does_not_offer(recording, name):
    """The ball's page offers no laser card: no hint on it names one (the page's help for
    that kind, and the help the script swaps in for each kind, ``data-help-KIND``)."""
    spec, _, more = INPUTS[name]
    doc = html5lib.parse(recording.get(f"/strands?input={spec}{more}").text,
                         namespaceHTMLElements=False)
    fields = {e.get("data-key"): e for e in doc.iter() if e.get("data-key")}
    kind = forms.input_kind(spec)
    refused = {k for k, e in fields.items() if e.get("data-not-for") == kind}
    gone = {k: f"“{forms.field_label(k)}”" for k, e in fields.items()
            if k in refused or e.get("data-needs") in refused}  # or needs a refused flag
    assert refused and all(fields[k].get("hidden") is not None for k in gone)
    hints = {k: e.find(".//p[@class='hint']") for k, e in fields.items() if k not in gone}
    shown = [" ".join("".join(e.itertext()).split()) for e in hints.values()]
    shown += [e.get(f"data-help-{kind}") or e.get("data-help")  # what the script swaps in
              for h in hints.values() for e in h.iter("span") if e.get("data-help")]
    assert [(h, w) for h in shown for w in gone.values() if w in h] == []
