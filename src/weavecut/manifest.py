"""The manifest of an output folder: which files weave-cut wrote there, with their SHA-256, and
which files each job of a build wrote (``.weave-cut-manifest.json``). A build replaces only the
files listed with their current hash (or with ``--force``) and removes a job's stale files; the
kit page's writer adds itself."""

from __future__ import annotations

import fcntl
import hashlib
import json
import os
import stat
from pathlib import Path

from .errors import WeaveCutError
from .fileio import write_atomic

MANIFEST = ".weave-cut-manifest.json"


class ManifestError(WeaveCutError, ValueError):
    """A manifest is there but cannot be read as one."""


def file_hash(path: Path) -> str | None:
    """SHA-256 of a regular file (None for anything else)."""
    try:
        if not stat.S_ISREG(os.lstat(path).st_mode):
            return None
        with open(path, "rb") as f:
            return hashlib.file_digest(f, "sha256").hexdigest()
    except OSError:
        return None


def read_manifest(out_dir: Path) -> tuple[dict[str, str], dict[str, list[str]]]:
    """The files weave-cut wrote into ``out_dir`` (relative path -> SHA-256), and the files
    each job wrote (its output's relative path -> relative paths; none in a version 1
    manifest)."""
    path = out_dir / MANIFEST
    if not path.exists():
        return {}, {}
    try:
        if os.lstat(path).st_size > 16 * 2**20 or not path.is_file():
            raise ValueError("not a small regular file")
        doc = json.loads(path.read_bytes())
        files, outputs = doc["files"], doc.get("outputs", {})
        if doc.get("format") != "weave-cut-manifest" or not all(
                isinstance(k, str) and isinstance(v, str) for k, v in files.items()) or not all(
                isinstance(k, str) and isinstance(v, list) and all(p in files for p in v)
                for k, v in outputs.items()):
            raise ValueError("not a weave-cut manifest")
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        raise ManifestError(f"{path}: unreadable manifest ({exc}); remove it and build with "
                          "--force") from exc
    return files, outputs


def record_manifest(out_dir: Path, entries: dict[str, str],
                    outputs: dict[str, list[str]] | None = None, gone=()) -> None:
    """Add ``entries`` (and the files each output's job wrote, ``outputs``) to the manifest of
    ``out_dir``, dropping the removed files ``gone`` (locked against concurrent builds)."""
    fd = os.open(out_dir, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        files, wrote = read_manifest(out_dir)
        files = {k: v for k, v in {**files, **entries}.items() if k not in gone}
        wrote = {**wrote, **(outputs or {})}
        doc = {"format": "weave-cut-manifest", "version": 2, "files": dict(sorted(files.items())),
               "outputs": {k: sorted(v) for k, v in sorted(wrote.items())}}
        text = json.dumps(doc, indent=1, allow_nan=False) + "\n"
        write_atomic(out_dir / MANIFEST, text.encode())
    finally:
        os.close(fd)
