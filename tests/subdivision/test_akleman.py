"""Akleman et al.'s pentagon-preserving step: counts, pentagons stay pentagons, convexity."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings

from weavecut.mesh_geometry import corner_turns
from weavecut.subdivision import akleman

from .classic_meshes import any_meshes, polygon


@settings(max_examples=30, deadline=None)
@given(mesh=any_meshes())
def test_counts_and_convex_children(mesh):
    c = akleman.step(mesh).mesh
    assert (c.n_vertices, c.topology.n_edges, c.n_faces, c.n_corners) == akleman.counts(
        mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces, mesh.n_corners)
    if (corner_turns(mesh) > 0).all():
        assert (corner_turns(c) > -1e-12).all()
    assert (c.face_sizes[mesh.n_faces:] == 5).all()


def test_a_pentagon_stays_a_pentagon_mesh():
    c = akleman.step(akleman.step(polygon(5)).mesh).mesh
    assert c.face_degree == 5
    assert c.n_faces == 36
    assert np.isfinite(c.vertices).all()
