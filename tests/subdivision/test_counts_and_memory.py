"""What the memory guard is built from, against its definitions: every scheme's ``counts``
against the levels it really makes (exact where the module says so, an upper bound with at most
two half-edges per edge where it says "upper bounds"), the byte estimate and its message,
the reading of /proc/meminfo and the allocator setting; and ``subdivide``'s own arguments."""

from __future__ import annotations

import io
import re
import sys

import numpy as np
import pytest

from weavecut import budget, inputs
from weavecut.budget import available_memory
from weavecut.errors import TooLargeError
from weavecut.mesh import Topology
from weavecut.subdivision import SCHEMES, _counts, hierarchy, snub, subdivide
from weavecut.subdivision.hierarchy import (
    BASE_BYTES, LEVEL_BYTES_PER_CORNER, check_fits, hierarchy_bytes,
    keep_freed_memory, require, sizes,
)

from .classic_meshes import mixed, quad_grid, tri_grid

EXACT = {"snub", "loop", "butterfly", "catmull-clark", "sqrt3", "akleman"}
TRIANGLES_ONLY = {"loop", "butterfly"}


def four_counts(mesh):
    return (mesh.n_vertices, Topology.build(mesh).n_edges, mesh.n_faces, mesh.n_corners)


@pytest.mark.parametrize("name", sorted(SCHEMES))
@pytest.mark.parametrize("make", [lambda: tri_grid(3, 2, jitter=0.1), lambda: quad_grid(3, 2),
                                  mixed, lambda: inputs.get("pentagon-flower")],
                         ids=["tri-grid", "quad-grid", "mixed", "pentagon-flower"])
def test_counts_give_the_sizes_of_the_next_level(name, make):
    mesh = make()
    if name in TRIANGLES_ONLY and mesh.face_degree != 3:
        return
    counts = _counts(name)
    assert counts is sys.modules[SCHEMES[name].__module__].counts
    got = four_counts(SCHEMES[name](mesh).mesh)
    bound = counts(*four_counts(mesh))
    if name in EXACT:
        assert bound == got
    else:  # V', E', F' bounded; H' bounded by two half-edges per bounded edge
        assert all(g <= b for g, b in zip(got, bound)), (got, bound)
        assert bound[3] == 2 * bound[1]


def test_snub_counts_are_equation_2():
    """V' = V + 2E + F, E' = 3E + H, F' = H, and every child face a pentagon."""
    for v, e, f, h in [(5, 5, 1, 5), (16, 20, 5, 25), (7, 10, 4, 14), (1, 2, 3, 4)]:
        assert snub.counts(v, e, f, h) == (v + 2 * e + f, 3 * e + h, h, 5 * h)


def test_sizes_and_bytes_follow_the_recursion():
    mesh = inputs.get("pentagon-flower")
    table = sizes(mesh, 3, snub.counts)
    want = [four_counts(lv.mesh) for lv in subdivide(mesh, 3)]
    assert table == want
    corners = sum(h for *_, h in want)
    assert hierarchy_bytes(table) == BASE_BYTES + LEVEL_BYTES_PER_CORNER * corners


@pytest.mark.parametrize("n, text", [
    (0, "0 MiB"), (5 << 20, "5 MiB"), (1536 << 20, "1.5 GiB"), ((1 << 30) - (1 << 20),
                                                                  "1,023 MiB"),
    (1 << 30, "1.0 GiB"), (3 << 30, "3.0 GiB"), (1234 << 30, "1,234.0 GiB"),
])
def test_gib_prints_mib_below_one_gib_and_gib_from_there(n, text):
    assert budget.gib(n) == text


def test_require_names_the_last_level_its_need_and_the_deepest_that_fits():
    need = [100 << 20, 700 << 20, 3 << 30]
    require(need, [1, 5, 25], available=3 << 30)  # exactly enough
    with pytest.raises(TooLargeError) as info:
        require(need, [1, 5, 25], available=1 << 30, what=" of the window")
    assert str(info.value) == ("level 2 of the window has 25 faces and needs about 3.0 GiB of "
                               "memory; 1.0 GiB is available (level 1 would fit)")
    with pytest.raises(TooLargeError) as info:
        require(need, [1, 5, 25], available=50 << 20)
    assert str(info.value) == ("level 2 has 25 faces and needs about 3.0 GiB of memory; 50 MiB "
                               "is available (no level fits)")
    with pytest.raises(TooLargeError):  # only the last level counts
        require([1 << 40, 1, 1 << 40], [1, 1, 1], available=1 << 30)


def test_check_fits_estimates_from_the_scheme_counts():
    mesh = inputs.get("pentagon")
    table = sizes(mesh, 4, snub.counts)
    need = hierarchy_bytes(table)
    check_fits(mesh, 4, snub.counts, available=need)
    with pytest.raises(TooLargeError, match=r"^level 4 has 625 faces"):
        check_fits(mesh, 4, snub.counts, available=need - 1)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc/meminfo")
def test_available_memory_reads_memavailable_in_kib():
    with open("/proc/meminfo") as f:
        kib = int(re.search(r"^MemAvailable:\s+(\d+) kB$", f.read(), re.M).group(1))
    assert abs(available_memory() - kib * 1024) < 256 << 20  # it changes between the reads


def test_available_memory_falls_back_to_8_gib(monkeypatch):
    def unreadable(*_args, **_kwargs):
        raise OSError("no /proc")

    monkeypatch.setattr(budget, "open", unreadable, raising=False)
    assert available_memory() == 8 << 30
    monkeypatch.setattr(budget, "open", lambda *a, **k: io.StringIO("MemTotal: 5 kB\n"),
                        raising=False)
    assert available_memory() == 8 << 30
    monkeypatch.setattr(budget, "open", lambda *a, **k: io.StringIO(
        "MemTotal:  9 kB\nMemAvailable:    3 kB\n"), raising=False)
    assert available_memory() == 3 * 1024


class FakeLibc:
    """Records mallopt calls; answers ``result`` (glibc: 1 on success, 0 on failure)."""

    def __init__(self, result=1):
        self.calls, self.result = [], result

    def __call__(self, _name):
        return self

    @property
    def mallopt(self):
        def mallopt(param, value):
            self.calls.append((param, value))
            return self.result
        return mallopt


def test_keep_freed_memory_turns_off_mmap_and_trimming(monkeypatch):
    """The same as MALLOC_MMAP_MAX_=0 MALLOC_TRIM_THRESHOLD_=2147483647 (malloc.h: M_MMAP_MAX
    is -4, M_TRIM_THRESHOLD -1)."""
    monkeypatch.setattr(sys, "platform", "linux")
    libc = FakeLibc()
    monkeypatch.setattr(hierarchy.ctypes, "CDLL", libc)
    assert keep_freed_memory() is True
    assert libc.calls == [(-4, 0), (-1, 2147483647)]
    failing = FakeLibc(result=0)
    monkeypatch.setattr(hierarchy.ctypes, "CDLL", failing)
    assert keep_freed_memory() is False


def test_keep_freed_memory_changes_nothing_off_glibc(monkeypatch):
    libc = FakeLibc()
    monkeypatch.setattr(hierarchy.ctypes, "CDLL", libc)
    monkeypatch.setattr(sys, "platform", "darwin")
    assert keep_freed_memory() is False
    assert libc.calls == []

    def no_libc(_name):
        raise OSError("no libc")

    monkeypatch.setattr(sys, "platform", "linux")
    monkeypatch.setattr(hierarchy.ctypes, "CDLL", no_libc)
    assert keep_freed_memory() is False


def test_subdivide_level_0_is_the_input_alone():
    mesh = inputs.get("pentagon")
    (only,) = subdivide(mesh, 0)
    assert only.mesh is mesh and only.parent_face is None and only.edge_part is None


def test_subdivide_runs_one_step_per_item_of_steps():
    seen = []

    def progress(n):
        for i in range(n):
            seen.append(i)
            yield i

    hierarchy_ = subdivide(inputs.get("pentagon"), 2, steps=progress(2))
    assert seen == [0, 1] and len(hierarchy_) == 3
    np.testing.assert_array_equal(hierarchy_[2].mesh.vertices,
                                  subdivide(inputs.get("pentagon"), 2)[2].mesh.vertices)


def test_subdivide_refuses_bad_arguments_by_name():
    with pytest.raises(ValueError, match=r"^levels must be >= 0, got -1$"):
        subdivide(inputs.get("pentagon"), -1)
    with pytest.raises(ValueError, match=r"^unknown scheme 'hex'; choose one of snub, loop, "
                                         r"butterfly, sqrt3, catmull-clark, midedge, doo-sabin, "
                                         r"dual, akleman$"):
        subdivide(inputs.get("pentagon"), 1, scheme="hex")


def test_upper_bounds_are_the_exact_counts_in_the_worst_case():
    """Mid-edge and Doo-Sabin bound from V, E, F, H alone: their exact counts with every
    vertex kept (mid-edge: all outer in two or more faces) or every edge and vertex inner
    (Doo-Sabin), and two half-edges per edge; the dual: every edge and vertex inner."""
    from weavecut.subdivision import doo_sabin, dual, midedge
    for v, e, f, h in [(7, 10, 4, 14), (9, 12, 4, 16), (16, 20, 5, 25)]:
        vm, em, fm = midedge.exact_counts(e, f, h, 0, v)
        assert midedge.counts(v, e, f, h) == (vm, em, fm, 2 * em)
        vd, ed, fd = doo_sabin.exact_counts(f, h, e, v)
        assert doo_sabin.counts(v, e, f, h) == (vd, ed, fd, 2 * ed)
        assert dual.counts(v, e, f, h) == (f, e, v, 2 * e)


def test_midedge_bound_is_reached_when_every_vertex_is_kept():
    """A ring of quads: every vertex is outer and in two faces, so mid-edge keeps them all."""
    from weavecut.mesh import Mesh
    from weavecut.subdivision import midedge
    n = 6
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    ring = np.vstack([np.column_stack([np.cos(a), np.sin(a)]),
                      2 * np.column_stack([np.cos(a), np.sin(a)])])
    quads = [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    mesh = Mesh.from_faces(ring, quads)
    got = four_counts(midedge.step(mesh).mesh)
    assert got[:3] == midedge.counts(*four_counts(mesh))[:3]


@pytest.mark.parametrize("name, message", [
    ("loop", "Loop subdivision needs faces with 3 corners; face 1 has 4"),
    ("butterfly", "butterfly subdivision needs faces with 3 corners; face 1 has 4"),
])
def test_triangle_schemes_name_themselves_and_the_first_other_face(name, message):
    from weavecut.errors import MeshError
    from weavecut.mesh import Mesh
    mesh = Mesh.from_faces([(0, 0), (1, 0), (0, 1), (1, 1), (0, 2)],
                           [[0, 1, 2], [2, 1, 3, 4]])
    with pytest.raises(MeshError, match=f"^{message}$"):
        SCHEMES[name](mesh)


@pytest.mark.parametrize("t", [0.0, 1.0, 1.5, -0.2])
def test_akleman_refuses_t_outside_the_open_unit_interval(t):
    from weavecut.subdivision import akleman
    with pytest.raises(ValueError, match=rf"^t must lie strictly between 0 and 1, got {t}$"):
        akleman.step(mixed(), t=t)
    assert akleman.step(mixed(), t=0.999).mesh.n_faces == mixed().n_faces + mixed().n_corners
