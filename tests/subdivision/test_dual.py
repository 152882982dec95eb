"""The dual: centroid vertices, one face per inner vertex, hexagons after Loop."""

from __future__ import annotations

import numpy as np

from weavecut.mesh_geometry import face_centroids
from weavecut.subdivision import dual, loop

from .classic_meshes import tri_grid


def test_dual_of_a_loop_level_is_hexagon_dominant():
    m = loop.step(tri_grid(3, 3)).mesh
    d = dual.step(m).mesh
    np.testing.assert_allclose(d.vertices, face_centroids(m))
    sizes = np.bincount(d.face_sizes)
    assert sizes.argmax() == 6
    inner = np.ones(m.n_vertices, bool)
    inner[m.topology.edges[m.topology.boundary_edges].ravel()] = False
    assert d.n_faces == inner.sum()
