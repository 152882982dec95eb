"""What every scheme's Level promises (hierarchy.Level, Mesh, Topology docstrings): the dtypes
and sizes of the provenance and topology arrays (the memory model counts int32 provenance), and
the provenance itself read against the numbering the scheme's docstring gives, checked by
membership (an old vertex, an edge point of the parent face's edges), not by the formulas."""

from __future__ import annotations

import numpy as np
import pytest

from weavecut import inputs
from weavecut.mesh import Topology
from weavecut.subdivision import SCHEMES, butterfly, loop

from .classic_meshes import mixed, quad_grid, tri_grid

TRIANGLES_ONLY = {"loop", "butterfly"}


def meshes_for(name):
    out = [tri_grid(2, 2, jitter=0.1), inputs.get("pentagon-flower")]
    if name not in TRIANGLES_ONLY:
        out += [mixed(), quad_grid(2, 1)]
    return [m for m in out if name not in TRIANGLES_ONLY or m.face_degree == 3]


@pytest.mark.parametrize("name", sorted(SCHEMES))
def test_level_arrays_have_the_documented_dtypes_and_sizes(name):
    for mesh in meshes_for(name):
        level = SCHEMES[name](mesh)
        child = level.mesh
        topo = child.topology
        n_e = Topology.build(child).n_edges
        for arr, dtype, size in [
            (level.parent_face, np.int32, child.n_faces),
            (level.parent_corner, np.int32, child.n_faces),
            (level.parent_edge, np.int32, n_e), (level.edge_part, np.int8, n_e),
            (child.face_offsets, np.int64, child.n_faces + 1),
            (child.face_indices, np.int32, child.n_corners),
            (topo.half_edge_edge, np.int32, child.n_corners),
            (topo.half_edge_side, np.int8, child.n_corners),
            (topo.boundary_edges, np.bool_, n_e),
        ]:
            assert arr.dtype == dtype and arr.shape == (size,), (arr.dtype, arr.shape)
        assert topo.edges.dtype == np.int32 and topo.edges.shape == (n_e, 2)
        assert child.vertices.dtype == np.float64
        assert child.face_offsets[0] == 0 and child.face_offsets[-1] == child.n_corners
        # the provenance points into the parent
        pf, pc = level.parent_face, level.parent_corner
        assert ((pf >= -1) & (pf < mesh.n_faces)).all()
        sizes = np.where(pf >= 0, mesh.face_sizes[np.maximum(pf, 0)], 0)
        assert ((pc >= -1) & (pc < np.maximum(sizes, 1))).all()


@pytest.mark.parametrize("step", [loop.step, butterfly.step], ids=["loop", "butterfly"])
def test_1_to_4_provenance_by_membership(step):
    """Face 4f + i (i < 3) is the corner triangle at corner i of f: it holds the old vertex a_i
    and the edge points of the two edges at a_i; face 4f + 3 (corner -1) holds the three edge
    points. Edge halves join an end of their parent edge to its edge point; inner edges join
    two edge points of their parent face."""
    mesh = tri_grid(3, 2, jitter=0.1)
    level = step(mesh)
    child, topo = level.mesh, mesh.topology
    n_v = mesh.n_vertices
    tri = mesh.dense_faces()
    edge_point = n_v + topo.half_edge_edge.reshape(-1, 3)
    np.testing.assert_array_equal(level.parent_face, np.repeat(np.arange(mesh.n_faces), 4))
    for k, face in enumerate(child.dense_faces()):
        f, c = level.parent_face[k], level.parent_corner[k]
        if c >= 0:
            assert set(face) == {tri[f, c], edge_point[f, c], edge_point[f, c - 1]}
        else:
            assert set(face) == set(edge_point[f])
    assert (level.parent_corner == -1).sum() == mesh.n_faces
    ends = child.topology.edges
    for e, (part, parent) in enumerate(zip(level.edge_part, level.parent_edge)):
        if part == loop.INNER:
            assert set(ends[e]) <= set(edge_point[parent])
        else:
            end = topo.edges[parent, 0 if part == loop.FIRST_HALF else 1]
            assert set(ends[e]) == {end, n_v + parent}
    np.testing.assert_array_equal(np.bincount(level.edge_part), [
        mesh.topology.n_edges, mesh.topology.n_edges, mesh.n_corners])


def parent_sets(mesh):
    """Per parent face: its vertices, its edges; per vertex: its edges; per edge: its faces."""
    faces = mesh.faces()
    topo = mesh.topology
    he = np.split(topo.half_edge_edge, mesh.face_offsets[1:-1])
    face_edges = [set(e.tolist()) for e in he]
    vertex_edges: dict = {}
    for e, (u, w) in enumerate(topo.edges.tolist()):
        vertex_edges.setdefault(u, set()).add(e)
        vertex_edges.setdefault(w, set()).add(e)
    edge_faces = [{f for f, es in enumerate(face_edges) if e in es}
                  for e in range(topo.n_edges)]
    return faces, face_edges, vertex_edges, edge_faces


GENERAL_MESHES = [mixed, lambda: quad_grid(2, 2, jitter=0.1),
                  lambda: inputs.get("pentagon-flower")]


@pytest.mark.parametrize("make", GENERAL_MESHES)
def test_catmull_clark_provenance_by_membership(make):
    """Quad of corner c of face f: the old vertex a_c and the face point V + E + f; edge halves
    join an end of their edge to its edge point V + e; spokes join the face point of their
    face to the point of one of its edges."""
    from weavecut.subdivision import catmull_clark as cc
    mesh = make()
    level = cc.step(mesh)
    faces, face_edges, _, _ = parent_sets(mesh)
    n_v, n_e = mesh.n_vertices, mesh.topology.n_edges
    for quad, f, c in zip(level.mesh.faces(), level.parent_face, level.parent_corner):
        assert faces[f][c] in quad and n_v + n_e + f in quad
    for (a, b), part, parent in zip(level.mesh.topology.edges, level.edge_part,
                                    level.parent_edge):
        if part == cc.SPOKE:
            assert b == n_v + n_e + parent and a - n_v in face_edges[parent]
        else:
            end = mesh.topology.edges[parent, 0 if part == cc.FIRST_HALF else 1]
            assert (a, b) == (end, n_v + parent)
    assert np.bincount(level.edge_part).tolist() == [n_e, n_e, mesh.n_corners]


@pytest.mark.parametrize("make", GENERAL_MESHES)
def test_sqrt3_provenance_by_membership(make):
    """Triangle of corner c of face f: a_c and the centre V + f; a flipped edge joins the
    centres of the two faces beside it, a kept (outer) edge is the parent edge; a spoke joins
    the centre of its face to one of the face's corners."""
    from weavecut.subdivision import sqrt3
    mesh = make()
    level = sqrt3.step(mesh)
    faces, _, _, edge_faces = parent_sets(mesh)
    n_v = mesh.n_vertices
    for tri, f, c in zip(level.mesh.faces(), level.parent_face, level.parent_corner):
        assert faces[f][c] in tri and n_v + f in tri
    outer = mesh.topology.boundary_edges
    for (a, b), part, parent in zip(level.mesh.topology.edges, level.edge_part,
                                    level.parent_edge):
        if part == sqrt3.SPOKE:
            assert b == n_v + parent and a in faces[parent]
        elif part == sqrt3.KEPT:
            assert outer[parent] and (a, b) == tuple(mesh.topology.edges[parent])
        else:
            assert {a - n_v, b - n_v} == edge_faces[parent]
    assert (level.edge_part == sqrt3.KEPT).sum() == outer.sum()


@pytest.mark.parametrize("make", GENERAL_MESHES)
def test_akleman_provenance_by_membership(make):
    """[F inner copies (corner -1) | one pentagon per corner, holding its old vertex]; halves
    join an end to the midpoint V + e, spokes a midpoint of the face's edges to a copy,
    ring edges two copies of one face."""
    from weavecut.subdivision import akleman
    mesh = make()
    level = akleman.step(mesh)
    faces, face_edges, _, _ = parent_sets(mesh)
    n_v, n_e, n_f = mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces
    copy_face = mesh.half_edge_face  # copy of corner h -> V + E + h
    np.testing.assert_array_equal(level.parent_face[:n_f], np.arange(n_f))
    np.testing.assert_array_equal(level.parent_corner[:n_f], -1)
    for k, (poly, f, c) in enumerate(zip(level.mesh.faces(), level.parent_face,
                                         level.parent_corner)):
        if k < n_f:
            assert all(p >= n_v + n_e and copy_face[p - n_v - n_e] == f for p in poly)
        else:
            assert len(poly) == 5 and faces[f][c] in poly
    for (a, b), part, parent in zip(level.mesh.topology.edges, level.edge_part,
                                    level.parent_edge):
        if part in (akleman.FIRST_HALF, akleman.SECOND_HALF):
            end = mesh.topology.edges[parent, part]
            assert (a, b) == (end, n_v + parent)
        elif part == akleman.SPOKE:
            assert a - n_v in face_edges[parent] and copy_face[b - n_v - n_e] == parent
        else:
            assert copy_face[a - n_v - n_e] == copy_face[b - n_v - n_e] == parent


@pytest.mark.parametrize("make", GENERAL_MESHES)
def test_midedge_doo_sabin_and_dual_provenance_by_membership(make):
    from weavecut.mesh import outer_vertices
    from weavecut.subdivision import doo_sabin, dual, midedge
    mesh = make()
    faces, face_edges, vertex_edges, edge_faces = parent_sets(mesh)
    n_f, n_e = mesh.n_faces, mesh.topology.n_edges
    # midedge: face f is the polygon of its edges' midpoints (vertex e); vertex polygons -1
    level = midedge.step(mesh)
    for k, (poly, f, c) in enumerate(zip(level.mesh.faces(), level.parent_face,
                                         level.parent_corner)):
        assert c == -1 and (f == k if k < n_f else f == -1)
        if k < n_f:
            assert set(poly) == face_edges[f]
    kept = level.mesh.vertices[n_e:]
    for (a, b), part, parent in zip(level.mesh.topology.edges, level.edge_part,
                                    level.parent_edge):
        if part == midedge.CORNER:
            assert {a, b} <= face_edges[parent]
        else:  # a midpoint of an edge at the kept outer vertex ``parent``, and the vertex
            assert a in vertex_edges[parent] and b >= n_e
            np.testing.assert_array_equal(level.mesh.vertices[b], mesh.vertices[parent])
    assert len(kept) == (level.edge_part == midedge.OUTER_SPOKE).sum() // 2
    # Doo-Sabin: vertex h per corner; face f holds the corners of f; edge quads and vertex
    # polygons have no parent; across-edge edges join two corners at one end of their edge
    level = doo_sabin.step(mesh)
    corner_face, corner_vertex = mesh.half_edge_face, mesh.face_indices
    for k, (poly, f, c) in enumerate(zip(level.mesh.faces(), level.parent_face,
                                         level.parent_corner)):
        assert c == -1 and (f == k if k < n_f else f == -1)
        if k < n_f:
            assert set(corner_face[poly]) == {f}
    for (a, b), part, parent in zip(level.mesh.topology.edges, level.edge_part,
                                    level.parent_edge):
        if part == doo_sabin.IN_FACE:
            assert corner_face[a] == corner_face[b] == parent
        else:
            assert corner_vertex[a] == corner_vertex[b]
            assert corner_vertex[a] in mesh.topology.edges[parent]
            assert {corner_face[a], corner_face[b]} == edge_faces[parent]
    # dual: one face per inner vertex (no parent face); edge i crosses the i-th inner edge
    # with an inner end and joins the two faces beside it
    level = dual.step(mesh)
    assert (level.parent_face == -1).all() and (level.parent_corner == -1).all()
    assert level.mesh.n_faces == (~outer_vertices(mesh)).sum()
    for (a, b), parent in zip(level.mesh.topology.edges, level.parent_edge):
        assert {a, b} == edge_faces[parent]
    assert (level.edge_part == dual.CROSSING).all()
