"""Atomic file writes: a file is written whole or not at all, never over an input of the same
command and never in place of a device, FIFO or socket."""

from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path

from .errors import ExportError

_INPUTS: set[tuple[int, int]] = set()  # (device, inode) of every file read as an input


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
