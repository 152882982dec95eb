"""Small named meshes for tests (valid and invalid)."""

from __future__ import annotations

import numpy as np

from weavecut.mesh import Mesh


def square() -> Mesh:
    return Mesh.from_faces([(0, 0), (1, 0), (1, 1), (0, 1)], [[0, 1, 2, 3]])


def hexagon() -> Mesh:
    """A hexagon of six triangles round a centre vertex (C6 after the snub step)."""
    ring = [(np.cos(a), np.sin(a)) for a in np.arange(6) * np.pi / 3]
    return Mesh.from_faces([(0.0, 0.0), *ring], [[0, i + 1, (i + 1) % 6 + 1] for i in range(6)])


def two_squares() -> Mesh:
    return Mesh.from_faces([(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (0, 1)],
                           [[0, 1, 4, 5], [1, 2, 3, 4]])


def mixed() -> Mesh:
    """A square, a triangle and a pentagon-ish face sharing edges."""
    v = [(0, 0), (1, 0), (1, 1), (0, 1), (2, 1.2), (1.5, 1.8), (0.5, 1.9)]
    return Mesh.from_faces(v, [[0, 1, 2, 3], [1, 4, 2], [2, 4, 5, 6, 3]])


def reference_snub_step(mesh: Mesh, smooth: bool = True) -> list[list[tuple]]:
    """A slow, loop-based snub step (left chirality, vertex centres) written from the paper,
    independent of the vectorised engine; returns faces as coordinate tuples."""
    verts = [complex(*p) for p in mesh.vertices.tolist()]
    faces = mesh.faces()
    z = {}  # directed edge (a, b) -> (x on the left, y on the right)
    for f in faces:
        for i, a in enumerate(f):
            b = f[(i + 1) % len(f)]
            d = verts[b] - verts[a]
            x = verts[a] + d * complex(5, 3 ** 0.5) / 14
            y = verts[a] + d * complex(9, -(3 ** 0.5)) / 14
            z[(a, b)] = (x, y)
    directed = set(z)
    boundary_pts = set()
    for (a, b), (x, y) in z.items():
        if (b, a) not in directed:
            boundary_pts.update([x, y, verts[a], verts[b]])
    pentagons = []
    for f in faces:
        c = sum(verts[i] for i in f) / len(f)
        n = len(f)
        for i in range(n):
            a, b, nxt = f[i], f[(i + 1) % n], f[(i + 2) % n]
            x, y = z[(a, b)]
            pentagons.append([c, x, y, verts[b], z[(b, nxt)][0]])
    if smooth:
        key = lambda p: (round(p.real, 9), round(p.imag, 9))  # noqa: E731
        centres: dict = {}
        for pent in pentagons:
            cen = sum(pent) / 5
            for p in pent:
                centres.setdefault(key(p), []).append(cen)
        fixed = {key(p) for p in boundary_pts}
        moved = {k: sum(cs) / len(cs) for k, cs in centres.items() if k not in fixed}
        pentagons = [[moved.get(key(p), p) for p in pent] for pent in pentagons]
    return [[(p.real, p.imag) for p in pent] for pent in pentagons]


def face_set(faces, decimals: int = 7) -> set:
    """Faces as a set of cyclically normalised tuples of rounded points (order-free compare)."""
    out = set()
    for f in faces:
        pts = [(round(x, decimals) + 0.0, round(y, decimals) + 0.0) for x, y in f]
        k = pts.index(min(pts))
        out.add(tuple(pts[k:] + pts[:k]))
    return out


def mesh_face_points(mesh: Mesh) -> list[list[tuple]]:
    return [[tuple(mesh.vertices[i]) for i in f] for f in mesh.faces()]


def mirror_points(faces) -> list[list[tuple]]:
    return [[(-x, y) for x, y in reversed(f)] for f in faces]


def rotate(mesh: Mesh, angle: float) -> Mesh:
    c, s = np.cos(angle), np.sin(angle)
    return mesh.moved(mesh.vertices @ np.array([[c, s], [-s, c]]))
