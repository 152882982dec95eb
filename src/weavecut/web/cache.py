"""Job results on disk by ``JobSpec.key()``, bounded in size, least recently used out first.

One file per result, ``FOLDER/ab/abcdef...`` (the key's first two hex digits name a
subfolder), holding ``JobResult.to_bytes()``. A file is written whole or not at all
(``fileio.write_atomic``: a temporary file, then a rename), so a reader sees a whole result or
none, and any number of processes may read and write one folder at once: a result removed
while read stays readable through the open file; one that cannot be read is a miss.

Use is recorded in the file's modification time (set at each put and hit, always later than
the last one this process set), and when the files pass ``max_bytes`` the least recently used
go first. Only results that are ``ok`` are kept: a refusal may depend on the limits or the
memory free at the time.
"""

from __future__ import annotations

import os
import re
import threading
import time
from pathlib import Path

from ..errors import ExportError
from ..fileio import make_folder, write_atomic
from .jobs import JobResult

KEY = re.compile(r"[0-9a-f]{64}")


class Cache:
    """Results by key in ``folder`` (created), at most ``max_bytes`` of them."""

    def __init__(self, folder: str | os.PathLike, max_bytes: int) -> None:
        self.folder = make_folder(folder)
        self.max_bytes = max_bytes
        self._lock = threading.Lock()
        self._last = 0  # the last use time this process set, in ns

    def path(self, key: str) -> Path:
        if not KEY.fullmatch(key):
            raise ValueError(f"{key!r} is not a job key (64 hex digits)")
        return self.folder / key[:2] / key

    def get(self, key: str) -> JobResult | None:
        """The result kept under ``key`` (now the most recently used), or None."""
        path = self.path(key)
        try:
            with open(path, "rb") as f:
                data = f.read()
            result = JobResult.from_bytes(data)
        except (OSError, ValueError):
            return None
        self._touch(path)
        return result

    def put(self, key: str, result: JobResult) -> None:
        """Keep ``result`` under ``key`` (if ok), then drop the least recently used results
        beyond ``max_bytes``; a result larger than that is not kept."""
        if not result.ok:
            return
        data = result.to_bytes()
        if len(data) > self.max_bytes:
            return
        path = self.path(key)
        try:
            make_folder(path.parent)
            write_atomic(path, data)
        except ExportError:  # a full disk or a folder removed meanwhile: a cache may forget
            return
        self._touch(path)
        self.evict(keep=path)

    def entries(self) -> list[tuple[int, str, int]]:
        """(last use in ns, key, bytes) of every result kept, least recently used first."""
        found = []
        for sub in _scan(self.folder):
            if not sub.is_dir(follow_symlinks=False) or len(sub.name) != 2:
                continue
            for entry in _scan(sub.path):
                if KEY.fullmatch(entry.name):
                    try:
                        st = entry.stat(follow_symlinks=False)
                    except OSError:  # removed meanwhile
                        continue
                    found.append((st.st_mtime_ns, entry.name, st.st_size))
        return sorted(found)

    def size(self) -> int:
        return sum(n for _, _, n in self.entries())

    def evict(self, keep: Path | None = None) -> None:
        """Remove the least recently used results until the rest fit in ``max_bytes``."""
        entries = self.entries()
        total = sum(n for _, _, n in entries)
        for _, key, n in entries:
            if total <= self.max_bytes:
                break
            path = self.path(key)
            if path == keep:
                continue
            try:
                os.unlink(path)
            except FileNotFoundError:  # another process evicted it
                pass
            except OSError:
                continue
            total -= n

    def _touch(self, path: Path) -> None:
        with self._lock:
            self._last = max(time.time_ns(), self._last + 1)
            stamp = self._last
        try:
            os.utime(path, ns=(stamp, stamp))
        except OSError:  # evicted meanwhile
            pass


def _scan(folder) -> list[os.DirEntry]:
    try:
        with os.scandir(folder) as it:
            return list(it)
    except OSError:
        return []
