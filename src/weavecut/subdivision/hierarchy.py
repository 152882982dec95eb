"""Levels of a subdivision and their provenance."""

from __future__ import annotations

import ctypes
import sys
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..budget import BASE_BYTES, gib, memory_limit
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


# The memory guard's model, fitted to peak resident memory measured on this machine
# (benchmarks/bench_memory.py prints estimate and measurement side by side), on top of
# BASE_BYTES, the interpreter with weave-cut's imports:
LEVEL_BYTES_PER_CORNER = 38  # a level kept in a hierarchy: mesh, topology, provenance, the
                             # step's scratch while it is made and what commands add to it


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


def sizes(mesh: Mesh, levels: int, counts) -> list[tuple[int, int, int, int]]:
    """(V, E, F, H) of levels 0..levels from a scheme's ``counts`` recursion."""
    out = [(mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces, mesh.n_corners)]
    for _ in range(levels):
        out.append(tuple(int(x) for x in counts(*out[-1])))
    return out


def check_fits(mesh: Mesh, levels: int, counts, available: int | None = None) -> None:
    """Refuse, with the numbers, a subdivision whose levels would not fit in memory."""
    table = sizes(mesh, levels, counts)
    require([hierarchy_bytes(table[:t + 1]) for t in range(len(table))],
            [f for _, _, f, _ in table], available)


def hierarchy_bytes(table) -> int:
    """Estimated peak bytes of a process holding all levels of ``table`` ((V, E, F, H) rows)."""
    return BASE_BYTES + LEVEL_BYTES_PER_CORNER * sum(h for *_, h in table)


def require(need: list[int], faces: list[int], available: int | None = None,
            what: str = "") -> None:
    """Raise TooLargeError unless ``need[-1]`` bytes are available (``available``, else the
    lower of the free memory and the room under ``ulimit -v``); ``need[t]`` and ``faces[t]``
    are the estimated peak and the faces when stopping at level t (the message names the
    limit and the deepest level that would fit)."""
    from ..errors import TooLargeError

    have, source = memory_limit() if available is None else (available, "is available")
    if need[-1] <= have:
        return
    fits = [t for t, n in enumerate(need) if n <= have]
    hint = f"level {fits[-1]} would fit" if fits else "no level fits"
    raise TooLargeError(
        f"level {len(need) - 1}{what} has {faces[-1]:,} faces and needs about "
        f"{gib(need[-1])} of memory; {gib(have)} {source} ({hint})")
