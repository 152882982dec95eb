"""Every classic scheme: consistent child topology, CCW faces, provenance of the right size."""

from __future__ import annotations

import numpy as np
import pytest
from .classic_meshes import any_meshes, assert_consistent, jittered_tri_grids
from hypothesis import given, settings

from weavecut.errors import MeshError
from weavecut.subdivision import SCHEMES, loop
from weavecut.subdivision._common import BLOCK, interleave

GENERAL = ["sqrt3", "catmull-clark", "midedge", "doo-sabin", "dual", "akleman"]


@pytest.mark.parametrize("name", GENERAL)
@settings(max_examples=30, deadline=None)
@given(mesh=any_meshes())
def test_general_schemes_build_valid_levels(name, mesh):
    level = SCHEMES[name](mesh)
    child = level.mesh
    assert_consistent(child)
    assert len(level.parent_face) == len(level.parent_corner) == child.n_faces
    assert len(level.parent_edge) == len(level.edge_part) == child.topology.n_edges
    if child.n_faces:
        assert_consistent(SCHEMES[name](child).mesh)


@pytest.mark.parametrize("name", ["loop", "butterfly"])
@settings(max_examples=30, deadline=None)
@given(mesh=jittered_tri_grids())
def test_triangle_schemes_build_valid_levels(name, mesh):
    level = SCHEMES[name](mesh)
    assert_consistent(level.mesh)
    assert_consistent(SCHEMES[name](level.mesh).mesh)
    # every child face lies in its parent face: each of its vertices is a corner of the parent
    # or the point of one of the parent's edges (edge e -> vertex V + e); a corner child
    # holds its parent corner, the middle child only edge points; four children a parent
    n_v, edges = mesh.n_vertices, mesh.topology.edges
    parents = mesh.face_indices.reshape(-1, 3).tolist()
    for child, f, i in zip(level.mesh.face_indices.reshape(-1, 3).tolist(),
                           level.parent_face.tolist(), level.parent_corner.tolist()):
        corners = set(parents[f])
        for x in child:
            assert (x in corners) if x < n_v else set(edges[x - n_v].tolist()) <= corners
        assert parents[f][i] in child if i >= 0 else min(child) >= n_v
    assert sorted(level.parent_face.tolist()) == [f for f in range(mesh.n_faces)
                                                  for _ in range(4)]


@pytest.mark.parametrize("name", ["loop", "butterfly"])
def test_triangle_schemes_refuse_quads(name):
    from .classic_meshes import quad_grid
    with pytest.raises(MeshError, match="3 corners"):
        SCHEMES[name](quad_grid(1, 1))


@pytest.mark.parametrize("name", GENERAL + ["loop", "butterfly"])
def test_counts_bound_the_next_level(name):
    import sys
    from .classic_meshes import tri_grid
    m = tri_grid(3, 2, jitter=0.1)
    c = SCHEMES[name](m).mesh
    bound = sys.modules[SCHEMES[name].__module__].counts(
        m.n_vertices, m.topology.n_edges, m.n_faces, m.n_corners)
    assert all(a <= b for a, b in zip((c.n_vertices, c.topology.n_edges, c.n_faces,
                                        c.n_corners), bound))


def test_registry_names_the_classic_schemes():
    assert {"snub", "loop", "butterfly", "sqrt3", "catmull-clark", "midedge", "doo-sabin",
            "dual", "akleman"} <= set(SCHEMES)
    assert SCHEMES["loop"] is loop.step


@pytest.mark.parametrize("n", [5, 2 * BLOCK + 7])  # several blocks, the last one partial
def test_interleave_puts_column_j_from_array_j(n):
    """Without ``out``: an (n, m) array of the first column's dtype whose column j is the j-th
    array (as np.column_stack puts them), over more rows than a block."""
    rng = np.random.default_rng(n)
    columns = [rng.integers(-1000, 1000, n).astype(np.int32), rng.integers(0, 1000, n)]
    got = interleave(columns)
    assert got.dtype == np.int32 and got.shape == (n, 2)
    np.testing.assert_array_equal(got, np.column_stack(columns))
    out = np.full((n, 3), -1, dtype=np.int64)
    assert interleave(np.stack([columns[1]] * 3), out=out) is out
    np.testing.assert_array_equal(out, np.column_stack([columns[1]] * 3))
