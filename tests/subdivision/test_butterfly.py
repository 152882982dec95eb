"""Modified butterfly: interpolation, the 8-point stencil, extraordinary and boundary rules."""

from __future__ import annotations

import numpy as np
import pytest

from weavecut.subdivision import butterfly

from .classic_meshes import edge_id, fan, tri_grid


def test_old_vertices_stay_and_counts():
    m = tri_grid(3, 2, jitter=0.1)
    child = butterfly.step(m).mesh
    np.testing.assert_array_equal(child.vertices[:m.n_vertices], m.vertices)
    assert child.n_faces == 4 * m.n_faces


def test_regular_eight_point_stencil():
    m = tri_grid(4, 4, jitter=0.15, seed=3)
    p = lambda i, j: m.vertices[j * 5 + i]  # noqa: E731
    e = edge_id(m, 2 * 5 + 2, 2 * 5 + 3)     # (2, 2) - (3, 2), both ends inner, valence 6
    expected = (0.5 * (p(2, 2) + p(3, 2)) + 0.125 * (p(3, 3) + p(2, 1))
                - 0.0625 * (p(4, 3) + p(2, 3) + p(1, 1) + p(3, 1)))
    np.testing.assert_allclose(butterfly.step(m).mesh.vertices[m.n_vertices + e], expected)


@pytest.mark.parametrize("k", [3, 4, 5, 7])
def test_extraordinary_ring_stencil(k):
    m = fan(k, centre=(0.1, -0.05), radii=1 + 0.1 * np.arange(k))
    s = butterfly.ring_weights(k)
    rim = m.vertices[1:]
    e = edge_id(m, 0, 1)
    expected = 0.75 * m.vertices[0] + (s[:, None] * rim).sum(axis=0)
    np.testing.assert_allclose(butterfly.step(m).mesh.vertices[m.n_vertices + e], expected)


def test_boundary_four_point_rule():
    m = fan(5, radii=[1.0, 1.2, 0.9, 1.1, 1.0])
    rim = m.vertices[1:]
    e = edge_id(m, 2, 3)                     # rim 1 - rim 2, boundary runs rim 0, 1, 2, 3
    expected = (9 * (rim[1] + rim[2]) - rim[0] - rim[3]) / 16
    np.testing.assert_allclose(butterfly.step(m).mesh.vertices[m.n_vertices + e], expected)


def test_weights_sum_to_one():
    for k in range(3, 12):
        assert butterfly.ring_weights(k).sum() == pytest.approx(0.25)


def flipped_grid():
    """A jittered 4 x 4 triangle grid with one inner diagonal flipped: two inner vertices of
    valence 5, two of valence 7 joined by the new edge, regular ones beside them, and the
    grid's outer rows (inner edges with one or two outer ends)."""
    from weavecut.mesh import Mesh
    m = tri_grid(4, 4, jitter=0.08, seed=5)
    faces = [list(f) for f in m.faces()]
    a, c = 2 * 5 + 2, 3 * 5 + 3        # diagonal (2, 2) - (3, 3) of cell (2, 2)
    b, d = 2 * 5 + 3, 3 * 5 + 2
    faces = [f for f in faces if not {a, c} <= set(f)] + [[a, b, d], [b, c, d]]
    return Mesh.from_faces(m.vertices, faces)


def reference_edge_point(mesh, u, w):
    """The module docstring's rules, by loops: neighbours sorted counter-clockwise by angle."""
    v = mesh.vertices
    nbrs = {}
    faces_of = {}
    for k, f in enumerate(mesh.faces()):
        for i, p in enumerate(f):
            nbrs.setdefault(p, set()).update({f[i - 1], f[(i + 1) % 3]})
            faces_of.setdefault(p, []).append(k)
    directed = {(f[i], f[(i + 1) % 3]) for f in mesh.faces() for i in range(3)}
    outer = {p for a, b in directed if (b, a) not in directed for p in (a, b)}
    opposite = [next(x for x in f if x not in (u, w)) for f in mesh.faces()
                if u in f and w in f]
    if len(opposite) == 1:  # outer edge: 4-point rule along the boundary
        a, b = (u, w) if (u, w) in directed else (w, u)
        p = next(x for x in nbrs[a] if (x, a) in directed and (a, x) not in directed)
        q = next(x for x in nbrs[b] if (b, x) in directed and (x, b) not in directed)
        return (9 * (v[a] + v[b]) - v[p] - v[q]) / 16

    def regular(p):
        return p not in outer and len(nbrs[p]) == 6

    def ring(a, b):  # 3/4 a + sum s_j n_j, n_0 = b, counter-clockwise
        ang = {x: np.arctan2(*(v[x] - v[a])[::-1]) for x in nbrs[a]}
        order = sorted(nbrs[a], key=lambda x: (ang[x] - ang[b]) % (2 * np.pi))
        return 0.75 * v[a] + sum(s * v[x] for s, x in zip(butterfly.ring_weights(len(order)),
                                                          order))
    if regular(u) and regular(w):
        c, d = opposite
        wings = [next(x for x in mesh.faces()[k] if x not in (p, q)) for p, q in
                 [(u, c), (w, c), (u, d), (w, d)] for k in set(faces_of[p]) & set(faces_of[q])
                 if not {u, w} <= set(mesh.faces()[k])]
        return (0.5 * (v[u] + v[w]) + 0.125 * (v[c] + v[d]) - 0.0625 * sum(v[x] for x in wings))
    used = [p for p in (u, w) if p not in outer and not regular(p)] or \
        [p for p in (u, w) if p not in outer]
    if not used:  # both ends outer: Loop's edge rule
        return 0.375 * (v[u] + v[w]) + 0.125 * sum(v[x] for x in opposite)
    return sum(ring(p, w if p == u else u) for p in used) / len(used)


def test_every_edge_point_follows_the_documented_rule():
    m = flipped_grid()
    child = butterfly.step(m).mesh
    for e, (u, w) in enumerate(m.topology.edges.tolist()):
        np.testing.assert_allclose(child.vertices[m.n_vertices + e],
                                   reference_edge_point(m, u, w), atol=1e-12, err_msg=str((u, w)))
    valence = np.bincount(m.topology.edges.ravel())
    assert {5, 7} <= set(valence.tolist())


@pytest.mark.parametrize("k", range(3, 12))
def test_ring_weights_have_zorins_fourier_coefficients(k):
    """Zorin et al. chose s_j so that the stencil passes the first harmonics of the ring with
    the factors 1/4, 1/2, 1/4 (the subdivision matrix's eigenvalues 1, 1/2, 1/4) and no
    higher one."""
    s = butterfly.ring_weights(k)
    theta = 2 * np.pi * np.arange(k) / k
    want = {0: 0.25, 1: 0.5, 2: 0.25}
    for m in range(0, k // 2 + 1):
        assert (s * np.cos(m * theta)).sum() == pytest.approx(want.get(m, 0.0), abs=1e-12), m
