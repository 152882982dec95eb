"""The manifest of an output folder: which files weave-cut wrote there, with their SHA-256, and
which files each job of a build wrote (``.weave-cut-manifest.json``).

One rule for every command (``Ledger``): an existing file is replaced only if weave-cut wrote
it, that is if the manifest of the output folder lists it with its current hash, or with
``--force``; a symlink never. Every command records what it wrote in the manifest of its
output folder (a folder option's folder, a file option's folder). This is how git keeps an
untracked file from being overwritten by a checkout, and pip knows the files it may remove
(RECORD, with hashes): a rerun replaces weave-cut's own files without being asked, a file the
maker put there or edited since is refused with its name, and no one learns to type
``--force`` every time. A build also removes a job's stale files; the kit page's writer adds
itself."""

from __future__ import annotations

import errno
import hashlib
import json
import os
import re
import stat
from pathlib import Path, PurePosixPath

from .errors import ExportError, WeaveCutError
from .fileio import check_writable, claim, folder_lock, write_atomic

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
    manifest).

    A manifest found in a folder is untrusted: a regular file (not a link) of at most
    MAX_BYTES, JSON nested no deeper than its schema (a deeper one is refused by the parser's
    recursion bound or by the schema), every name a normalised relative path inside
    ``out_dir`` (no ``..``, not absolute, not through a symlink out). Anything else is a
    ManifestError naming it, before a file is replaced or removed."""
    path = out_dir / MANIFEST
    if not os.path.lexists(path):
        return {}, {}
    try:
        doc = json.loads(_read_small(path))
        files, outputs = _checked(doc)
    except RecursionError:
        raise ManifestError(f"{path}: unreadable manifest (nested too deep); remove it and "
                            "run again with --force") from None
    except (OSError, ValueError) as exc:
        raise ManifestError(f"{path}: unreadable manifest ({exc}); remove it and run again "
                            "with --force") from exc
    real = os.path.realpath(out_dir)
    for folder in {os.path.dirname(name) for name in files}:
        if not _inside(os.path.realpath(os.path.join(real, folder)), real):
            name = next(n for n in sorted(files) if os.path.dirname(n) == folder)
            raise ManifestError(f"{path}: lists {name!r}, which is not inside {out_dir} (a "
                                "symlink leads out); remove the manifest and run again with "
                                "--force")
    return files, outputs


MAX_BYTES = 16 * 2**20
_SHA256 = re.compile(r"[0-9a-f]{64}")


def _read_small(path: Path) -> bytes:
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError as exc:
        raise ValueError("a symlink" if exc.errno == errno.ELOOP else exc.strerror) from exc
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise ValueError("not a regular file")
        data = f.read(MAX_BYTES + 1)
    if len(data) > MAX_BYTES:
        raise ValueError(f"larger than {MAX_BYTES >> 20} MiB")
    return data


def _checked(doc) -> tuple[dict[str, str], dict[str, list[str]]]:
    """``doc``'s files and outputs, or ValueError naming the first thing that breaks the
    schema."""
    if not isinstance(doc, dict) or doc.get("format") != "weave-cut-manifest":
        raise ValueError("not a weave-cut manifest")
    if set(doc) - {"format", "version", "files", "outputs"} or doc.get("version") not in (1, 2):
        raise ValueError("unknown keys or version")
    files, outputs = doc.get("files"), doc.get("outputs", {})
    if not isinstance(files, dict) or not isinstance(outputs, dict):
        raise ValueError("'files' and 'outputs' must be tables")
    for name, digest in files.items():
        _relative(name)
        if not (isinstance(digest, str) and _SHA256.fullmatch(digest)):
            raise ValueError(f"the hash of {name!r} is not a SHA-256")
    for name, wrote in outputs.items():
        _relative(name, folder_ok=True)
        if not (isinstance(wrote, list) and all(isinstance(p, str) and p in files
                                                for p in wrote)):
            raise ValueError(f"the files of {name!r} are not a list of listed files")
    return files, outputs


def _relative(name, folder_ok: bool = False) -> None:
    """Raise ValueError unless ``name`` is a normalised relative path that stays inside."""
    pure = PurePosixPath(name) if isinstance(name, str) and name and "\0" not in name else None
    if (pure is None or pure.is_absolute() or ".." in pure.parts or pure.as_posix() != name
            or (name == "." and not folder_ok)):
        raise ValueError(f"lists {name!r}, which is not a relative path inside the folder")


def _inside(path: str, folder: str) -> bool:
    return path == folder or path.startswith(folder.rstrip(os.sep) + os.sep)


def record_manifest(out_dir: Path, entries: dict[str, str],
                    outputs: dict[str, list[str]] | None = None, gone=()) -> None:
    """Add ``entries`` (and the files each output's job wrote, ``outputs``) to the manifest of
    ``out_dir``, dropping the removed files ``gone`` (locked against concurrent builds)."""
    with folder_lock(out_dir):
        files, wrote = read_manifest(out_dir)
        files = {k: v for k, v in {**files, **entries}.items() if k not in gone}
        wrote = {**wrote, **(outputs or {})}
        doc = {"format": "weave-cut-manifest", "version": 2, "files": dict(sorted(files.items())),
               "outputs": {k: sorted(v) for k, v in sorted(wrote.items())}}
        text = json.dumps(doc, indent=1, allow_nan=False) + "\n"
        write_atomic(out_dir / MANIFEST, text.encode(), noted=False)


class Ledger:
    """The one rule for replacing files, for a command writing into ``roots`` (its output
    folders: a folder option's folder, a file option's folder; a build's jobs write under the
    build's). ``check(path)`` before a file is replaced: not a link, a folder, a device or an
    input, and weave-cut wrote it (listed with its current hash in the manifest of a root that
    holds it, or written in this run), unless ``force``. A refusal is confirmed under the
    folder's lock, as another weave-cut may be writing there and lists its files before it
    lets go. ``wrote(path)`` for every file written; ``record`` lists them in the manifest of
    the innermost root that holds each (the file's own folder if none does), and under each
    of ``outputs`` (the command's ``-o``) the files the run wrote in its root: a file the same
    output listed last time and this run did not write (a sheet or page the work no longer
    needs) is removed, if it is as weave-cut wrote it (as a build's jobs do,
    ``recipe.Planner.remember``)."""

    def __init__(self, roots, force: bool = False, outputs=()) -> None:
        real = {os.path.realpath(r) for r in roots}
        self.roots = sorted(real, key=lambda r: (-len(r), r))  # innermost first
        self.force = force
        self.outputs = sorted({self._real(o) for o in outputs})
        self.written: set[str] = set()
        self._listed: dict[str, dict[str, str]] = {}

    def open(self) -> None:
        """Read the manifest of every root now: an unreadable one is refused before any work
        (with ``--force`` too: it would be rewritten at the end)."""
        for root in self.roots:
            self._manifest(root)

    def _manifest(self, root: str, again: bool = False) -> dict[str, str]:
        if again or root not in self._listed:
            self._listed[root] = read_manifest(Path(root))[0]
        return self._listed[root]

    @staticmethod
    def _real(path) -> str:
        """``path`` with its folder resolved (not a final symlink)."""
        path = os.path.abspath(path)
        return os.path.join(os.path.realpath(os.path.dirname(path)), os.path.basename(path))

    def _holders(self, real: str) -> list[str]:
        return [r for r in self.roots if real.startswith(r.rstrip(os.sep) + os.sep)]

    def ours(self, path, again: bool = False) -> bool:
        """Whether weave-cut wrote the file at ``path`` as it is now."""
        real = self._real(path)
        if real in self.written:
            return True
        digest = file_hash(Path(real))
        return digest is not None and any(
            self._manifest(root, again).get(os.path.relpath(real, root)) == digest
            for root in self._holders(real) or [os.path.dirname(real)])

    def check(self, path, shown: str | None = None) -> None:
        """Raise ExportError unless ``path`` may be written (``shown``: the name in the
        message)."""
        shown = str(path) if shown is None else shown
        if not os.path.lexists(path):
            return
        if os.path.islink(path):
            if os.path.isfile(path):
                check_writable(path)  # a link to an input: said as such
            raise ExportError(f"{shown} is a symlink; weave-cut does not replace links")
        check_writable(path)
        if self.force or self.ours(path):
            return
        claim(path)  # wait for another weave-cut writing there, then look again
        if not os.path.lexists(path):  # gone meanwhile (its temporary file, a stale page)
            return
        if not self.ours(path, again=True):
            raise ExportError(f"{shown} exists and weave-cut did not write it (it is not listed "
                              f"in {MANIFEST}, or was changed since); use --force to replace "
                              "it")

    def wrote(self, path) -> None:
        self.written.add(self._real(path))

    def record(self, strict: bool = True) -> None:
        """List every file written in the manifest of its root; ``strict=False`` (the command
        failed) keeps quiet about a failure here, so the command's own error is the one said."""
        by_root: dict[str, dict[str, str]] = {}
        for real in sorted(self.written):
            root = (self._holders(real) or [os.path.dirname(real)])[0]
            digest = file_hash(Path(real))
            if digest is not None and os.path.basename(real) != MANIFEST:
                by_root.setdefault(root, {})[os.path.relpath(real, root)] = digest
        try:
            lists: dict[str, dict[str, list[str]]] = {}
            for output in self.outputs if strict else ():  # a failed run removes nothing
                root = output if output in self.roots else (self._holders(output)
                                                             or [os.path.dirname(output)])[0]
                lists.setdefault(root, {})[os.path.relpath(output, root)] = sorted(
                    by_root.get(root, {}))
            for root in sorted(set(by_root) | set(lists)):
                gone = _remove_stale(Path(root), lists.get(root, {}))
                record_manifest(Path(root), by_root.get(root, {}), lists.get(root), gone)
        except (WeaveCutError, OSError):
            if strict:
                raise


def _remove_stale(root: Path, outputs: dict[str, list[str]]) -> list[str]:
    """Remove the files the manifest of ``root`` lists under each of ``outputs`` that the run
    did not write now (its list), each only if unchanged since weave-cut wrote it; return the
    relative paths that are no longer weave-cut's to list."""
    files, wrote = read_manifest(root)
    gone = []
    for output, now in sorted(outputs.items()):
        for rel in sorted(set(wrote.get(output, ())) - set(now)):  # a few files
            if file_hash(root / rel) == files.get(rel):  # edited since: the maker's now
                os.unlink(root / rel)
            gone.append(rel)
    return gone
