"""The memory guard: refuses before any work, names the deepest level that fits, and its
windowed estimate follows the faces the window keeps."""

from __future__ import annotations

import numpy as np
import pytest

from weavecut import inputs
from weavecut.analysis import levels as lv
from weavecut.errors import TooLargeError
from weavecut.mesh import outer_vertices
from weavecut.subdivision import snub, subdivide
from weavecut.subdivision.hierarchy import check_fits, hierarchy_bytes, keep_freed_memory, sizes


def test_check_fits_names_the_deepest_level_that_fits():
    mesh = inputs.get("pentagon")
    table = sizes(mesh, 6, snub.counts)
    assert [f for _, _, f, _ in table] == [5 ** t for t in range(7)]
    check_fits(mesh, 6, snub.counts, available=hierarchy_bytes(table))
    with pytest.raises(TooLargeError, match=r"level 6 has 15,625 faces .*\(level 3 would fit\)"):
        check_fits(mesh, 6, snub.counts, available=hierarchy_bytes(table[:4]))
    with pytest.raises(TooLargeError, match="no level fits"):
        check_fits(mesh, 6, snub.counts, available=1)


def test_subdivide_refuses_before_refining(monkeypatch):
    monkeypatch.setattr("weavecut.budget.available_memory", lambda: 1 << 20)
    monkeypatch.setattr(snub, "step", lambda *a, **k: pytest.fail("refined anyway"))
    with pytest.raises(TooLargeError):
        subdivide(inputs.get("pentagon"), 12)


def test_window_covering_the_mesh_keeps_every_face():
    mesh = inputs.get("tiling-8-4:2x2")
    expect = [f for _, _, f, _ in sizes(mesh, 5, snub.counts)]
    assert lv.window_faces(mesh, 5, (-100.0, -100.0, 100.0, 100.0)) == expect


@pytest.mark.parametrize("window", [(0.05, 0.25, 0.2042, 0.4042), (-0.95, -0.85, -0.6, -0.5)])
def test_window_estimate_follows_the_patch(window):
    """The estimate is at least the faces the windowed refinement keeps, and not far above it
    once the halo is small against the window (it is made for the deep levels)."""
    mesh = inputs.get("pentagon")
    estimate = lv.window_faces(mesh, 8, window)
    patch = lv.Patch(mesh, np.ones(5, bool), np.ones(5, bool), outer_vertices(mesh).astype(np.int8))
    for t in range(1, 9):
        patch = lv._step(patch, window, lv.HALO, True, "vertex", "left")
        assert patch.mesh.n_faces <= estimate[t], t
    assert estimate[8] <= 2.5 * patch.mesh.n_faces


def test_guard_refuses_a_window_that_keeps_everything():
    mesh = inputs.get("pentagon")
    grid = lv.Grid.fit((-2.0, -2.0, 2.0, 2.0), 64)
    with pytest.raises(TooLargeError, match="of the window has 6,103,515,625 faces"):
        lv.check_memory(mesh, 14, grid, windowed=True, available=16 << 30)
    lv.check_memory(mesh, 8, grid, windowed=True, available=16 << 30)


def test_keep_freed_memory_keeps_results():
    keep_freed_memory()  # a process-wide allocator setting: results must not change
    mesh = inputs.get("pentagon")
    assert np.array_equal(snub.step(snub.step(mesh).mesh).mesh.vertices,
                          subdivide(mesh, 2)[-1].mesh.vertices)
