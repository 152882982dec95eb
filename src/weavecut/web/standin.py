"""A small in-process stand-in for ``web.jobs`` (the job queue, its workers and the result
cache of issue #30, built in another branch), with the same names and signatures as the
contract in notes/web-interface.md, so the app runs and its tests pass before that branch is
merged. ``server`` imports ``web.jobs`` when it exists and this module only otherwise; once
``web.jobs`` is merged this module and that fallback go.

It runs one job at a time in a thread of the server's process (cwd, ``sys.argv`` and stdout are
the process's), has no CPU or memory limit, and cannot stop a job whose client left.
"""

from __future__ import annotations

import asyncio
import contextlib
import hashlib
import io
import json
import os
import sys
import tempfile
import threading
import zipfile
from dataclasses import dataclass
from pathlib import Path

import click

from .. import __version__
from ..fileio import write_atomic

ZIP_TIME = (1980, 1, 1, 0, 0, 0)
_LOCK = threading.Lock()


@dataclass(frozen=True)
class JobSpec:
    kind: str  # "preview" or "kit"
    command: str
    args: tuple[str, ...]
    files: tuple[tuple[str, bytes], ...] = ()

    def key(self) -> str:
        h = hashlib.sha256(json.dumps([__version__, self.kind, self.command,
                                       list(self.args)], allow_nan=False).encode())
        for name, data in self.files:
            h.update(name.encode() + b"\0" + hashlib.sha256(data).digest())
        return h.hexdigest()


@dataclass(frozen=True)
class JobResult:
    ok: bool
    body: bytes
    media_type: str
    summary: dict
    error: str = ""
    status: int = 200


class QueueFull(Exception):
    def __init__(self, retry_after: int = 5) -> None:
        super().__init__("the queue is full")
        self.retry_after = retry_after


def _argv(spec: JobSpec) -> tuple[list[str], str]:
    """The command line of the job and what it reads back (a file or folder)."""
    args = list(spec.args)
    if spec.kind == "preview":
        if spec.command == "strands":
            args = [a for a in args if not a.startswith(("--cutter=", "--material=", "--laser="))
                    and a != "--laser-card"]
            from ..inputs import SURFACES

            ball = args and args[0].partition(":")[0] in SURFACES  # no --preview: the pages
            return ([spec.command, *args, *([] if ball else ["--preview"]), "-o", "preview.svg"],
                    "preview.svg")
        if spec.command == "puzzle":
            return [spec.command, *args, "--preview", "-o", "preview"], "preview/puzzle-preview.svg"
        return [spec.command, *args, "-o", "preview.svg"], "preview.svg"
    out = {"strands": "strands-card" if "--laser-card" in args else "strands.pdf",
           "puzzle": "puzzle", "weave": "weave.svg"}.get(spec.command)
    if out is not None:
        return [spec.command, *args, "-o", out, "--html", "index.html", "--json"], "."
    return [spec.command, *args, "-o", f"{spec.command}.svg"], "."


def _run(argv: list[str], folder: Path) -> tuple[int, str, str, str]:
    """Run the CLI in ``folder``; (exit code, stdout, stderr, error message)."""
    from ..cli.app import cli

    out, err = io.StringIO(), io.StringIO()
    here, old_argv = os.getcwd(), sys.argv
    code, message = 0, ""
    try:
        os.chdir(folder)
        sys.argv = ["weave-cut", *argv]
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            cli.main(args=["-q", *argv], prog_name="weave-cut", standalone_mode=False)
    except click.ClickException as exc:
        code, message = exc.exit_code, exc.format_message()
    except MemoryError:
        code, message = 1, "out of memory; try fewer levels"
    finally:
        os.chdir(here)
        sys.argv = old_argv
    return code, out.getvalue(), err.getvalue(), message


def _zip(folder: Path, skip: set[str]) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        for path in sorted(p for p in folder.rglob("*") if p.is_file()):
            rel = path.relative_to(folder).as_posix()
            if rel in skip:
                continue
            info = zipfile.ZipInfo(rel, ZIP_TIME)
            info.external_attr = 0o644 << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, path.read_bytes())
    return buf.getvalue()


def run_job(spec: JobSpec) -> JobResult:
    argv, target = _argv(spec)
    with _LOCK, tempfile.TemporaryDirectory(prefix="weavecut-job-") as tmp:
        folder = Path(tmp)
        for name, data in spec.files:
            (folder / name).write_bytes(data)
        code, out, err, message = _run(argv, folder)
        if code:
            return JobResult(False, b"", "text/plain", {}, message, 400 if code == 2 else 422)
        warnings = [line.removeprefix("weave-cut: warning: ") for line in err.splitlines()
                    if line.startswith("weave-cut: warning: ")]
        try:
            summary = json.loads(out) if out.strip().startswith("{") else {}
        except ValueError:
            summary = {}
        if warnings and "warnings" not in summary:
            summary["warnings"] = warnings
        if spec.kind == "preview":
            path = folder / target
            media = "image/png" if path.suffix == ".png" else "image/svg+xml"
            return JobResult(True, path.read_bytes(), media, summary)
        return JobResult(True, _zip(folder, {n for n, _ in spec.files}), "application/zip",
                         summary)


class _Queue:
    def __init__(self, waiting: int) -> None:
        self.waiting, self.queued = waiting, 0

    async def run(self, spec: JobSpec) -> JobResult:
        if self.queued >= self.waiting:
            raise QueueFull(5)
        self.queued += 1
        try:
            return await asyncio.to_thread(run_job, spec)
        finally:
            self.queued -= 1

    async def close(self) -> None:
        pass


def open_queue(url: str | None, *, workers: int, cpu_seconds: int, memory_mb: int,
               waiting: int) -> _Queue:
    if url is not None:
        raise click.UsageError("--queue needs the job queue of issue #30 (not merged yet)")
    return _Queue(waiting)


class Cache:
    def __init__(self, folder: Path, max_bytes: int) -> None:
        self.folder, self.max_bytes = Path(folder), max_bytes
        self.folder.mkdir(parents=True, exist_ok=True)

    def get(self, key: str) -> JobResult | None:
        meta, body = self.folder / f"{key}.json", self.folder / f"{key}.body"
        try:
            doc = json.loads(meta.read_text())
            data = body.read_bytes()
        except (OSError, ValueError):
            return None
        os.utime(meta)
        return JobResult(True, data, doc["media_type"], doc["summary"])

    def put(self, key: str, result: JobResult) -> None:
        write_atomic(self.folder / f"{key}.body", result.body)
        write_atomic(self.folder / f"{key}.json", json.dumps(
            {"media_type": result.media_type, "summary": result.summary},
            allow_nan=False).encode())
        metas = sorted(self.folder.glob("*.json"), key=lambda p: p.stat().st_mtime)
        total = sum(p.stat().st_size for p in self.folder.iterdir())
        while total > self.max_bytes and len(metas) > 1:
            old = metas.pop(0)
            for p in (old, old.with_suffix(".body")):
                with contextlib.suppress(OSError):
                    total -= p.stat().st_size
                    p.unlink()
