"""The one-pass angle summary of ``stats`` equals the per-corner definitions."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from tests.strategies import valid_meshes
from weavecut import inputs
from weavecut.analysis import stats
from weavecut.mesh_geometry import corner_angles, edge_lengths
from weavecut.subdivision import subdivide


def _by_definition(mesh):
    angles = corner_angles(mesh)
    return float(angles.min()), float(angles.max()), int(stats.nonconvex_faces(mesh).sum())


@pytest.mark.parametrize("block", [7, stats.BLOCK])
def test_summary_equals_corner_angles_on_levels_with_reflex_corners(monkeypatch, block):
    monkeypatch.setattr(stats, "BLOCK", block)  # blocks that split the faces unevenly
    for lv in subdivide(inputs.get("ngon:24"), 3, smooth=False)[1:]:
        summary = stats.angle_summary(lv.mesh)
        assert summary == _by_definition(lv.mesh)
        assert np.isfinite(summary[:2]).all()
    assert summary[2] > 0


@settings(max_examples=30, deadline=None)
@given(valid_meshes)
def test_summary_and_boundary_length_on_random_meshes(mesh):
    assert stats.angle_summary(mesh) == _by_definition(mesh)
    b = mesh.topology.boundary_edges
    assert stats.boundary_length(mesh) == float(edge_lengths(mesh)[b].sum())
