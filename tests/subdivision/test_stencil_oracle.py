"""Every classic scheme's positions against the published stencils, written out independently in
``stencil_oracle`` (per vertex, plain loops), on meshes that hold inner vertices of valence
3, 4, 5, 6 and 7 and outer vertices of valence 2 to 8.

A plausible wrong weight (Warren's beta for Loop's, a boundary stencil applied to an inner
edge, the area centroid for the vertex mean) keeps every count and connection right; only the
positions show it, so every position of every child is compared here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial import Delaunay

from weavecut.mesh import Mesh
from weavecut.subdivision import akleman, butterfly, catmull_clark, doo_sabin, loop, sqrt3

from . import stencil_oracle as oracle
from .classic_meshes import fan, mixed, polygon, quad_grid, tri_grid

TOL = dict(rtol=1e-12, atol=1e-12)


def open_fan(k: int, *, quads: bool = False, seed: int = 0) -> Mesh:
    """k triangles (or quads) around vertex 0 spanning 150 degrees: vertex 0 is outer with
    k + 1 neighbours (k + 2 for quads' extra corners do not touch it: still k + 1)."""
    rng = np.random.default_rng(seed)
    a = np.linspace(0, 5 * np.pi / 6, k + 1)
    rim = np.column_stack([np.cos(a), np.sin(a)]) * rng.uniform(0.9, 1.1, (k + 1, 1))
    if not quads:
        return Mesh.from_faces(np.vstack([(0.0, 0.0), rim]),
                               [[0, 1 + i, 2 + i] for i in range(k)])
    b = (a[:-1] + a[1:]) / 2
    tips = 1.5 * np.column_stack([np.cos(b), np.sin(b)])
    v = np.vstack([(0.0, 0.0), rim, tips])
    return Mesh.from_faces(v, [[0, 1 + i, 2 + k + i, 2 + i] for i in range(k)])


def quad_star(k: int, seed: int = 0) -> Mesh:
    """k quads around inner vertex 0 (valence k), each (0, r_i, d_i, r_{i+1})."""
    rng = np.random.default_rng(seed)
    a = np.linspace(0, 2 * np.pi, k, endpoint=False)
    r = np.column_stack([np.cos(a), np.sin(a)]) * rng.uniform(0.9, 1.1, (k, 1))
    b = a + np.pi / k
    d = np.column_stack([np.cos(b), np.sin(b)]) * (1.2 / math.cos(math.pi / k))
    v = np.vstack([rng.uniform(-0.05, 0.05, 2), r, d])
    return Mesh.from_faces(v, [[0, 1 + i, 1 + k + i, 1 + (i + 1) % k] for i in range(k)])


def delaunay(seed: int, n: int = 40) -> Mesh:
    """A Delaunay triangulation of random points in a disc (valences 3 to 9 inside, 2 to 8 on
    its hull), faces turned counter-clockwise."""
    rng = np.random.default_rng(seed)
    r, t = np.sqrt(rng.uniform(0, 1, n)), rng.uniform(0, 2 * np.pi, n)
    v = np.column_stack([r * np.cos(t), r * np.sin(t)])
    tri = Delaunay(v).simplices
    a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
    cw = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0] < 0
    tri[cw] = tri[cw][:, [0, 2, 1]]
    return Mesh.from_faces(v, tri.tolist())


TRIANGLES = ([fan(k, centre=(0.07, -0.03), radii=1 + 0.05 * np.arange(k)) for k in (3, 4, 5, 7)]
             + [open_fan(k, seed=k) for k in range(1, 8)]
             + [delaunay(s) for s in range(4)] + [tri_grid(4, 3, jitter=0.15, seed=2)])
POLYGONS = ([quad_star(k, seed=k) for k in (3, 4, 5, 7)]
            + [open_fan(k, quads=True, seed=k) for k in range(1, 8)]
            + [quad_grid(3, 3, jitter=0.15, seed=1), mixed(), polygon(5)])


def adjacency(mesh: Mesh) -> oracle.Adjacency:
    return oracle.Adjacency(mesh.vertices.tolist(), [list(map(int, f)) for f in mesh.faces()])


def edge_index(mesh: Mesh) -> dict:
    """(u, w) with u < w -> the code's edge id (the documented numbering of child points)."""
    return {(int(u), int(w)): i for i, (u, w) in enumerate(mesh.topology.edges)}


def compare(got: np.ndarray, expected: dict, index) -> None:
    keys = sorted(expected)
    np.testing.assert_allclose(got[[index(k) for k in keys]],
                               np.array([expected[k] for k in keys]), **TOL)


def test_the_meshes_hold_every_valence():
    inner, outer = set(), set()
    for mesh in TRIANGLES:
        adj = adjacency(mesh)
        for v in range(len(adj.p)):
            (outer if v in adj.outer else inner).add(adj.valence(v))
    assert {3, 4, 5, 6, 7} <= inner
    assert set(range(2, 9)) <= outer
    quad_inner = {adjacency(m).valence(0) for m in POLYGONS[:4]}
    assert quad_inner == {3, 4, 5, 7}


def test_loops_beta_is_not_warrens_where_it_is_tested():
    """The oracle's weights tell the two published betas apart at valence 4, 5 and 7 (they
    agree at 3 and 6), so a switch of the code's beta is seen."""
    for n in (4, 5, 7):
        assert abs(oracle.loop_beta(n) - oracle.warren_beta(n)) > 1e-3
    for n in (3, 6):
        assert oracle.loop_beta(n) == pytest.approx(oracle.warren_beta(n))


@pytest.mark.parametrize("mesh", TRIANGLES)
def test_loop_positions(mesh):
    """Loop's own beta (loop.py documents Loop 1987, not Warren), Hoppe's boundary."""
    even, odd = oracle.loop(adjacency(mesh))
    child = loop.step(mesh).mesh.vertices
    ids = edge_index(mesh)
    compare(child, even, lambda v: v)
    compare(child, odd, lambda e: mesh.n_vertices + ids[e])


@pytest.mark.parametrize("mesh", TRIANGLES)
def test_butterfly_positions(mesh):
    points = oracle.butterfly(adjacency(mesh))
    child = butterfly.step(mesh).mesh.vertices
    ids = edge_index(mesh)
    np.testing.assert_array_equal(child[:mesh.n_vertices], mesh.vertices)
    compare(child, points, lambda e: mesh.n_vertices + ids[e])


@pytest.mark.parametrize("mesh", TRIANGLES + POLYGONS)
def test_sqrt3_positions(mesh):
    even, centres = oracle.sqrt3(adjacency(mesh))
    child = sqrt3.step(mesh).mesh.vertices
    compare(child, even, lambda v: v)
    compare(child, centres, lambda f: mesh.n_vertices + f)


@pytest.mark.parametrize("mesh", TRIANGLES + POLYGONS)
def test_catmull_clark_positions(mesh):
    vertex, edge, face = oracle.catmull_clark(adjacency(mesh))
    child = catmull_clark.step(mesh).mesh.vertices
    ids = edge_index(mesh)
    n_v, n_e = mesh.n_vertices, mesh.topology.n_edges
    compare(child, vertex, lambda v: v)
    compare(child, edge, lambda e: n_v + ids[e])
    compare(child, face, lambda f: n_v + n_e + f)


@pytest.mark.parametrize("mesh", TRIANGLES + POLYGONS)
def test_doo_sabin_positions(mesh):
    corners = oracle.doo_sabin(adjacency(mesh))
    child = doo_sabin.step(mesh).mesh.vertices
    compare(child, corners, lambda fi: int(mesh.face_offsets[fi[0]]) + fi[1])


@pytest.mark.parametrize("t", [0.5, 0.3])
@pytest.mark.parametrize("mesh", POLYGONS[:4] + POLYGONS[-3:])
def test_akleman_positions(mesh, t):
    copies = oracle.akleman(adjacency(mesh), t)
    child = akleman.step(mesh, t=t).mesh.vertices
    first = mesh.n_vertices + mesh.topology.n_edges
    compare(child, copies, lambda fi: first + int(mesh.face_offsets[fi[0]]) + fi[1])


def test_akleman_default_t_is_one_half():
    """akleman.py documents t = 1/2 when none is given."""
    mesh = quad_star(5)
    copies = oracle.akleman(adjacency(mesh), 0.5)
    child = akleman.step(mesh).mesh.vertices
    first = mesh.n_vertices + mesh.topology.n_edges
    compare(child, copies, lambda fi: first + int(mesh.face_offsets[fi[0]]) + fi[1])


@pytest.mark.parametrize("mesh", [quad_star(5), open_fan(4, quads=True)])
def test_second_step_on_a_child(mesh):
    """The child of an irregular quad mesh has irregular vertices next to each other: one
    more Catmull-Clark step still follows the stencils."""
    child = catmull_clark.step(mesh).mesh
    vertex, edge, face = oracle.catmull_clark(adjacency(child))
    grand = catmull_clark.step(child).mesh.vertices
    compare(grand, vertex, lambda v: v)
    compare(grand, edge, lambda e: child.n_vertices + edge_index(child)[e])
