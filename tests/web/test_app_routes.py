"""The routes: every value of a query reaches the command (read back by the command's own
parser, not by the code that wrote the arguments), a bad value answers 400 with the CLI's own
message, an unknown command 404, a kit is cached, the command line and recipe on the page are
what ``weave-cut build`` runs, and nothing unexpected shows a traceback."""

from __future__ import annotations

import asyncio
import io
import re
import shlex
import zipfile

import click
import pytest
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.cli.common import DRAWING_KEY
from weavecut.web import forms
from weavecut.web.refusals import in_form_words

from tests.web_app import cli_files, make_client


VALUES = {"input": "hex-grid:2x2", "figure": "edge-renders", "flag": "on", "number": "7",
          "length": "12mm", "page": "letter", "text": "cuts"}  # valid, none a default
BY_KEY = {"formats": "svg,lbrn2"}  # text fields with a grammar of their own


def value_for(f: forms.Field) -> str:
    """A valid value of field ``f`` that is not its default."""
    if f.key in BY_KEY:
        return BY_KEY[f.key]
    if f.kind in ("choice", "preset"):
        return next(c.value for c in reversed(f.choices) if c.value != f.default)
    if f.kind == "integer":
        return str(f.minimum + 1 if str(f.minimum + 1) != f.default else f.minimum)
    return VALUES[f.kind]


def parsed(name: str, args) -> click.Context:
    """The command's own reading of ``args`` (a placeholder -o, as the job adds one)."""
    command = cli.commands[name]
    extra = ["-o", "x.svg"] if any("-o" in p.opts for p in command.params) else []
    return command.make_context(name, [*args, *extra], parent=click.Context(cli))


@pytest.mark.parametrize("name", forms.COMMANDS)
def test_every_option_of_the_query_reaches_the_command(recording, name):
    kind = forms.input_kind(VALUES["input"])  # every option this input takes (a flat one)
    taken = [f for f in forms.fields(name) if f.not_for != kind]
    given = {f.key: value_for(f) for f in taken}
    for kind in ("preview.svg", "summary.json"):
        response = recording.get(f"/{name}/{kind}", params=given)
        assert response.status_code == 200, response.text
    assert {s.kind for s in recording.queue.specs} == {"preview", "kit"}
    for spec in recording.queue.specs:
        assert spec.command == name
        ctx = parsed(name, spec.args)
        for f in taken:
            p = f.param
            want = p.type_cast_value(ctx, given[f.key] if f.kind != "flag" else True)
            got = (ctx.params[p.name] if p.expose_value
                   else ctx.meta[DRAWING_KEY][p.name])
            assert got == want, (f.key, got, want)


def test_values_left_empty_are_the_defaults(recording):
    # the form's defaults: the command's, but for the flags the form ticks at first (Numbers)
    assert recording.get("/puzzle/preview.svg?size=&levels=&numbers=").status_code == 200
    assert recording.queue.specs[-1].args == tuple(f"--{k}" for k in forms.TICKED["puzzle"])


@pytest.mark.parametrize(("query", "field"), [
    ("input=square-grid&size=-3cm", "size"), ("input=square-grid&levels=99", "levels"),
    ("input=square-grid&levels=two", "levels"), ("input=square-grid&layout=spiral", "layout"),
    ("input=square-grid&turn=nan", "turn"), ("input=square-grid&page=huge", "page"),
    ("input=square-grid&size=1e308mm", "size"), ("input=square-grid&laser-card=maybe",
                                                 "laser-card"),
])
def test_a_bad_value_answers_400_with_the_clis_message(recording, query, field):
    response = recording.get(f"/strands/preview.svg?{query}")
    assert response.status_code == 400
    assert response.headers["x-field"] == field
    words = ["strands", *(f"--{k}={v}" if k != "input" else v
                          for k, v in (i.split("=", 1) for i in query.split("&")))]
    if field == "laser-card":  # a flag takes no value on the command line
        return
    printed = CliRunner().invoke(cli, [*words, "-o", "x.pdf"]).output
    assert f"Error: {response.text}" in in_form_words(printed, "strands")  # in the form's words
    assert recording.queue.specs == []


def test_the_commands_own_checks_answer_400_with_their_message(served):
    response = served.get("/strands/preview.svg?input=square-grid&size=27cm&tile-size=2cm")
    assert response.status_code == 400
    printed = CliRunner().invoke(cli, ["strands", "square-grid", "--size=27cm",
                                       "--tile-size=2cm", "--preview", "-o", "x.svg"]).output
    assert f"Error: {response.text}" in in_form_words(printed, "strands")
    assert response.headers["x-field"] == "size"


@pytest.mark.parametrize("path", ["/nope", "/nope.zip", "/nope/preview.svg",
                                  "/nope/summary.json", "/nope/check", "/build", "/stats"])
def test_an_unknown_command_is_404(recording, path):
    response = recording.get(path)
    assert response.status_code == 404
    assert "strands" in response.text  # says which pages there are


def test_an_unknown_parameter_says_the_nearest(recording):
    response = recording.get("/strands/check?input=square-grid&sise=27cm")
    assert response.status_code == 400
    assert "did you mean 'size'?" in response.json()["errors"]["form"]
    response = recording.get("/strands/preview.svg?input=square-grid&output=x.pdf")
    assert response.status_code == 400 and "names and packs the files" in response.text


def test_check_gives_the_command_line_and_a_recipe_build_runs_the_same(recording, tmp_path):
    query = "input=pentagon&levels=3&outline-level=2&style=ribbons&page=letter"
    found = recording.get(f"/weave/check?{query}").json()
    assert found["ok"] and found["errors"] == {}
    line = found["command_line"]
    assert line == ("weave-cut weave pentagon --levels 3 --page letter --outline-level 2 "
                    "--style ribbons -o weave.svg") or sorted(shlex.split(line)) == sorted(
        "weave-cut weave pentagon --levels 3 --outline-level 2 --style ribbons --page letter "
        "-o weave.svg".split())
    recipe = tmp_path / "r.toml"
    recipe.write_text(found["recipe"])
    dry = CliRunner().invoke(cli, ["build", str(recipe), "-o", str(tmp_path / "out"),
                                   "--dry-run"])
    assert dry.exit_code == 0, dry.output
    planned = shlex.split(dry.output.strip())
    assert planned[planned.index("-o") + 1] == str(tmp_path / "out" / "weave.svg")
    planned[planned.index("-o") + 1] = "weave.svg"
    assert sorted(planned) == sorted(shlex.split(line))


def test_a_kit_is_made_once_then_comes_from_the_cache(recording):
    first = recording.get("/weave.zip?input=square-grid&levels=2")
    second = recording.get("/weave.zip?input=square-grid&levels=2")
    assert first.status_code == second.status_code == 200
    assert first.content == second.content
    assert len(recording.queue.specs) == 1


def test_the_kit_is_the_clis_files(served, tmp_path):
    response = served.get("/weave.zip?input=square-grid&levels=2&outline-level=1")
    assert response.status_code == 200
    assert response.headers["content-type"] == "application/zip"
    kit = zipfile.ZipFile(io.BytesIO(response.content))
    names = kit.namelist()
    assert names == sorted(names) and "index.html" in names
    out = tmp_path / "cli"
    out.mkdir()
    made = cli_files(kit.read("index.html").decode(), out)
    assert sorted(made) == names
    for name in names:
        if name != "index.html":
            assert kit.read(name) == made[name], name
    assert kit.read("index.html") == made["index.html"]


@pytest.mark.slow
def test_figures_of_the_kit(served):
    response = served.get("/strands/summary.json?input=square-grid&size=27cm")
    assert response.status_code == 200
    found = dict(response.json()["figures"])
    summary = response.json()["summary"]
    assert found["Strands"] == str(summary["strands"]) == "48"
    assert found["Pages"].startswith(str(summary["pages"]["total"]))
    assert found["Strip width"] == f"{summary['strip_width_mm']:g} mm"


class Broken:
    async def run(self, spec):
        raise RuntimeError("a bug /home/secret/path")

    async def close(self):
        pass


def test_a_bug_is_a_plain_500_without_a_traceback(tmp_path, cwd):
    with make_client(tmp_path, Broken()) as client:
        for accept in ("text/html", "*/*"):
            response = client.get("/weave/preview.svg?input=square-grid",
                                  headers={"accept": accept})
            assert response.status_code == 500
            assert "Traceback" not in response.text and "secret" not in response.text
            assert "internal error" in response.text


def test_every_answer_forbids_other_hosts(recording):
    for path in ("/", "/strands", "/static/app.css", "/strands/check?input=pentagon"):
        policy = recording.get(path).headers["content-security-policy"]
        assert "default-src 'self'" in policy and "http" not in policy


def test_pages_and_assets_name_no_other_host(recording):
    from weavecut.web.server import STATIC

    texts = [recording.get(p).text for p in ("/", *(f"/{n}" for n in forms.COMMANDS))]
    texts += [p.read_text() for p in STATIC.glob("*.*") if p.suffix in (".css", ".js", ".svg")]
    for text in texts:
        hosts = re.findall(r"(?:https?:)?//[a-z0-9.-]+\.[a-z]{2,}", text)
        assert set(hosts) <= {"http://www.w3.org"}, hosts


class Slow:
    """A queue whose job runs until it is cancelled."""

    def __init__(self) -> None:
        self.started, self.cancelled = asyncio.Event(), False

    async def run(self, spec):
        self.started.set()
        try:
            await asyncio.sleep(3600)
        except asyncio.CancelledError:
            self.cancelled = True
            raise

    async def close(self):
        pass


@pytest.mark.parametrize("method, path, query, body", [
    ("GET", "/weave.zip", b"input=square-grid", b""),
    ("POST", "/upload", b"", b"v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n"),  # read by a job
])
def test_a_client_that_leaves_cancels_its_job(tmp_path, cwd, method, path, query, body):
    """The job is cancelled, the answer (to nobody) is 499, not a crash's 500, and an upload
    whose reading was cancelled is not kept."""
    from weavecut.web.server import create_app
    from weavecut.web.cache import Cache

    async def scenario() -> tuple[Slow, list]:
        queue = Slow()
        app = create_app(queue, Cache(tmp_path / "app" / "results", 2**20), tmp_path / "app")
        messages = [{"type": "http.request", "body": body, "more_body": False}]
        gone, sent = asyncio.Event(), []

        async def receive():
            if messages:
                return messages.pop(0)
            await gone.wait()
            return {"type": "http.disconnect"}

        async def send(message):
            sent.append(message)

        scope = {"type": "http", "method": method, "path": path, "raw_path": path.encode(),
                 "query_string": query, "scheme": "http", "server": ("test", 80),
                 "headers": [(b"content-length", str(len(body)).encode())],
                 "client": ("test", 1), "root_path": "", "http_version": "1.1",
                 "asgi": {"version": "3.0"}}
        served = asyncio.ensure_future(app(scope, receive, send))
        await asyncio.wait_for(queue.started.wait(), 30)
        assert not queue.cancelled
        gone.set()
        await asyncio.wait_for(served, 30)
        for _ in range(3):  # the cancellation reaches the job (not the loop's end)
            await asyncio.sleep(0)
        return queue, sent

    queue, sent = asyncio.run(scenario())
    assert queue.cancelled
    assert sent[0]["type"] == "http.response.start" and sent[0]["status"] == 499
    uploads = tmp_path / "app" / "uploads"
    assert not uploads.exists() or not any(uploads.rglob("upload-*"))


def test_a_recipe_cannot_start_a_server(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text('[[job]]\ncommand = "serve"\nport = 0\n')
    result = CliRunner().invoke(cli, ["build", str(recipe), "-o", str(tmp_path / "out")])
    assert result.exit_code == 1
    assert "unknown command 'serve'" in result.output


def test_a_balls_preview_is_the_ball_from_the_front_and_the_back(served):
    response = served.get("/strands/preview.svg?input=dodecahedron&levels=1&project=sphere"
                          "&size=12cm")
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith("image/svg+xml")
    text = response.text
    assert text.count("<svg") == 1 and ">front<" in text and ">back<" in text


@pytest.mark.parametrize("query", ["laser-card=on&palette=maritime-4&formats=lbrn2",
                                   "cutter=silhouette"])
def test_the_preview_of_strips_cut_by_machine_is_their_pattern(served, query):
    # --preview refuses --cutter and --laser-card: the preview job leaves them out (they
    # change how the strips are cut, not the pattern); the kit keeps them
    response = served.get(f"/strands/preview.svg?input=square-grid&{query}")
    assert response.status_code == 200, response.text
    plain = served.get("/strands/preview.svg?input=square-grid&" + "&".join(
        p for p in query.split("&") if p.startswith("palette")))
    strip = re.compile(rb"<metadata.*?</metadata>|<title>.*?</title>", re.S)
    assert strip.sub(b"", response.content) == strip.sub(b"", plain.content)
