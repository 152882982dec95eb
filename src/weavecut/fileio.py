"""Atomic file writes: a file is written whole or not at all, never over an input of the same
command and never in place of a device, FIFO or socket. Inside ``recording()`` every write is
also noted (with the Drawing it was rendered from, and the summary a command printed), which
is what the kit page shows.

Inside ``writing_into(folders)`` (every command, through ``cli.common.reports_errors``) the
first write into one of ``folders`` locks it (an exclusive ``flock`` on the folder itself)
until the outermost block ends, so two weave-cut processes never write one folder at once:
the second waits, saying so on stderr, at most ``LOCK_WAIT`` seconds, then is refused.
Waiting rather than refusing at once: two runs started together (``make -j``, a repeated
command) both finish, as if run one after the other; the bound keeps a stopped or stuck
writer from hanging the other. The lock is taken at the first write, not at the start, so a
run refused for its input never waits, and a folder that does not exist yet is locked as soon
as it is made.

The outermost block may also carry a ``guard`` (``manifest.Ledger``: which existing files
weave-cut may replace): every write in this process is checked by it first
(``guard.check(path)``), every file written or noted is told to it (``guard.wrote(path)``),
and it records them (``guard.record(strict)``) before the locks are released, so another
weave-cut waiting for the folder finds them listed.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import stat
import sys
import tempfile
import time
from contextvars import ContextVar
from dataclasses import dataclass, field
from pathlib import Path

from .budget import check_file_size
from .errors import ExportError

_INPUTS: set[tuple[int, int]] = set()  # (device, inode) of every file read as an input
LOCK_WAIT = 600.0  # seconds a writer waits for another weave-cut writing into its folder


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
    """Note a written ``path`` (and the ``drawing`` it shows) or a summary line, if recording;
    a written path is also told to the running command's guard (``writing_into``)."""
    guard = active_guard()
    if guard is not None and path is not None:
        guard.wrote(path)
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
    _claim(path)
    return path


@dataclass
class _Locks:
    """The folders the running command writes into, and those it holds locked."""

    roots: list[str] = field(default_factory=list)  # absolute, locked at the first write
    held: dict[tuple[int, int], int] = field(default_factory=dict)  # (device, inode) -> fd
    claimed: set[str] = field(default_factory=set)
    depth: int = 0
    pid: int = 0
    guard: object | None = None  # the outermost block's guard (manifest.Ledger)


_LOCKS = _Locks()


@contextlib.contextmanager
def writing_into(folders, guard=None):
    """Lock each of ``folders`` at the first write into it or below (``make_folder``,
    ``write_atomic``) and hold the locks until the outermost block ends. Nested blocks (the
    jobs of a build) add their folders; a forked worker writes under its parent's locks.
    The outermost block's ``guard`` checks and records every write (a nested block's is
    ignored: a build's jobs write under the build's rule and its ``--force``)."""
    if _LOCKS.depth == 0:
        _LOCKS.pid = os.getpid()
        _LOCKS.guard = guard
    _LOCKS.depth += 1
    _LOCKS.roots += [os.path.abspath(f) for f in folders]
    done = False
    try:
        yield
        done = True
    finally:
        try:
            if _LOCKS.depth == 1 and _LOCKS.guard is not None:
                _LOCKS.guard.record(strict=done)  # still under the locks
        finally:
            _LOCKS.depth -= 1
            if _LOCKS.depth == 0:
                for fd in _LOCKS.held.values():
                    os.close(fd)
                _LOCKS.roots.clear()
                _LOCKS.held.clear()
                _LOCKS.claimed.clear()
                _LOCKS.guard = None


def active_guard():
    """The running command's guard (``writing_into``), or None (also in a worker process)."""
    return _LOCKS.guard if _LOCKS.pid == os.getpid() else None


def claim(path: str | os.PathLike) -> None:
    """Lock now every folder of the running command that ``path`` lies in (waiting for
    another weave-cut writing there), as its first write there would."""
    _claim(path)


def _claim(path: str | os.PathLike) -> None:
    """Lock every registered folder that ``path`` (being written) lies in, once."""
    if _LOCKS.pid != os.getpid():
        return
    where = os.path.abspath(path)
    for root in _LOCKS.roots:
        if root not in _LOCKS.claimed and (
                where == root or where.startswith(root.rstrip(os.sep) + os.sep)):
            _LOCKS.claimed.add(root)
            if os.path.isdir(root):  # not the file an option that takes either names
                lock_folder(root)


def lock_folder(folder: str | os.PathLike) -> bool:
    """Lock ``folder`` against other weave-cut processes until the outermost ``writing_into``
    ends; False if this process holds it already (or the file system cannot lock it). Waits
    at most LOCK_WAIT seconds for another writer, saying so on stderr, then raises
    ExportError."""
    try:
        fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    except OSError:  # a folder this user may write but not read: written as before, unlocked
        return False
    st = os.fstat(fd)
    key = (st.st_dev, st.st_ino)
    try:
        locked = key not in _LOCKS.held and _wait_for(fd, folder)
    except BaseException:
        os.close(fd)
        raise
    if not locked:
        os.close(fd)
        return False
    _LOCKS.held[key] = fd
    return True


def _wait_for(fd: int, folder) -> bool:
    deadline = None
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return True
        except BlockingIOError:
            pass
        except OSError:  # a file system without locks
            return False
        now = time.monotonic()
        if deadline is None:
            deadline = now + LOCK_WAIT
            _tell(f"weave-cut: waiting for another weave-cut writing into {folder} (at most "
                  f"{LOCK_WAIT:g} s)...")
        elif now >= deadline:
            raise ExportError(f"another weave-cut has been writing into {folder} for "
                              f"{LOCK_WAIT:g} s; try again when it is done")
        time.sleep(min(0.1, LOCK_WAIT))


@contextlib.contextmanager
def folder_lock(folder: str | os.PathLike):
    """Hold the lock on ``folder`` inside the block (kept if this process held it before)."""
    with writing_into(()):
        yield lock_folder(folder)


def _tell(message: str) -> None:
    try:
        sys.stderr.write(message + "\n")
        sys.stderr.flush()
    except (OSError, ValueError):
        pass


def write_atomic(path: str | os.PathLike, data: bytes, *, noted: bool = True) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder, then rename.

    The temporary name is short (``.wc-XXXXXXXX.part``), so any name the file system takes
    for ``path`` also works for it. The running command's guard checks ``path`` first and is
    told of it after (``writing_into``); ``noted=False`` is for weave-cut's own bookkeeping
    (the manifest), which is neither an output nor checked as one.
    """
    path = Path(path)
    check_writable(path)
    guard = active_guard() if noted else None
    if guard is not None:
        guard.check(path)
    check_file_size(len(data), str(path))
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise ExportError(f"cannot write {path}: folder {folder} does not exist")
    _claim(path)
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=".wc-", suffix=".part")
    except OSError as exc:
        raise ExportError(f"cannot write to {folder}: {exc.strerror}") from exc
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
        if noted:
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
