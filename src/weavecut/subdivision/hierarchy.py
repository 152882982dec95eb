"""Levels of a subdivision and their provenance."""

from __future__ import annotations

import ctypes
import sys
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh


@dataclass(frozen=True, eq=False)
class Level:
    """One refinement level: a mesh plus where each of its faces and edges came from.

    Level 0 (the input) has no provenance (all ``None``).

    Parameters
    ----------
    mesh : Mesh
    parent_face : (F,) int32, the parent face every face lies in
    parent_corner : (F,) int32, the corner of the parent face it was made for
    parent_edge : (E,) int32, the parent edge an edge descends from, or the parent face for
        edges born inside a face (see the scheme's ``EDGE_PARTS``)
    edge_part : (E,) int8, which part of its parent the edge is (scheme-specific codes)
    """

    mesh: Mesh
    parent_face: NDArray[np.int32] | None = None
    parent_corner: NDArray[np.int32] | None = None
    parent_edge: NDArray[np.int32] | None = None
    edge_part: NDArray[np.int8] | None = None


Hierarchy = tuple[Level, ...]


BYTES_PER_CORNER = 120  # measured peak of one snub step per child corner (benchmarks/bench_snub.py)


M_TRIM_THRESHOLD, M_MMAP_MAX = -1, -4  # glibc mallopt parameters (malloc.h)


def keep_freed_memory() -> bool:
    """Keep memory freed by numpy in the process for the next arrays, where the platform allows.

    A snub step allocates a few hundred MB; by default glibc gives every large array fresh
    pages from the kernel (mmap), which are zero-filled on first touch (tens of thousands of
    page faults per step, and most of the spread between runs), and returns them on free.
    With big-block mmap off and trimming at 2 GiB, freed arrays stay in the heap and the
    next step's arrays reuse their pages. Costs: the process keeps its peak size until it
    exits (fine for the command line, which calls this; a library user opts in). Linux with
    glibc only (the same as ``MALLOC_MMAP_MAX_=0 MALLOC_TRIM_THRESHOLD_=2147483647``); returns
    False, and changes nothing, elsewhere.
    """
    if not sys.platform.startswith("linux"):
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):  # not glibc (musl has no mallopt)
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    return bool(mallopt(M_MMAP_MAX, 0)) and bool(mallopt(M_TRIM_THRESHOLD, 2**31 - 1))


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


def sizes(mesh: Mesh, levels: int, counts) -> list[tuple[int, int, int, int]]:
    """(V, E, F, H) of levels 0..levels from a scheme's ``counts`` recursion."""
    out = [(mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces, mesh.n_corners)]
    for _ in range(levels):
        out.append(tuple(int(x) for x in counts(*out[-1])))
    return out


def check_fits(mesh: Mesh, levels: int, counts, available: int | None = None) -> None:
    """Refuse, with the numbers, a subdivision whose levels would not fit in memory."""
    from ..errors import TooLargeError

    table = sizes(mesh, levels, counts)
    need = sum(BYTES_PER_CORNER * h for *_, h in table)
    have = available_memory() if available is None else available
    if need > have:
        last = table[-1]
        raise TooLargeError(
            f"level {levels} has {last[2]:,} faces and needs about {_gib(need)} of memory; "
            f"{_gib(have)} is available (level {_deepest(table, have)} would fit)")


def _deepest(table, have: int) -> int:
    total = 0
    for t, (*_, h) in enumerate(table):
        total += BYTES_PER_CORNER * h
        if total > have:
            return max(t - 1, 0)
    return len(table) - 1


def _gib(n: float) -> str:
    return f"{n / 2**30:,.1f} GiB" if n >= 2**30 else f"{n / 2**20:,.0f} MiB"
