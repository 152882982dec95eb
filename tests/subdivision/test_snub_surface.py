"""One snub step on a surface in space against a loop-based oracle written from the paper and
the surface rule (surface.py): the Z-triplet of edge (u, w) lies in the plane whose normal is the
mean of the unit (Newell) normals of the faces beside the edge, turned by alpha towards the
face on the chirality's side; centres are vertex means; smoothing moves every inner vertex to
the mean centre of its faces. The oracle knows nothing of the step's numbering: it compares
faces as point sequences."""

from __future__ import annotations

import math

import numpy as np
import pytest

from weavecut import inputs
from weavecut.errors import MeshError
from weavecut.mesh import Mesh
from weavecut.subdivision import snub

from .classic_meshes import mixed


def bent_mixed() -> Mesh:
    """Two quads and two triangles round an inner vertex, lifted onto a saddle: bent quads,
    inner and outer edges, an inner old vertex."""
    flat = mixed()
    x, y = flat.vertices.T
    return Mesh(np.column_stack([x, y, 0.3 * x * x - 0.2 * y * y + 0.1 * x * y]),
                flat.face_offsets, flat.face_indices)


def newell(points: list[np.ndarray]) -> np.ndarray:
    n = np.zeros(3)
    for p, q in zip(points, points[1:] + points[:1]):
        n += np.cross(p, q)
    return n / np.linalg.norm(n)


def reference_surface_step(mesh: Mesh, smooth: bool, chirality: str) -> list[list[tuple]]:
    """The child faces as point lists, one pentagon per corner, by loops over the parent."""
    v = [np.array(p, dtype=float) for p in mesh.vertices.tolist()]
    faces = mesh.faces()
    normal = [newell([v[i] for i in f]) for f in faces]
    beside: dict = {}  # undirected edge -> faces
    for k, f in enumerate(faces):
        for a, b in zip(f, f[1:] + f[:1]):
            beside.setdefault(frozenset((a, b)), []).append(k)
    sign = 1.0 if chirality == "left" else -1.0
    z = {}  # directed (a, b) in face f -> (x on f's side, y on the other)
    for k, f in enumerate(faces):
        for a, b in zip(f, f[1:] + f[:1]):
            u, w = min(a, b), max(a, b)
            d = v[w] - v[u]
            n = sum(normal[g] for g in beside[frozenset((a, b))])
            t = np.cross(n / np.linalg.norm(n), d)
            t *= sign * math.sqrt(3) * np.linalg.norm(d) / np.linalg.norm(t)
            z0, z1 = v[u] + (5 * d + t) / 14, v[u] + (9 * d - t) / 14
            inward = np.cross(normal[k], v[b] - v[a])  # towards f, in f's plane
            if np.dot(z0 - (v[u] + v[w]) / 2, inward) > 0:
                z[(a, b)] = (z0, z1)
            else:
                z[(a, b)] = (z1, z0)
    pentagons = []
    for k, f in enumerate(faces):
        c = sum(v[i] for i in f) / len(f)
        n = len(f)
        for i in range(n):
            prev, a, b, nxt = f[i - 1], f[i], f[(i + 1) % n], f[(i + 2) % n]
            x, y = z[(a, b)]
            if chirality == "left":
                pentagons.append([c, x, y, v[b], z[(b, nxt)][0]])
            else:
                pentagons.append([v[a], y, x, c, z[(prev, a)][0]])
    if smooth:
        key = lambda p: tuple(np.round(p, 9))  # noqa: E731
        directed = {(key(p), key(q)) for pent in pentagons
                    for p, q in zip(pent, pent[1:] + pent[:1])}
        outer = {k for pq in directed if pq[::-1] not in directed for k in pq}
        around: dict = {}
        for pent in pentagons:
            centre = sum(pent) / 5
            for p in pent:
                around.setdefault(key(p), []).append(centre)
        pentagons = [[p if key(p) in outer else sum(around[key(p)]) / len(around[key(p)])
                      for p in pent] for pent in pentagons]
    return [[tuple(p) for p in pent] for pent in pentagons]


def face_set(faces, decimals: int = 9) -> set:
    out = set()
    for f in faces:
        pts = [tuple(round(c, decimals) + 0.0 for c in p) for p in f]
        k = pts.index(min(pts))
        out.add(tuple(pts[k:] + pts[:k]))
    return out


def child_face_points(mesh: Mesh) -> list[list[tuple]]:
    return [[tuple(mesh.vertices[i]) for i in f] for f in mesh.faces()]


@pytest.mark.parametrize("chirality", snub.CHIRALITIES)
@pytest.mark.parametrize("smooth", [False, True])
@pytest.mark.parametrize("make", [bent_mixed, lambda: inputs.get("cube"),
                                  lambda: inputs.get("octahedron")],
                         ids=["bent-mixed", "cube", "octahedron"])
def test_surface_step_matches_the_loop_oracle(make, smooth, chirality):
    mesh = make()
    child = snub.step(mesh, smooth=smooth, chirality=chirality).mesh
    assert child.vertices.shape == (mesh.n_vertices + 2 * mesh.topology.n_edges
                                    + mesh.n_faces, 3)
    assert face_set(child_face_points(child)) == face_set(
        reference_surface_step(mesh, smooth, chirality))


def test_a_planar_mesh_lifted_to_z_0_gives_the_planar_step():
    flat = mixed()
    lifted = Mesh(np.column_stack([flat.vertices, np.zeros(flat.n_vertices)]),
                  flat.face_offsets, flat.face_indices)
    for chirality in snub.CHIRALITIES:
        want = snub.step(flat, chirality=chirality).mesh.vertices
        got = snub.step(lifted, chirality=chirality).mesh.vertices
        np.testing.assert_allclose(got[:, :2], want, atol=1e-12)
        np.testing.assert_array_equal(got[:, 2], 0.0)


def test_project_sphere_moves_every_vertex_radially_onto_the_circumsphere():
    mesh = inputs.get("icosphere:1")
    centre, radius = np.array([1.0, -2.0, 0.5]), 2.5
    mesh = mesh.moved(mesh.vertices * radius + centre)
    plain = snub.step(mesh).mesh.vertices
    projected = snub.step(mesh, project="sphere").mesh.vertices
    ray = plain - centre
    np.testing.assert_allclose(projected, centre + radius * ray / np.linalg.norm(
        ray, axis=1)[:, None], atol=1e-12)
    assert np.abs(np.linalg.norm(plain - centre, axis=1) - radius).max() > 0.05


@pytest.mark.parametrize("options, message", [
    ({"centre": "mean"}, r"centre must be one of \('vertex', 'area'\), got 'mean'"),
    ({"chirality": "up"}, r"chirality must be one of \('left', 'right'\), got 'up'"),
    ({"project": "plane"}, r"project must be None or one of \('sphere',\), got 'plane'"),
])
def test_bad_options_are_refused_by_name(options, message):
    with pytest.raises(ValueError, match=message):
        snub.step(inputs.get("pentagon"), **options)


def test_area_centres_are_refused_on_a_surface_only():
    with pytest.raises(MeshError, match="^--centre area needs a planar mesh; a surface uses "
                                        "vertex means$"):
        snub.step(inputs.get("cube"), centre="area")
    assert snub.step(inputs.get("pentagon"), centre="area").mesh.n_faces == 5
