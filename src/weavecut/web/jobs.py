"""A web job: one weave-cut command run in a temporary folder exactly as the command line runs
it, and what it made, as the web app serves it (``weave-cut serve``, issue #30).

``run_job(spec)`` writes the uploaded inputs into a fresh folder, runs ``weave-cut -q COMMAND
ARGS ... --json -o OUTPUT --html index.html`` in it (in this process, through the click group,
with ``sys.argv`` as a shell would set it, so the command line the files record is that one),
and returns:

- a kit: every file the command wrote, with its kit page, as a ZIP whose entries are sorted
  by name, dated 1980-01-01, rw-r--r--, with no extra fields, so the same job gives the same
  bytes; the files are byte for byte those of the same command typed in an empty folder
  (``command_line(spec)`` gives it); a command without ``--html`` (``subdivide``,
  ``figure``) gets its kit page written after it (``weavecut.kitpage``), so every download
  explains itself;
- a preview: the picture ``--preview`` draws (``strands``, ``puzzle``), else the command's
  own drawing;

with the summary the command printed as ``--json``. A usage error answers 400 with the
command's own message, refused work (a budget, a memory estimate) 422; an unexpected error
answers 500 in one line (its traceback goes to the log). Nothing is ever raised.

The queues (``queues.open_queue``: ``local_queue``, ``redis_queue``) run each job in a child
process with CPU and memory limits (``limits``); ``cache`` keeps results by ``JobSpec.key()``.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import json
import logging
import os
import re
import shlex
import shutil
import sys
import tempfile
import zipfile
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Protocol

import click

from ..cli.recipe import NOT_IN_RECIPES
from ..fileio import recording
from .version import code_version

log = logging.getLogger(__name__)

KINDS = ("preview", "kit", "read")  # read: an upload read as the CLI reads it
# (``uploads.read_job``; ``limits.child_main`` runs it, ``run_job`` the other two)
PAGE = "index.html"  # the kit page, beside the outputs (as ``build`` writes it)
NOT_JOBS = NOT_IN_RECIPES  # build reads a recipe's files; serve and worker serve
ADDED = ("--output", "--json", "--preview", "--html", "--force", "--quiet")  # set by the job
FOLDER_FLAGS = frozenset({"--laser-card"})  # flags that make -o a folder
NOT_PREVIEWED = {  # options a command's --preview refuses, left out of a preview job: they
    "strands": ("--cutter", "--laser-card", "--material", "--laser", "--formats")}  # change
# how the strips are cut, not the pattern the preview draws
DRAWING_FORMATS = ("svg", "pdf", "dxf", "png")  # a drawing's -o (``export``), by the web's order
NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9._-]{0,99}")  # an upload's or an output's name
ZIP_DATE = (1980, 1, 1, 0, 0, 0)  # the earliest date a ZIP entry can hold
MAX_BODY = 200 << 20  # bytes of a kit a web job returns; larger kits belong to the CLI
OUT_OF_MEMORY = "out of memory; try fewer levels"  # the command line's own words
MEDIA = {".svg": "image/svg+xml", ".png": "image/png", ".pdf": "application/pdf",
         ".json": "application/json", ".zip": "application/zip", ".dxf": "image/vnd.dxf",
         ".html": "text/html"}


@dataclass(frozen=True)
class JobSpec:
    """What to make: ``kind`` "preview" or "kit", a command and its arguments (long option
    names; never -o, --json, --preview, --html, --force or -q, which the job adds), the
    uploaded inputs by bare name, and optionally the kit's output name (``output``: the -o
    value, such as "square.svg"; by default ``default_output``)."""

    kind: str
    command: str
    args: tuple[str, ...]
    files: tuple[tuple[str, bytes], ...] = ()
    output: str = ""

    def key(self) -> str:
        """sha256 hex of the canonical JSON of the spec, its uploads by their hashes, and
        the code that runs it (``code_version``: weave-cut's version, a hash of its files and
        presets): equal keys, equal results; a changed source file or preset, a new key."""
        doc = {"kind": self.kind, "command": self.command, "args": list(self.args),
               "files": sorted([n, hashlib.sha256(b).hexdigest()] for n, b in self.files),
               "output": self.output, "version": code_version()}
        text = json.dumps(doc, sort_keys=True, separators=(",", ":"), ensure_ascii=True,
                          allow_nan=False)
        return hashlib.sha256(text.encode("ascii")).hexdigest()


@dataclass(frozen=True)
class JobResult:
    """What a job made (``body``, of ``media_type``) and what the command printed as
    ``--json`` (``summary``: with "warnings" the command gave; a preview's summary has the
    lines it "said"); or, when ``ok`` is False, the command's one-line message and the HTTP
    status it answers (400 usage error, 422 refused work, 500 unexpected)."""

    ok: bool
    body: bytes
    media_type: str
    summary: dict = field(default_factory=dict)
    error: str = ""
    status: int = 200

    def to_bytes(self) -> bytes:
        """One line of JSON (everything but the body), then the body."""
        head = {"ok": self.ok, "media_type": self.media_type, "summary": self.summary,
                "error": self.error, "status": self.status}
        return json.dumps(head, sort_keys=True, ensure_ascii=True,
                          allow_nan=False).encode("ascii") + b"\n" + self.body

    @classmethod
    def from_bytes(cls, data: bytes) -> JobResult:
        """The result ``to_bytes`` wrote; ValueError if ``data`` is not one."""
        head, sep, body = data.partition(b"\n")
        if not sep:
            raise ValueError("not a job result: no header line")
        doc = json.loads(head)
        if not isinstance(doc, dict) or set(doc) != {"ok", "media_type", "summary", "error",
                                                     "status"}:
            raise ValueError("not a job result: wrong header")
        return cls(bool(doc["ok"]), body, str(doc["media_type"]), dict(doc["summary"]),
                   str(doc["error"]), int(doc["status"]))


def failed(status: int, message: str) -> JobResult:
    """A job that made nothing: ``message`` is one line."""
    return JobResult(False, b"", "text/plain; charset=utf-8", {}, " ".join(message.split()),
                     status)


class QueueFull(Exception):
    """Too many jobs wait already; try again in ``retry_after`` seconds."""

    def __init__(self, retry_after: int) -> None:
        super().__init__(f"the job queue is full; try again in {retry_after} s")
        self.retry_after = retry_after


class JobQueue(Protocol):
    async def run(self, spec: JobSpec) -> JobResult:
        """The job's result; raises QueueFull. Cancelling the awaiting task kills the job."""

    async def close(self) -> None:
        """Kill the running jobs and stop."""


# --- the command line of a job -----------------------------------------------------------

@dataclass(frozen=True)
class Plan:
    """How a job runs: ``argv`` after ``weave-cut``; ``shown``: the file a preview returns
    (None: what the command prints)."""

    argv: tuple[str, ...]
    shown: str | None
    prints: bool  # the command writes no file: the kit is its --json output


def _command(name: str) -> click.Command | None:
    from ..cli.app import cli

    return None if name in NOT_JOBS or name not in cli.commands else cli.commands[name]


def _opts(command: click.Command) -> set[str]:
    return {o for p in command.params for o in p.opts}


def output_formats(command: str, args=()) -> tuple[str, ...]:
    """The formats the kit of ``command`` with ``args`` may be written in: the suffixes its -o
    takes, as the command's own lists say, the default first; () where -o is a folder
    (``puzzle``, ``strands --laser-card``: their files are chosen with ``--formats``)."""
    cmd = _command(command)
    option = next((p for p in cmd.params if "-o" in p.opts), None) if cmd else None
    if option is None or not getattr(option.type, "file_okay", True) \
            or FOLDER_FLAGS & set(args):
        return ()
    if command == "strands":
        from ..cli.strands_command import FORMATS
        return FORMATS
    if command == "weave":  # a 3-D model of a surface's weave, a drawing of a flat one
        from ..cli.weave_command import DRAWINGS, MODELS
        return DRAWINGS + tuple(m for m in MODELS if m not in DRAWINGS)
    if command == "figure":
        from ..figures.gallery import FIGURES
        name = next((a for a in args if not a.startswith("-")), "")
        return ("png",) if "(PNG)" in FIGURES.get(name, ("",))[0] else DRAWING_FORMATS
    if command == "subdivide":
        from ..cli.mesh_commands import MESH_SUFFIXES
        return DRAWING_FORMATS + tuple(s.lstrip(".") for s in MESH_SUFFIXES)
    return ("png",) if command == "levels" else ("svg",)


def laser_formats(command: str) -> str:
    """'svg,dxf': the files per sheet ``command`` writes without --formats (the formats of the
    laser preset its --laser gives by default, else ``lasersetup.DEFAULT_FORMATS``)."""
    from ..layout.lasersetup import DEFAULT_LASER, output_formats as written

    cmd = _command(command)
    laser = next((p.default for p in (cmd.params if cmd else ()) if "--laser" in p.opts
                  and isinstance(p.default, str)), DEFAULT_LASER)
    return ",".join(written(None, laser))


def default_output(spec: JobSpec, file_format: str = "") -> str:
    """The kit's -o: a folder named after the command where -o takes a folder (``puzzle``,
    ``strands --laser-card``), else a file in ``file_format`` (by default the first of
    ``output_formats``) named after the command, or after the figure (``figure``)."""
    offered = output_formats(spec.command, spec.args)
    if not offered:
        return spec.command
    stem = next((a for a in spec.args if not a.startswith("-")), spec.command) \
        if spec.command == "figure" else spec.command
    return f"{stem}.{file_format or offered[0]}"


def plan(spec: JobSpec) -> Plan:
    """The command line of ``spec`` (raises ValueError with the reason it is refused)."""
    if spec.kind not in KINDS[:2]:
        raise ValueError(f"unknown job kind {spec.kind!r}; choose one of {', '.join(KINDS[:2])}")
    command = _command(spec.command)
    if command is None:
        raise ValueError(f"unknown command {spec.command!r}")
    _check_args(spec)
    opts = _opts(command)
    if spec.kind == "preview":  # the pattern is the same with or without the cutter or card
        spec = replace(spec, args=tuple(a for a in spec.args if a.partition("=")[0]
                                        not in NOT_PREVIEWED.get(spec.command, ())))
    output = spec.output or default_output(spec)
    folder = not Path(output).suffix
    extra: list[str] = []
    shown = None
    if spec.kind == "kit":
        extra += ["--json"] if "--json" in opts else []
        extra += ["-o", output] if "-o" in opts else []
        extra += ["--html", PAGE] if "--html" in opts else []
    elif "-o" in opts:
        preview = "preview" + ("" if folder else ".png" if output.endswith(".png") else ".svg")
        extra += ["--preview"] if "--preview" in opts else []
        extra += ["-o", preview]
        shown = f"{preview}/{spec.command}-preview.svg" if folder else preview
    else:
        extra += ["--json"] if "--json" in opts else []
    return Plan(("-q", spec.command, *spec.args, *extra), shown, "-o" not in opts)


def command_line(spec: JobSpec) -> list[str]:
    """The arguments after ``weave-cut`` that make the same files as ``spec`` in an empty
    folder holding its uploads."""
    return list(plan(spec).argv)


def _check_args(spec: JobSpec) -> None:
    names = [n for n, _ in spec.files]
    for name in [*names, *([spec.output] if spec.output else [])]:
        if not NAME.fullmatch(name) or name == PAGE:
            raise ValueError(f"{name!r} is not a plain file name (letters, digits, '.', '_', "
                             f"'-'; not {PAGE})")
    if spec.output in names:
        raise ValueError(f"the output {spec.output!r} is an upload's name")
    for arg in spec.args:
        option, _, value = arg.partition("=") if arg.startswith("--") else ("", "", arg)
        if option in ADDED or re.fullmatch(r"-[oq].*", arg):
            raise ValueError(f"{option or arg[:2]} is set by the job, not given")
        if re.fullmatch(r"-[^-\d.].*", arg):
            raise ValueError(f"{arg!r}: give options by their long names (--levels, not -n)")
        if any(c in value for c in "/\\\0") or value.startswith("~") or value in (".", ".."):
            raise ValueError(f"{value!r}: a web job reads uploaded files by their names, "
                             "never a path")


# --- running it ----------------------------------------------------------------------------

def run_job(spec: JobSpec) -> JobResult:
    """Run ``spec`` in a temporary folder in this process; its result (never raises). It
    sets the process's working folder and ``sys.argv`` while the command runs, so one job
    at a time per process (the queues run each in a process of its own)."""
    try:
        how = plan(spec)
    except ValueError as exc:
        return failed(400, str(exc))
    folder = Path(tempfile.mkdtemp(prefix="weave-cut-job-"))
    try:
        for name, data in spec.files:
            (folder / name).write_bytes(data)
        code, error, out, err, record = _invoke(list(how.argv), folder)
        if code:
            return failed(code, error)
        if spec.kind == "kit" and not how.prints and "--html" not in how.argv:
            _kit_page(spec, how, folder, record)
        warnings = [line.removeprefix("weave-cut: warning: ") for line in err.splitlines()
                    if line.startswith("weave-cut: warning: ")]
        return _collect(spec, how, folder, out, warnings, list(record.said))
    except Exception as exc:  # noqa: BLE001 - a job answers, never raises
        log.exception("web job %s failed", spec.key())
        return failed(500, f"internal error: {type(exc).__name__}: {exc}")
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _invoke(argv: list[str], folder: Path) -> tuple[int, str, str, str, object]:
    """Run ``weave-cut ARGV`` in ``folder`` as ``weavecut.cli.main`` does: (HTTP status or 0,
    message, stdout, stderr, the ``fileio.Record`` of the files written and lines said)."""
    from ..cli.app import cli

    out, err = io.StringIO(), io.StringIO()
    cwd, args = os.getcwd(), sys.argv
    os.chdir(folder)
    sys.argv = ["weave-cut", *argv]
    code, message = 0, ""
    try:
        with recording() as record, contextlib.redirect_stdout(out), \
                contextlib.redirect_stderr(err):
            try:
                returned = cli.main(args=argv, prog_name="weave-cut", standalone_mode=False)
                if isinstance(returned, int) and returned:
                    code, message = 400, f"the command ended with status {returned}"
            except click.ClickException as exc:  # a usage error exits 2, refused work 1
                code, message = (400 if exc.exit_code == 2 else 422), exc.format_message()
            except MemoryError:
                code, message = 422, OUT_OF_MEMORY
            except (SystemExit, KeyboardInterrupt, click.Abort):
                code, message = 500, "the job was interrupted"
    finally:
        os.chdir(cwd)
        sys.argv = args
    return code, message, out.getvalue(), err.getvalue(), record


def _kit_page(spec: JobSpec, how: Plan, folder: Path, record) -> None:
    """The kit page of a command that writes none (no ``--html``): what ``--html`` writes,
    for the files the command wrote and the command line that wrote them."""
    from .. import kitpage

    line = "weave-cut " + " ".join(shlex.quote(a) for a in how.argv)
    kitpage.write(folder / PAGE, f"weave-cut {spec.command}",
                  [kitpage.Run.of(record, line, spec.command)])


def _collect(spec: JobSpec, how: Plan, folder: Path, out: str, warnings: list[str],
             said: list[str]) -> JobResult:
    uploads = {n for n, _ in spec.files}
    summary = _summary(out) if "--json" in how.argv else {"said": said}
    for w in warnings:
        if w not in summary.setdefault("warnings", []):
            summary["warnings"].append(w)
    if spec.kind == "preview":
        if how.shown is None:
            return JobResult(True, out.encode("utf-8"), MEDIA[".json"], summary)
        path = folder / how.shown
        return JobResult(True, path.read_bytes(),
                         MEDIA.get(path.suffix.lower(), "application/octet-stream"), summary)
    if how.prints:
        entries = [(f"{spec.command}.json", out.encode("utf-8"))]
    else:
        entries = [(p.relative_to(folder).as_posix(), p) for p in folder.rglob("*")
                   if p.is_file() and not p.is_symlink() and p.name not in uploads]
        size = sum(p.stat().st_size for _, p in entries)
        if size > MAX_BODY:
            return failed(422, f"the kit is {size / 2**20:,.0f} MB; a web job returns at most "
                          f"{MAX_BODY >> 20} MB (run it with the weave-cut command)")
    return JobResult(True, zip_files(entries), MEDIA[".zip"], summary)


def _summary(out: str) -> dict:
    try:
        doc = json.loads(out) if out.strip() else {}
    except ValueError:
        return {"printed": out}
    return doc if isinstance(doc, dict) else {"json": doc}


def zip_files(entries) -> bytes:
    """A ZIP of ``(name, bytes or path)`` entries that depends on nothing but them: sorted by
    name, every entry dated 1980-01-01 00:00, rw-r--r-- (Unix), deflated at level 6, no
    extra fields or comment."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        for name, data in sorted(entries, key=lambda e: e[0]):
            info = zipfile.ZipInfo(name, ZIP_DATE)
            info.create_system = 3  # Unix, so the mode below is read
            info.external_attr = 0o100644 << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            zf.writestr(info, data if isinstance(data, bytes) else Path(data).read_bytes(),
                        compresslevel=6)
    return buf.getvalue()
