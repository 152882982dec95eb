"""Quad, glued-triangle, sqrt(3) and face-split weaves against an oracle that walks each strand
quad by quad with dictionaries (paper 5.3): a strand crosses every quad from an edge to the
opposite one, goes on to the quad on the other side of that edge, and is on top where it
enters through a half-edge a -> b of the counter-clockwise quad with a of colour c1.

The quads are found from the faces alone (glue edges: c2-c2 edges of a triangle weave, centre
to centre edges of a sqrt(3) level; the face split's (u, c_g, w, c_f)), and tiles are compared
by their corner vertices, so no numbering of the library's enters the comparison."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from weavecut import inputs
from weavecut.mesh import Mesh
from weavecut.subdivision import catmull_clark, loop, sqrt3
from weavecut.weave.face_split import face_split_weave
from weavecut.weave.quad import quad_weave
from weavecut.weave.triangles import sqrt3_weave, triangle_weave
from weavecut.weave.two_colouring import (
    catmull_clark_colouring,
    disc_two_colouring,
    triangle_colouring_step,
    triangle_three_colouring,
)

from ..subdivision.classic_meshes import any_meshes, jittered_quad_grids, polygon, quad_grid
from .test_triangle_weaves import split_quads


def canonical(seq: list, closed: bool) -> tuple:
    """A strand's visits up to walking direction (and starting point, when closed)."""
    runs = [seq, seq[::-1]]
    if closed:
        runs = [r[i:] + r[:i] for r in runs for i in range(len(r))]
    return (closed, min(tuple(r) for r in runs))


def walked_strands(quads: list[tuple[int, int, int, int]], c1) -> list[tuple]:
    """Every strand of the quads (counter-clockwise corner tuples) as canonical visits of
    (sorted corners, on top)."""
    by_edge: dict[frozenset, list[tuple[int, int]]] = {}
    for t, q in enumerate(quads):
        for k in range(4):
            by_edge.setdefault(frozenset((q[k], q[(k + 1) % 4])), []).append((t, k))

    def across(t: int, k: int):
        """The (tile, edge position) on the other side of edge k of tile t, or None."""
        q = quads[t]
        others = [s for s in by_edge[frozenset((q[k], q[(k + 1) % 4]))] if s != (t, k)]
        return others[0] if others else None

    def visit(t, k):
        return (tuple(sorted(quads[t])), bool(c1[quads[t][k]]))

    seen: set[tuple[int, int]] = set()  # (tile, entry edge mod 2): one pass of a strand
    out = []
    for t0 in range(len(quads)):
        for k0 in (0, 1):
            if (t0, k0) in seen:
                continue
            # walk forward (entering through k0), then backward (entering through k0 + 2)
            runs, closed = [], False
            for start in (k0, k0 + 2):
                run, t, k = [], t0, start
                while True:
                    if run and (t, k) == (t0, start):
                        closed = True
                        break
                    seen.add((t, k % 2))
                    run.append(visit(t, k))
                    nxt = across(t, (k + 2) % 4)
                    if nxt is None:
                        break
                    t, k = nxt
                runs.append(run)
                if closed:
                    break
            seq = runs[0] if closed else runs[1][::-1] + runs[0][1:]
            out.append(canonical(seq, closed))
    return sorted(out, key=repr)


def library_strands(weave) -> list[tuple]:
    faces = weave.mesh.faces()
    tile_corners = [tuple(sorted({v for f in weave.tile_faces[a:b].tolist() for v in faces[f]}))
                    for a, b in zip(weave.tile_offsets[:-1], weave.tile_offsets[1:])]
    out = []
    for s in range(weave.n_strands):
        tiles, over = weave.strand(s)
        seq = [(tile_corners[t], bool(o)) for t, o in zip(tiles.tolist(), over.tolist())]
        out.append(canonical(seq, bool(weave.strand_closed[s])))
    return sorted(out, key=repr)


def glued_quads(mesh: Mesh, glue) -> list[tuple[int, int, int, int]]:
    """(p, a, q, b) for every inner glue edge a - b with p, q the far corners of its two
    triangles, found by a loop over the faces; ``glue(a, b)`` says which edges are glued."""
    left = {}
    for f in mesh.faces():
        for i in range(3):
            left[(f[i], f[(i + 1) % 3])] = f[(i + 2) % 3]
    return [(p, a, left[(b, a)], b) for (a, b), p in left.items()
            if a < b and (b, a) in left and glue(a, b)]


def check(weave, quads, c1):
    assert library_strands(weave) == walked_strands(quads, c1)
    # the array types the Weave documents
    assert [a.dtype for a in (weave.tile_offsets, weave.tile_faces, weave.strand_offsets,
                              weave.strand_visits, weave.visit_over, weave.strand_closed)] == \
        [np.int64, np.int32, np.int64, np.int32, np.bool_, np.bool_]


@settings(deadline=None)
@given(mesh=jittered_quad_grids())
def test_quad_weave_walks_like_the_oracle(mesh):
    c1 = disc_two_colouring(mesh)
    check(quad_weave(mesh, c1), [tuple(f) for f in mesh.faces()], c1)
    check(quad_weave(mesh, c1.astype(np.int64)), [tuple(f) for f in mesh.faces()], c1)


@settings(deadline=None)
@given(mesh=any_meshes())
def test_catmull_clark_weave_walks_like_the_oracle(mesh):
    level = catmull_clark.step(mesh)
    c1 = catmull_clark_colouring(level)
    assert c1.dtype == bool
    # edge points are c1: numbered after the old vertices, before the face points
    n_v, n_e = mesh.n_vertices, mesh.topology.n_edges
    np.testing.assert_array_equal(np.flatnonzero(c1), np.arange(n_v, n_v + n_e))
    check(quad_weave(level.mesh, c1), [tuple(f) for f in level.mesh.faces()], c1)


@pytest.mark.parametrize("mesh", [split_quads(3, 2)[0], split_quads(1, 1)[0],
                                  inputs.get("triangulated-ngon:6")],
                         ids=["split-3x2", "split-1x1", "ngon-6"])
def test_triangle_weave_walks_like_the_oracle(mesh):
    c1 = triangle_three_colouring(mesh)
    for _ in range(2):
        quads = glued_quads(mesh, lambda a, b: not c1[a] and not c1[b])
        check(triangle_weave(mesh, c1), quads, c1)
        c1 = triangle_colouring_step(mesh, c1)
        mesh = loop.step(mesh).mesh


@pytest.mark.parametrize("name", ["triangle-grid:3x2", "triangulated-ngon:5",
                                  "triangulated-ngon:8"])
def test_sqrt3_weave_walks_like_the_oracle(name):
    mesh = inputs.get(name)
    level = sqrt3.step(mesh)
    n = mesh.n_vertices
    c1 = np.arange(level.mesh.n_vertices) < n
    quads = glued_quads(level.mesh, lambda a, b: a >= n and b >= n)  # centre to centre
    assert quads
    check(sqrt3_weave(level, n), quads, c1)


@settings(deadline=None)
@given(mesh=any_meshes())
def test_face_split_weave_walks_like_the_oracle(mesh):
    n = mesh.n_vertices
    left = {(f[i], f[(i + 1) % len(f)]): face for face, f in enumerate(mesh.faces())
            for i in range(len(f))}
    quads = [(u, n + left[(w, u)], w, n + f) for (u, w), f in left.items()
             if u < w and (w, u) in left]
    weave = face_split_weave(mesh)
    c1 = np.arange(weave.mesh.n_vertices) < n
    # the centres are the vertex means of the faces
    np.testing.assert_allclose(weave.mesh.vertices[n:],
                               [mesh.vertices[f].mean(axis=0) for f in mesh.faces()])
    check(weave, quads, c1)


def test_a_quad_grid_has_its_rows_and_columns_as_strands():
    """On a 4 x 3 grid the strands are the 3 rows and 4 columns, each open, alternating."""
    mesh = quad_grid(4, 3)
    strands = library_strands(quad_weave(mesh, disc_two_colouring(mesh)))
    assert sorted(len(seq) for _, seq in strands) == [3, 3, 3, 3, 4, 4, 4]
    assert not any(closed for closed, _ in strands)


def glue_turned(mesh: Mesh, c1) -> Mesh:
    """The mesh with every triangle renumbered to start at its glue edge (c2-c2), and a
    triangle whose glue edge runs from the higher vertex to the lower one moved first, so
    that half-edge 0 is the falling half of an inner glue edge."""
    turned = []
    for f in mesh.faces():
        i = next(i for i in range(3) if not c1[f[i]] and not c1[f[(i + 1) % 3]])
        turned.append(f[i:] + f[:i])
    inner = {(f[i], f[(i + 1) % 3]) for f in turned for i in range(3)}
    first = next(k for k, f in enumerate(turned) if f[0] > f[1] and (f[1], f[0]) in inner)
    turned.insert(0, turned.pop(first))
    return Mesh.from_faces(mesh.vertices, turned)


@pytest.mark.parametrize("turn", [False, True])
def test_glued_tiles_list_the_face_left_of_the_rising_glue_half_edge_first(turn):
    """Tile k is the k-th glue edge; its first face has the glue edge from the lower vertex
    to the higher one, the second face the other way."""
    mesh = split_quads(3, 2)[0]
    c1 = triangle_three_colouring(mesh)
    if turn:
        mesh = glue_turned(mesh, c1)
    weave = triangle_weave(mesh, c1)
    faces = mesh.faces()

    def runs(f, a, b):
        return any(f[i] == a and f[(i + 1) % 3] == b for i in range(3))

    tiles = weave.tile_faces.reshape(-1, 2).tolist()
    assert len(tiles) == len(glued_quads(mesh, lambda a, b: not c1[a] and not c1[b]))
    for first, second in tiles:
        shared = sorted(set(faces[first]) & set(faces[second]))
        assert not c1[shared].any()
        lo, hi = shared
        assert runs(faces[first], lo, hi) and runs(faces[second], hi, lo)
    check(weave, glued_quads(mesh, lambda a, b: not c1[a] and not c1[b]), c1)


def test_a_weave_without_tiles_has_no_strands():
    weave = face_split_weave(polygon(5))  # one face: no inner edge, no quad
    assert weave.n_tiles == weave.n_strands == 0
    assert weave.strand_closed.shape == (0,) and weave.strand_closed.dtype == bool
