"""Budgets: the memory a command needs and what it is about to write (files, pages, pixels,
bytes), checked before the work against fixed limits and against this process's own limits
(``ulimit -v``: RLIMIT_AS; ``ulimit -f``: RLIMIT_FSIZE) and the free disk space. A refusal is
a TooLargeError of one line with the numbers."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from .errors import TooLargeError

try:
    import resource
except ImportError:  # not a Unix: no process limits to read
    resource = None

# The interpreter with weave-cut's imports (RSS of ``--version``), under every memory estimate.
BASE_BYTES = 128 << 20
# Files one command writes: a DeepZoom pyramid of a 65,536-pixel image in the default
# 256-pixel tiles has 87,381; beyond that a folder is slow to list, copy and serve.
MAX_FILES = 100_000
# Printer pages of one PDF: a ream of paper (a 1:1 print of about 4.5 x 4.5 m on A4);
# larger is a job for a plotter.
MAX_PAGES = 500
# The least room a file takes on disk: one block of ext4, APFS or NTFS.
FILE_BLOCK = 4096


def available_memory() -> int:
    """Bytes of memory available now (MemAvailable), or 8 GiB when it cannot be read."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 8 << 30


def _limit(which: str) -> int | None:
    """The soft limit ``resource.RLIMIT_<which>`` in bytes, or None when there is none."""
    if resource is None or not hasattr(resource, f"RLIMIT_{which}"):
        return None
    soft = resource.getrlimit(getattr(resource, f"RLIMIT_{which}"))[0]
    return None if soft == resource.RLIM_INFINITY else int(soft)


def address_space_room() -> int | None:
    """How large this process's resident memory may grow under its address-space limit
    (``ulimit -v``): the limit less what it has mapped but not touched (libraries, thread
    stacks), since new arrays are mapped and touched alike; None without a limit."""
    limit = _limit("AS")
    if limit is None:
        return None
    status = {}
    try:
        with open("/proc/self/status") as f:
            status = {k: int(v.split()[0]) * 1024 for k, _, v in (ln.partition(":") for ln in f)
                      if k in ("VmSize", "VmRSS")}
    except (OSError, ValueError, IndexError):
        pass
    return max(0, limit - (status.get("VmSize", 0) - status.get("VmRSS", 0)))


def memory_limit() -> tuple[int, str]:
    """(bytes, how to say it): the memory available now or, when lower, the room the
    address-space limit leaves."""
    have, room = available_memory(), address_space_room()
    if room is not None and room < have:
        return room, "is left under this process's address-space limit (ulimit -v)"
    return have, "is available"


def file_size_limit() -> int | None:
    """The largest file this process may write (``ulimit -f``), or None."""
    return _limit("FSIZE")


def gib(n: float) -> str:
    return f"{n / 2**30:,.1f} GiB" if n >= 2**30 else f"{n / 2**20:,.0f} MiB"


def _amount(n: int) -> str:
    return gib(n) if n >= 2**20 else f"{n:,} bytes"


def check_memory(need: int, what: str) -> None:
    """Refuse ``what`` (a phrase: "a 9,000 x 9,000 px PNG") when it needs more than
    :func:`memory_limit`."""
    have, source = memory_limit()
    if need > have:
        raise TooLargeError(f"{what} needs about {gib(need)} of memory; {gib(have)} {source}")


def check_count(n: int, limit: int, unit: str, what: str, advice: str) -> None:
    """Refuse ``what`` when it would make more than ``limit`` ``unit``."""
    if n > limit:
        raise TooLargeError(f"{what} makes {n:,} {unit}; at most {limit:,} ({advice})")


def check_file_size(nbytes: int, what: str, advice: str = "", most: bool = False) -> None:
    """Refuse a file of ``nbytes`` (at ``most``) beyond the process's file-size limit
    (``ulimit -f``)."""
    limit = file_size_limit()
    if limit is not None and nbytes > limit:
        raise TooLargeError(f"{what} {'can take up to' if most else 'takes'} {nbytes:,} bytes, "
                            f"beyond this process's file-size limit (ulimit -f) of {limit:,} "
                            "bytes" + (f"; {advice}" if advice else ""))


def check_disk(nbytes: int, folder, what: str) -> None:
    """Refuse writing about ``nbytes`` into ``folder`` (or the nearest folder above it that
    exists) when its file system has less room free."""
    place = Path(os.path.abspath(folder))
    while not place.is_dir() and place != place.parent:
        place = place.parent
    try:
        free = shutil.disk_usage(place).free
    except OSError:
        return
    if nbytes > free:
        raise TooLargeError(f"{what} takes about {_amount(nbytes)} on disk; {_amount(free)} "
                            f"is free in {place}")
