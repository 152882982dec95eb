"""Loop, butterfly and Catmull-Clark against libigl, vtk and pymeshlab, written once to ``peer_fixtures/`` (its README
says how and what each peer does); the comparisons are by what each point belongs to (an old
vertex keeps its id in every peer, an edge point is found by the two old vertices its child
faces hold), so no peer's numbering is assumed."""

from __future__ import annotations

import json
from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest

from weavecut.mesh import Mesh
from weavecut.subdivision import butterfly, catmull_clark, loop

from . import stencil_oracle as oracle

HERE = Path(__file__).with_name("peer_fixtures")
INPUTS = {m["name"]: m for m in json.loads((HERE / "inputs.json").read_text())}


def runs(fixture: str):
    doc = json.loads((HERE / f"{fixture}.json").read_text())
    for out in doc["meshes"]:
        given = INPUTS[out["name"]]
        mesh = Mesh.from_faces(np.array(given["vertices"]), given["faces"])
        yield mesh, oracle.Adjacency(given["vertices"], given["faces"]), out


def peer_points(mesh: Mesh, out: dict) -> tuple[np.ndarray, dict]:
    """The peer's vertices and {(u, w): id of its point of edge (u, w)}."""
    ends = defaultdict(set)
    for face in out["faces"]:
        for x in face:
            if x >= mesh.n_vertices:
                ends[x] |= {y for y in face if y < mesh.n_vertices}
    points = {tuple(sorted(s)): x for x, s in ends.items()}
    assert len(points) == mesh.topology.n_edges and all(len(e) == 2 for e in points)
    return np.array(out["vertices"]), points


def ours(step, mesh: Mesh) -> tuple[np.ndarray, dict]:
    child = step(mesh).mesh.vertices
    return child, {(int(u), int(w)): mesh.n_vertices + i
                   for i, (u, w) in enumerate(mesh.topology.edges)}


def close(a, b, rel: float, size: float = 1.0) -> bool:
    return bool(np.abs(np.asarray(a) - np.asarray(b)).max() <= rel * size)


@pytest.mark.parametrize("mesh, adj, out", list(runs("libigl-loop")), ids=list(INPUTS))
def test_loop_against_libigl(mesh, adj, out):
    theirs, their_edge = peer_points(mesh, out)
    mine, my_edge = ours(loop.step, mesh)
    warren, _ = oracle.loop(adj, beta=oracle.warren_beta)
    for e in their_edge:
        assert close(mine[my_edge[e]], theirs[their_edge[e]], 1e-12), e
    for v in range(mesh.n_vertices):
        if v in adj.outer or adj.valence(v) in (3, 6):
            assert close(mine[v], theirs[v], 1e-12), v
        else:  # libigl is Warren's beta, weave-cut Loop's own: they part by about 1e-3
            assert close(theirs[v], warren[v], 1e-12), v
            assert not close(mine[v], theirs[v], 1e-4), v


LOOP_PEERS = {"vtk-loop": ("float", 1e-6), "pymeshlab-loop": ("double", 1e-12)}
LOOP_RUNS = [(f, *run) for f in LOOP_PEERS for run in runs(f)]


@pytest.mark.parametrize("fixture, mesh, adj, out", LOOP_RUNS,
                         ids=[f"{f}-{out['name']}" for f, _, _, out in LOOP_RUNS])
def test_loop_against_vtk_and_meshlab(fixture, mesh, adj, out):
    """Both use Loop's own beta at every valence (4, 5, 7, 8 included, where Warren's is 1e-3
    away) and the cubic B-spline boundary; vtk in single precision, MeshLab in double."""
    precision, rel = LOOP_PEERS[fixture]
    assert out["precision"] == precision
    theirs, their_edge = peer_points(mesh, out)
    mine, my_edge = ours(loop.step, mesh)
    size = float(np.ptp(mesh.vertices, axis=0).max())
    np.testing.assert_allclose(mine[:mesh.n_vertices], theirs[:mesh.n_vertices], rtol=0,
                               atol=rel * size)
    for e in their_edge:
        assert close(mine[my_edge[e]], theirs[their_edge[e]], rel, size), e


@pytest.mark.parametrize("mesh, adj, out", list(runs("vtk-butterfly")), ids=list(INPUTS))
def test_butterfly_against_vtk(mesh, adj, out):
    theirs, their_edge = peer_points(mesh, out)
    mine, my_edge = ours(butterfly.step, mesh)
    size = float(np.ptp(mesh.vertices, axis=0).max())
    compared = 0
    for e in their_edge:
        if adj.is_outer_edge(*e) or not (set(e) & adj.outer):
            assert close(mine[my_edge[e]], theirs[their_edge[e]], 1e-6, size), e
            compared += 1
    assert compared >= len(their_edge) // 2


def eight_point(adj, u, w):
    """Dyn, Levin, Gregory 1990 (the butterfly before Zorin's modification): 1/2 (u + w)
    + 1/8 (c + d) - 1/16 (wings) at any valence; None where a wing is missing."""
    c, d = adj.opposite(u, w), adj.opposite(w, u)
    wings = [adj.opposite(u, c), adj.opposite(c, w), adj.opposite(d, u), adj.opposite(w, d)]
    if None in wings:
        return None
    return oracle.comb((1 / 2, adj.p[u]), (1 / 2, adj.p[w]), (1 / 8, adj.p[c]),
                       (1 / 8, adj.p[d]), *[(-1 / 16, adj.p[x]) for x in wings])


@pytest.mark.parametrize("mesh, adj, out", list(runs("pymeshlab-butterfly")), ids=list(INPUTS))
def test_butterfly_against_meshlab(mesh, adj, out):
    """MeshLab's butterfly (vcg's MidPointButterfly) is the original 8-point butterfly at every
    inner edge whose eight points exist, whatever the valence of its ends, not Zorin's
    modified one: the two agree at outer edges (the 4-point rule) and at inner edges between
    two inner vertices of valence 6 only, and are compared there."""
    theirs, their_edge = peer_points(mesh, out)
    mine, my_edge = ours(butterfly.step, mesh)
    assert close(mine[:mesh.n_vertices], theirs[:mesh.n_vertices], 0)
    compared = 0
    for (u, w), x in their_edge.items():
        regular = not {u, w} & adj.outer and adj.valence(u) == adj.valence(w) == 6
        if adj.is_outer_edge(u, w) or regular:
            assert close(mine[my_edge[(u, w)]], theirs[x], 1e-12), (u, w)
            compared += 1
        elif (expected := eight_point(adj, u, w)) is not None:
            assert close(theirs[x], expected, 1e-12), (u, w)
            compared += 1
    assert compared >= len(their_edge) // 2


def quad_points(n_old: int, quads) -> tuple[dict, dict]:
    """{edge (u, w): peer id} and {frozenset(face's corners): peer id} of a Catmull-Clark child
    given as quads (old vertex, edge point, face point, edge point): an edge point is next to
    its two ends, a face point is across from its face's corners."""
    beside, across = defaultdict(set), defaultdict(set)
    for q in quads:
        for i, x in enumerate(q):
            if x >= n_old:
                beside[x] |= {y for y in (q[i - 1], q[(i + 1) % 4]) if y < n_old}
                if q[(i + 2) % 4] < n_old:
                    across[x].add(q[(i + 2) % 4])
    edges = {tuple(sorted(s)): x for x, s in beside.items() if x not in across}
    return edges, {frozenset(s): x for x, s in across.items()}


@pytest.mark.parametrize("mesh, adj, out", list(runs("pymeshlab-catmull-clark")),
                         ids=list(INPUTS))
def test_catmull_clark_against_meshlab(mesh, adj, out):
    """MeshLab's Catmull-Clark (on these triangle meshes, written as quads) agrees with
    weave-cut at every face point and inner edge point to 1e-6 of the mesh size (MeshLab
    rounds to single precision there); its old vertices (inner ones 0.004-0.02 away) and its
    outer edges and vertices (it has no crease rule) do not follow Catmull and Clark's
    (Q + 2R + (n - 3) S) / n or the B-spline boundary, and are not compared."""
    n_v, n_e = mesh.n_vertices, mesh.topology.n_edges
    their_edge, their_face = quad_points(n_v, out["faces"])
    theirs = np.array(out["vertices"])
    mine = catmull_clark.step(mesh).mesh.vertices
    size = float(np.ptp(mesh.vertices, axis=0).max())
    assert len(their_face) == mesh.n_faces and len(their_edge) == n_e
    for f, corners in enumerate(adj.faces):
        assert close(mine[n_v + n_e + f], theirs[their_face[frozenset(corners)]], 1e-6, size), f
    for i, (u, w) in enumerate(mesh.topology.edges.tolist()):
        if not adj.is_outer_edge(u, w):
            assert close(mine[n_v + i], theirs[their_edge[(u, w)]], 1e-6, size), (u, w)
