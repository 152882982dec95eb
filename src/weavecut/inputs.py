"""Built-in input meshes, by name: ``pentagon``, ``ngon:7``, ``square-grid:4x3``, ...

Every builder returns a valid counter-clockwise mesh; ``get("name[:param]")`` parses the name.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .errors import MeshError
from .mesh import Mesh
from .numeric import distinct, dot
from .text import nearest

MAX_GRID = 2000


@dataclass(frozen=True)
class Input:
    build: Callable[[str | None], Mesh]
    description: str
    parameter: str  # "" when the input takes none


def _regular(n: int, radius: float = 1.0, phase: float = math.pi / 2) -> np.ndarray:
    t = phase + 2 * np.pi * np.arange(n) / n
    return np.column_stack([np.cos(t), np.sin(t)]) * radius


def _weld(polygons: list[np.ndarray], decimals: int = 9) -> Mesh:
    """One mesh from polygons given by coordinates; equal points become one vertex."""
    pts = np.concatenate(polygons)
    keys = np.round(pts, decimals) + 0.0
    uniq, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")  # vertices numbered by first appearance
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    sizes = [len(p) for p in polygons]
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    return Mesh(pts[first[order]], offsets, rank[inverse.reshape(-1)])


def _count(param: str | None, default: int, name: str, lo: int = 3, hi: int = 10000) -> int:
    if param is None:
        return default
    try:
        n = int(param)
    except ValueError:
        raise MeshError(f"{name} takes a whole number, got {param!r}") from None
    if not lo <= n <= hi:
        raise MeshError(f"{name} takes a number from {lo} to {hi}, got {n}")
    return n


def _size(param: str | None, default: tuple[int, int], name: str) -> tuple[int, int]:
    if param is None:
        return default
    parts = param.lower().split("x")
    try:
        w, h = (int(parts[0]), int(parts[1])) if len(parts) == 2 else (int(parts[0]),) * 2
    except ValueError:
        raise MeshError(f"{name} takes a size WxH like 4x3, got {param!r}") from None
    if not (1 <= w <= MAX_GRID and 1 <= h <= MAX_GRID):
        raise MeshError(f"{name} size must be from 1x1 to {MAX_GRID}x{MAX_GRID}, got {param}")
    return w, h


def ngon(param: str | None = None) -> Mesh:
    n = _count(param, 5, "ngon")
    return Mesh(_regular(n), [0, n], np.arange(n))


def pentagon(param: str | None = None) -> Mesh:
    return ngon("5")


def triangulated_ngon(param: str | None = None) -> Mesh:
    n = _count(param, 6, "triangulated-ngon")
    vertices = np.vstack([[0.0, 0.0], _regular(n)])
    i = np.arange(n)
    faces = np.column_stack([np.zeros(n, dtype=int), 1 + i, 1 + (i + 1) % n])
    return Mesh(vertices, np.arange(0, 3 * n + 1, 3), faces.ravel())


def square_grid(param: str | None = None) -> Mesh:
    w, h = _size(param, (4, 4), "square-grid")
    x, y = np.meshgrid(np.arange(w + 1.0), np.arange(h + 1.0))
    vertices = np.column_stack([x.ravel(), y.ravel()]) - (w / 2, h / 2)
    i, j = np.meshgrid(np.arange(w), np.arange(h))
    v0 = (j * (w + 1) + i).ravel()
    faces = np.column_stack([v0, v0 + 1, v0 + w + 2, v0 + w + 1])
    return Mesh(vertices, np.arange(0, 4 * len(v0) + 1, 4), faces.ravel())


def tiling_8_4(param: str | None = None) -> Mesh:
    w, h = _size(param, (3, 3), "tiling-8-4")
    pitch = 1 + math.sqrt(2)  # octagon side 1
    octagon = _regular(8, 1 / (2 * math.sin(math.pi / 8)), math.pi / 8)
    square = _regular(4, math.sqrt(0.5), 0.0)
    polys = [octagon + (i * pitch, j * pitch) for j in range(h) for i in range(w)]
    polys += [square + ((i + 0.5) * pitch, (j + 0.5) * pitch)
              for j in range(h - 1) for i in range(w - 1)]
    mesh = _weld(polys)
    return mesh.moved(mesh.vertices - ((w - 1) * pitch / 2, (h - 1) * pitch / 2))


def pentagon_flower(param: str | None = None) -> Mesh:
    centre = _regular(5)
    polys = [centre]
    for i in range(5):  # reflect the central pentagon across each of its edges
        a, b = centre[i], centre[(i + 1) % 5]
        n = np.array([b[1] - a[1], a[0] - b[0]]) / np.hypot(*(b - a))
        petal = centre - 2 * dot(centre - a, n)[:, None] * n
        polys.append(petal[::-1])  # a reflection reverses orientation
    return _weld(polys)


def triangle_grid(param: str | None = None) -> Mesh:
    w, h = _size(param, (4, 4), "triangle-grid")
    j, i = np.meshgrid(np.arange(h + 1.0), np.arange(w + 1.0), indexing="ij")
    vertices = np.column_stack([(i + 0.5 * j).ravel(), (j * math.sqrt(3) / 2).ravel()])
    vertices -= vertices.mean(axis=0)
    jj, ii = np.meshgrid(np.arange(h), np.arange(w), indexing="ij")
    v0 = (jj * (w + 1) + ii).ravel()
    up = np.column_stack([v0, v0 + 1, v0 + w + 1])
    down = np.column_stack([v0 + 1, v0 + w + 2, v0 + w + 1])
    faces = np.stack([up, down], axis=1).reshape(-1, 3)
    return Mesh(vertices, np.arange(0, 3 * len(faces) + 1, 3), faces.ravel())


def hex_grid(param: str | None = None) -> Mesh:
    w, h = _size(param, (3, 3), "hex-grid")
    hexagon = _regular(6, 1.0, math.pi / 6)
    dx, dy = math.sqrt(3), 1.5
    polys = [hexagon + ((i + 0.5 * (j % 2)) * dx, j * dy) for j in range(h) for i in range(w)]
    mesh = _weld(polys)
    return mesh.moved(mesh.vertices - mesh.vertices.mean(axis=0))


def _hull(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(planes, triangles) of the convex hull of a few dozen points in 3D: every triple of
    points whose plane has all the points on one side; a plane is its outward unit normal and
    offset, ``normal . x + offset <= 0`` inside (as qhull's ``equations``)."""
    tri = np.array(list(itertools.combinations(range(len(points)), 3)))
    a, b, c = points[tri].transpose(1, 0, 2)
    normal = np.cross(b - a, c - a)
    length = np.sqrt(dot(normal, normal))
    tri, a, normal = tri[length > 1e-9], a[length > 1e-9], normal[length > 1e-9]
    normal /= length[length > 1e-9][:, None]
    offset = -dot(normal, a)
    side = dot(points[None], normal[:, None]) + offset[:, None]  # (triples, points)
    sign = np.where((side <= 1e-9).all(axis=1), 1.0, np.where((side >= -1e-9).all(axis=1),
                                                                 -1.0, 0.0))
    planes = np.column_stack([normal, offset]) * sign[:, None]
    return planes[sign != 0], tri[sign != 0]


def _convex_solid(points) -> Mesh:
    """The convex polyhedron with ``points`` as corners, scaled to unit circumradius: the
    convex hull's coplanar triangles merged into faces, counter-clockwise seen from outside."""
    points = np.asarray(points, dtype=np.float64)
    points /= np.linalg.norm(points, axis=1)[:, None]
    equations, simplices = _hull(points)
    planes, face = np.unique(np.round(equations, 9), axis=0, return_inverse=True)
    face = face.reshape(-1)
    corner_face = np.repeat(face, 3)
    pairs = distinct(np.column_stack([corner_face, simplices.reshape(-1)]), axis=0)
    f, v = pairs.T
    normal = planes[f, :3]
    centre = np.add.reduceat(points[v], np.flatnonzero(np.r_[True, f[1:] != f[:-1]]))
    centre = centre[f] / np.bincount(f)[f][:, None]
    ref = points[v][np.r_[0, np.flatnonzero(f[1:] != f[:-1]) + 1]][f] - centre
    # angle around the outward normal from the face's first corner: counter-clockwise outside
    angle = np.arctan2(dot(np.cross(ref, points[v] - centre), normal),
                       dot(ref, points[v] - centre))
    order = np.lexsort((angle, f))
    sizes = np.bincount(f)
    return Mesh(points, np.concatenate([[0], np.cumsum(sizes)]), v[order])


PHI = (1 + math.sqrt(5)) / 2
_CUBE = np.array([(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
_CYCLIC = [lambda a, b: (0, a, b), lambda a, b: (a, b, 0), lambda a, b: (b, 0, a)]
_ICOSAHEDRON = np.array([c(a, b) for c in _CYCLIC for a in (-1, 1) for b in (-PHI, PHI)])


def tetrahedron(param: str | None = None) -> Mesh:
    return _convex_solid(_CUBE[[0, 3, 5, 6]])


def cube(param: str | None = None) -> Mesh:
    return _convex_solid(_CUBE)


def octahedron(param: str | None = None) -> Mesh:
    return _convex_solid(np.vstack([np.eye(3), -np.eye(3)]))


def icosahedron(param: str | None = None) -> Mesh:
    return _convex_solid(_ICOSAHEDRON)


def dodecahedron(param: str | None = None) -> Mesh:
    rest = [c(a, b) for c in _CYCLIC for a in (-1 / PHI, 1 / PHI) for b in (-PHI, PHI)]
    return _convex_solid(np.vstack([_CUBE, rest]))


def icosphere(param: str | None = None) -> Mesh:
    """The icosahedron with every triangle split into four N times, vertices on the sphere."""
    n = _count(param, 2, "icosphere", lo=0, hi=7)
    mesh = icosahedron()
    vertices, tris = mesh.vertices, mesh.face_indices.reshape(-1, 3).astype(np.int64)
    for _ in range(n):
        edges = np.sort(np.stack([tris, np.roll(tris, -1, axis=1)], axis=2), axis=2)
        keys, mid = np.unique(edges.reshape(-1, 2), axis=0, return_inverse=True)
        mid = mid.reshape(-1, 3) + len(vertices)  # mid[:, i]: middle of edge (t_i, t_i+1)
        middles = vertices[keys].mean(axis=1)
        vertices = np.vstack([vertices, middles / np.linalg.norm(middles, axis=1)[:, None]])
        a, b, c = tris.T
        ab, bc, ca = mid.T
        tris = np.concatenate([np.column_stack(t) for t in
                               ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))])
    return Mesh(vertices, np.arange(0, tris.size + 1, 3), tris.ravel())


INPUTS: dict[str, Input] = {
    "pentagon": Input(pentagon, "regular pentagon, circumradius 1", ""),
    "ngon": Input(ngon, "regular N-gon, circumradius 1 (ngon:N)", "N"),
    "triangulated-ngon": Input(triangulated_ngon, "regular N-gon fanned from its centre", "N"),
    "square-grid": Input(square_grid, "W x H unit squares (default 4x4)", "WxH"),
    "tiling-8-4": Input(tiling_8_4, "regular octagons and squares, the paper's 8-4 mesh", "WxH"),
    "pentagon-flower": Input(pentagon_flower,
                             "a regular pentagon with a pentagon on each edge (paper model)", ""),
    "triangle-grid": Input(triangle_grid, "W x H rhombi of equilateral triangles", "WxH"),
    "hex-grid": Input(hex_grid, "W x H regular hexagons in offset rows", "WxH"),
    "tetrahedron": Input(tetrahedron, "regular tetrahedron, circumradius 1 (a closed surface)",
                         ""),
    "cube": Input(cube, "cube, circumradius 1 (a closed surface)", ""),
    "octahedron": Input(octahedron, "regular octahedron, circumradius 1 (a closed surface)", ""),
    "dodecahedron": Input(dodecahedron, "regular dodecahedron, circumradius 1 (a closed surface)",
                          ""),
    "icosahedron": Input(icosahedron, "regular icosahedron, circumradius 1 (a closed surface)",
                         ""),
    "icosphere": Input(icosphere, "icosahedron split N times (default 2) onto the unit sphere",
                       "N"),
}


SURFACES = ("tetrahedron", "cube", "octahedron", "dodecahedron", "icosahedron", "icosphere")
FLAT = tuple(name for name in INPUTS if name not in SURFACES)


def get(spec: str) -> Mesh:
    """The built-in mesh named ``spec`` (``name`` or ``name:param``).

    Examples
    --------
    >>> get("square-grid:2x1").n_faces
    2
    """
    name, _, param = spec.partition(":")
    if name not in INPUTS:
        raise MeshError(f"unknown input {name!r}{nearest(name, INPUTS)}; built-in inputs: "
                        f"{', '.join(INPUTS)}")
    entry = INPUTS[name]
    if param and not entry.parameter:
        raise MeshError(f"input {name!r} takes no parameter, got {param!r}")
    return entry.build(param or None)


def is_builtin(spec: str) -> bool:
    return spec.partition(":")[0] in INPUTS
