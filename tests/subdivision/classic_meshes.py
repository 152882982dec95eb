"""Small meshes and hypothesis strategies for the classic schemes and their weaves."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from weavecut.mesh import Mesh, Topology
from weavecut.mesh_geometry import signed_areas


def grid_points(n: int, m: int, jitter: float = 0.0, seed: int = 0) -> np.ndarray:
    x, y = np.meshgrid(np.arange(n + 1, dtype=float), np.arange(m + 1, dtype=float))
    v = np.column_stack([x.ravel(), y.ravel()])
    return v + np.random.default_rng(seed).uniform(-jitter, jitter, v.shape)


def quad_grid(n: int, m: int, jitter: float = 0.0, seed: int = 0) -> Mesh:
    """n x m quads; vertex (i, j) has id j * (n + 1) + i."""
    idx = np.arange((n + 1) * (m + 1)).reshape(m + 1, n + 1)
    q = np.column_stack([idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, 1:].ravel(),
                         idx[1:, :-1].ravel()])
    return Mesh(grid_points(n, m, jitter, seed), np.arange(0, q.size + 1, 4), q.ravel())


def tri_grid(n: int, m: int, jitter: float = 0.0, seed: int = 0) -> Mesh:
    """n x m cells, each split along its (i, j) - (i + 1, j + 1) diagonal."""
    idx = np.arange((n + 1) * (m + 1)).reshape(m + 1, n + 1)
    a, b, c, d = (idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, 1:].ravel(),
                  idx[1:, :-1].ravel())
    t = np.stack([np.column_stack([a, b, c]), np.column_stack([a, c, d])], axis=1).ravel()
    return Mesh(grid_points(n, m, jitter, seed), np.arange(0, t.size + 1, 3), t)


def fan(k: int, centre=(0.0, 0.0), angles=None, radii=None) -> Mesh:
    """k triangles around vertex 0; rim vertex i + 1 at angle i (counter-clockwise)."""
    a = np.linspace(0, 2 * np.pi, k, endpoint=False) if angles is None else np.asarray(angles)
    r = np.ones(k) if radii is None else np.asarray(radii)
    v = np.vstack([centre, np.column_stack([r * np.cos(a), r * np.sin(a)])])
    return Mesh.from_faces(v, [[0, 1 + i, 1 + (i + 1) % k] for i in range(k)])


def polygon(k: int) -> Mesh:
    a = np.linspace(0, 2 * np.pi, k, endpoint=False)
    return Mesh.from_faces(np.column_stack([np.cos(a), np.sin(a)]), [list(range(k))])


def mixed() -> Mesh:
    """Two quads and two triangles around inner vertex 4."""
    return Mesh.from_faces([(0, 0), (1, 0), (2, 0), (0, 1), (1, 1.1), (2, 1.2), (1, 2)],
                           [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 6], [4, 5, 6]])


@st.composite
def jittered_tri_grids(draw) -> Mesh:
    n, m = draw(st.integers(1, 4)), draw(st.integers(1, 4))
    return tri_grid(n, m, draw(st.floats(0, 0.2)), draw(st.integers(0, 999)))


@st.composite
def jittered_quad_grids(draw) -> Mesh:
    n, m = draw(st.integers(1, 4)), draw(st.integers(1, 4))
    return quad_grid(n, m, draw(st.floats(0, 0.2)), draw(st.integers(0, 999)))


@st.composite
def convex_fans(draw) -> Mesh:
    """A fan around an inner point of a convex polygon (every gap below pi)."""
    k = draw(st.integers(3, 9))
    gaps = np.array(draw(st.lists(st.floats(0.3, 1.0), min_size=k, max_size=k)))
    gaps = gaps / gaps.sum() * 2 * np.pi
    if gaps.max() >= 0.95 * np.pi:
        gaps = np.full(k, 2 * np.pi / k)
    radii = draw(st.lists(st.floats(0.8, 1.2), min_size=k, max_size=k))
    return fan(k, angles=np.cumsum(gaps) - gaps[0], radii=radii)


def any_meshes():
    return st.one_of(jittered_tri_grids(), jittered_quad_grids(), convex_fans(),
                     st.sampled_from([mixed(), polygon(5), polygon(3)]))


def assert_consistent(mesh: Mesh) -> None:
    """The topology a step attached equals one built from scratch; faces are CCW."""
    fresh = Topology.build(Mesh(mesh.vertices, mesh.face_offsets, mesh.face_indices))
    topo = mesh.topology
    assert topo.n_edges == fresh.n_edges
    np.testing.assert_array_equal(topo.edges[topo.half_edge_edge],
                                  fresh.edges[fresh.half_edge_edge])
    np.testing.assert_array_equal(topo.half_edge_side, fresh.half_edge_side)
    np.testing.assert_array_equal(topo.boundary_edges[topo.half_edge_edge],
                                  fresh.boundary_edges[fresh.half_edge_edge])
    assert (signed_areas(mesh) > 0).all()


def edge_id(mesh: Mesh, u: int, w: int) -> int:
    e = mesh.topology.edges
    return int(np.flatnonzero((e[:, 0] == min(u, w)) & (e[:, 1] == max(u, w)))[0])
