"""Atomic file writes: a file is written whole or not at all, never over an input of the same
command and never in place of a device, FIFO or socket. Inside ``recording()`` every write is
also noted (with the Drawing it was rendered from, and the summary a command printed), which
is what the kit page shows."""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
from contextvars import ContextVar
from dataclasses import dataclass, field
from pathlib import Path

from .budget import check_file_size
from .errors import ExportError

_INPUTS: set[tuple[int, int]] = set()  # (device, inode) of every file read as an input


@dataclass
class Record:
    """What was written inside one ``recording()``: ``files`` maps every path written, in
    order, to the Drawing it was rendered from (None for other files); ``said`` holds the
    summary lines the command printed (also with -q)."""

    files: dict[Path, object] = field(default_factory=dict)
    said: list[str] = field(default_factory=list)


_RECORD: ContextVar[Record | None] = ContextVar("weavecut_record", default=None)


@contextlib.contextmanager
def recording():
    """Note every file written and every summary said inside the block; yields the Record."""
    record = Record()
    token = _RECORD.set(record)
    try:
        yield record
    finally:
        _RECORD.reset(token)


def note(path: str | os.PathLike | None = None, drawing=None, said: str | None = None) -> None:
    """Note a written ``path`` (and the ``drawing`` it shows) or a summary line, if recording."""
    record = _RECORD.get()
    if record is None:
        return
    if path is not None:
        key = Path(os.path.abspath(path))
        record.files[key] = drawing if drawing is not None else record.files.get(key)
    if said is not None:
        record.said.append(said)


def protect(path: str | os.PathLike) -> None:
    """Remember ``path`` as an input: ``write_atomic`` refuses to replace it (also through a
    symlink or a hard link)."""
    try:
        st = os.stat(path)
    except OSError:
        return
    _INPUTS.add((st.st_dev, st.st_ino))


def check_writable(path: str | os.PathLike) -> None:
    """Raise ExportError if ``path`` exists and is an input, a folder or not a regular file."""
    path = Path(path)
    try:
        st = os.stat(path)
    except OSError:
        return
    if stat.S_ISDIR(st.st_mode):
        raise ExportError(f"cannot write {path}: it is a directory")
    if not stat.S_ISREG(st.st_mode):
        raise ExportError(f"cannot write {path}: it is not a regular file (a device, FIFO or "
                          "socket)")
    if (st.st_dev, st.st_ino) in _INPUTS:
        raise ExportError(f"cannot write {path}: it is an input of this command; choose "
                          "another output name")


def make_folder(path: str | os.PathLike) -> Path:
    """Create the output folder ``path`` (and its parents) or raise ExportError."""
    path = Path(path)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except FileExistsError as exc:
        raise ExportError(f"cannot create folder {path}: a file of that name exists") from exc
    except OSError as exc:
        raise ExportError(f"cannot create folder {path}: {exc.strerror}") from exc
    return path


def write_atomic(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder, then rename.

    The temporary name is short (``.wc-XXXXXXXX.part``), so any name the file system takes
    for ``path`` also works for it.
    """
    path = Path(path)
    check_writable(path)
    check_file_size(len(data), str(path))
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise ExportError(f"cannot write {path}: folder {folder} does not exist")
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=".wc-", suffix=".part")
    except OSError as exc:
        raise ExportError(f"cannot write to {folder}: {exc.strerror}") from exc
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
        note(path)
    except OSError as exc:
        _unlink_quietly(tmp)
        raise ExportError(f"cannot write {path}: {exc.strerror}") from exc
    except BaseException:
        _unlink_quietly(tmp)
        raise


def _unlink_quietly(path: str) -> None:
    try:
        os.unlink(path)
    except OSError:
        pass
