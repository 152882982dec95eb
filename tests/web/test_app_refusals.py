"""Every refusal a form page shows is in the form's words: after a change (``/check``), on
the page itself (a link with a bad value), when a job or an upload is refused. A maker in a
browser reads the field's name (“Cell size”), never the CLI's flag (``--cell``)."""

from __future__ import annotations

import html5lib
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from tests.web.test_app_forms import CLI_WORDS, text
from tests.web_app import Recording, make_client
from weavecut.web import forms
from weavecut.web.jobs import failed
from weavecut.web.refusals import in_form_words

BAD = {"length": ["5", "-3mm", "huge", "0mm"], "integer": ["0", "x", "999"],
       "number": ["x", "1e9", "nan"], "choice": ["nope"], "preset": ["nope"],
       "flag": ["maybe"], "page": ["zz", "0x0mm"], "formats": ["xyz"], "text": ["a b"],
       "input": ["nope", "ngon:2", "upload:" + "0" * 64], "figure": ["nope"]}
KITS = [  # refusals of a kind of kit, and of options that go together
    ("strands", "input=dodecahedron&levels=1&cutter=silhouette"),
    ("strands", "input=dodecahedron&levels=1&laser-card=on&layout=module"),
    ("strands", "input=square-grid&project=sphere"),
    ("strands", "input=square-grid&tile-size=20mm&size=20cm"),
    ("strands", "input=square-grid&format=dxf&laser-card=on"),
    ("strands", "input=square-grid&format=zip"),
    ("puzzle", "format=svg"),
]


def flags(message: str, given: str = "") -> list[str]:
    """The CLI words in ``message``, the values the query gave (echoed) left out."""
    for value in given.split("&"):
        message = message.replace(value.partition("=")[2], "")
    return [found.group(0) for found in CLI_WORDS.finditer(message)]


def bad_queries() -> list[tuple[str, str]]:
    out = list(KITS)
    for name in forms.COMMANDS:
        start = "=".join(forms.STARTING[name]) + "&" if name in forms.STARTING else ""
        for f in forms.form_fields(name):
            out += [(name, f"{start}{f.key}={v}") for v in BAD.get(f.kind, ["zz"])]
    return out


@pytest.mark.parametrize(("name", "query"), bad_queries())
def test_a_refused_value_is_said_in_the_forms_words(recording, name, query):
    answer = recording.get(f"/{name}/check?{query}")
    if answer.json()["ok"]:
        return  # not every odd value is refused (a text field takes "a b")
    (key, message), = answer.json()["errors"].items()
    assert flags(message, query) == [], message
    assert key == "form" or key in {f.key for f in forms.form_fields(name)}
    shown = html5lib.parse(recording.get(f"/{name}?{query}").text, namespaceHTMLElements=False)
    errors = [text(e) for e in shown.iter() if "error" in (e.get("class") or "").split()]
    assert message in errors  # the page, opened from the link, says the same next to the field


@settings(suppress_health_check=[HealthCheck.function_scoped_fixture], max_examples=40)
@given(name=st.sampled_from(forms.COMMANDS), data=st.data())
def test_any_query_a_form_can_send_is_refused_in_its_words(recording, name, data):
    fields = forms.form_fields(name)
    chosen = data.draw(st.lists(st.sampled_from(fields), min_size=1, max_size=4,
                                unique_by=lambda f: f.key))
    values = [data.draw(st.sampled_from([*BAD.get(f.kind, ["zz"]), *(c.value for c in
                                         f.choices[:6]), f.default or "1"])) for f in chosen]
    query = "&".join(f"{f.key}={v}" for f, v in zip(chosen, values))
    answer = recording.get(f"/{name}/check?{query}").json()
    for message in answer["errors"].values():
        assert flags(message, query) == [], message


class Refusing(Recording):
    """A queue whose jobs are refused with the CLI's own words, as a job's command says them."""

    MESSAGE = ("Invalid value for '--levels' / '-n': --cell 3 mm would give about 2 million "
               "faces; give a larger --cell or fewer --levels")

    async def run(self, spec):
        self.specs.append(spec)
        return failed(400, self.MESSAGE)


def test_a_refused_job_is_said_in_the_forms_words(tmp_path, cwd):
    with make_client(tmp_path, Refusing()) as client:
        answer = client.get("/strands/preview.svg?input=square-grid")
        assert answer.status_code == 400
        assert flags(answer.text) == [], answer.text
        assert answer.text == ("Invalid value for “Levels”: “Cell size” 3 mm would give about "
                               "2 million faces; give a larger “Cell size” or fewer “Levels”")
        assert answer.headers["X-Field"] == "levels"  # found from the CLI's words
        upload = client.post("/upload", content=b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        assert upload.status_code == 400 and flags(upload.text) == [], upload.text


@pytest.mark.parametrize("name", forms.COMMANDS)
def test_every_option_of_a_page_is_named_by_its_field(name):
    """The planted flag of each option of each page, in click's hints and in a sentence."""
    for f in forms.fields(name):
        if f.kind in ("input", "figure"):
            continue
        said = in_form_words(f"Invalid value for '--{f.key}': not with --{f.key}", name)
        assert flags(said) == [] and said.count(f"“{f.label}”") == 2, said
