"""Process-wide memory tuning for deep subdivisions.

glibc returns every large numpy array to the kernel when it is freed and maps fresh pages for
the next one; touching fresh pages for the first time is slow on virtual machines (page faults,
huge-page compaction). ``keep_freed_memory`` asks glibc to serve large arrays from its heap and
keep freed memory for reuse. The CLI calls it once; library users may call it themselves.
"""

from __future__ import annotations

import ctypes
import ctypes.util

M_TRIM_THRESHOLD, M_TOP_PAD, M_MMAP_MAX = -1, -2, -4


def keep_freed_memory() -> bool:
    """Keep freed memory in the process for reuse; False where glibc's mallopt is missing."""
    name = ctypes.util.find_library("c")
    try:
        libc = ctypes.CDLL(name)
        mallopt = libc.mallopt
    except (OSError, AttributeError, TypeError):
        return False
    return bool(mallopt(M_MMAP_MAX, 0) and mallopt(M_TRIM_THRESHOLD, 1 << 40)
                and mallopt(M_TOP_PAD, 64 << 20))
