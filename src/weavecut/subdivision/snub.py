"""The pentagon snub subdivision step (the paper's operations 1-4).

For a counter-clockwise face f and its half-edge h = (a -> b) on edge e = (u, w), u < w, the
Z-triplet is u - z0 - z1 - w with three edges of length |e|/sqrt(7) and 120 degrees between
consecutive edges; z0 lies near u, z1 near w, point-symmetric about the edge midpoint:

    z0 = u + d (5 + i sqrt3 s) / 14,   z1 = u + d (9 - i sqrt3 s) / 14,   d = w - u,

with s = +1 for left chirality (the first Z edge turns by alpha = atan(sqrt3/5) towards the face
on its left) and s = -1 for right. The Z vertex on f's side of e is x_h, the other y_h. The
centre c_f joins every x_h and f splits into one pentagon per corner, with local edge 1 always
the Z middle edge and local vertex 4 the tip opposite it:

    left:  P_h = (c_f, x_h, y_h, b, x_next(h))       right: P_h = (a, y_h, x_h, c_f, x_prev(h))

Numbering (child of a mesh with V, E, F, H): vertices ``[old V | z0, z1 of every edge | centres]``,
faces: one per parent half-edge (face h comes from half-edge h), edges: ``3e + part`` for the Z
parts (FIRST = (u, z0), MIDDLE = (z0, z1), LAST = (w, z1)) and ``3E + h`` for the spoke (x_h, c_f).
Counts (paper eq. 2): V' = V + 2E + F, E' = 3E + H, F' = H.

On a surface in space (vertices (V, 3)) the same topology code runs; only the Z vertices
differ: ``i d`` becomes ``n x d`` scaled to ``|d|``, with ``n`` the normal of the plane the
triplet lies in (:func:`weavecut.surface.edge_normals`: the mean of the normals of the faces
beside the edge). Centres are vertex means and the smoothing, being linear, runs on the
(x, y) and (z, 0) columns as on two planar meshes. On z = 0 this is the planar step; the
planar hot path is untouched.

The step writes each output array once, in place, and reads the parent only through its corner
arithmetic (:class:`Corners`), so it runs close to the speed of writing its output. The
numbers are those of the plain definition, bit for bit: every sum adds the same terms in the
same order as "the vertex mean of a child face" and "the mean of a vertex's face centres"
would (``tests/subdivision/test_snub_identity.py`` holds the earlier, direct implementation
as the oracle), which the windowed refinement of :mod:`weavecut.analysis.levels` relies on.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..errors import MeshError
from ..mesh import Mesh, Topology, outer_vertices
from ..mesh_geometry import area_centroids, face_centroids
from ..surface import circumsphere, edge_normals, onto_sphere
from ._common import Corners, fill_rows, interleave
from .hierarchy import Level

FIRST, MIDDLE, LAST, SPOKE = 0, 1, 2, 3
EDGE_PARTS = {"first": FIRST, "middle": MIDDLE, "last": LAST, "spoke": SPOKE}
ALPHA = float(np.arctan(np.sqrt(3.0) / 5.0))  # 19.1066 degrees
CENTRES = ("vertex", "area")
CHIRALITIES = ("left", "right")
PROJECTIONS = ("sphere",)


def counts(n_vertices: int, n_edges: int, n_faces: int, n_corners: int) -> tuple[int, ...]:
    """(V', E', F', H') after one step, from the paper's eq. (2); every child face is a pentagon.

    Examples
    --------
    >>> counts(5, 5, 1, 5)  # a pentagon -> 5 pentagons
    (16, 20, 5, 25)
    """
    return (n_vertices + 2 * n_edges + n_faces, 3 * n_edges + n_corners, n_corners, 5 * n_corners)


def step(mesh: Mesh, *, smooth: bool = True, centre: str = "vertex",
         chirality: str = "left", project: str | None = None) -> Level:
    """One pentagon snub step: Z-triplets, centres, joins and (optionally) smoothing.

    Parameters
    ----------
    mesh : Mesh with counter-clockwise faces
    smooth : apply operation 4 (move inner vertices to the mean centre of their faces)
    centre : "vertex" (vertex mean, the paper's figures) or "area" (area centroid)
    chirality : "left" or "right"
    project : None, or "sphere": move every vertex of the result onto the circumsphere of
        ``mesh`` (whose vertices must lie on a sphere)

    Returns
    -------
    Level with provenance (see the module docstring for the numbering).
    """
    if centre not in CENTRES:
        raise ValueError(f"centre must be one of {CENTRES}, got {centre!r}")
    if chirality not in CHIRALITIES:
        raise ValueError(f"chirality must be one of {CHIRALITIES}, got {chirality!r}")
    if project not in (None, *PROJECTIONS):
        raise ValueError(f"project must be None or one of {PROJECTIONS}, got {project!r}")
    if mesh.dim == 3 and centre == "area":
        raise MeshError("--centre area needs a planar mesh; a surface uses vertex means")
    sphere = circumsphere(mesh.vertices) if project else None
    right = chirality == "right"
    ring = Corners(mesh)
    vertices = (_new_vertices if mesh.dim == 2 else _new_surface_vertices)(mesh, right, centre)
    x, y, old = _corner_vertices(mesh, ring, right)
    if smooth and mesh.dim == 3:
        _smooth_surface(mesh, ring, vertices, x, y, old, right)
    elif smooth:  # first, while the vertices are the only output: it needs the most scratch
        if centre == "area":
            faces = _faces(mesh, ring, x, y, old, right).reshape(-1)
            offsets = np.arange(0, len(faces) + 1, 5, dtype=np.int64)
            centres = area_centroids(Mesh.trusted(vertices.view(), offsets, faces))
            centres = centres.view(np.complex128).ravel()
            del faces, offsets
        else:
            centres = _vertex_centres(mesh, ring, vertices, x, y, old, right)
        _smooth(mesh, ring, vertices, centres, old, right)
        del centres
    if sphere is not None:
        onto_sphere(vertices, *sphere)
    faces = _faces(mesh, ring, x, y, old, right)
    del y, old
    edges, parent_edge, edge_part, boundary = _edges(mesh, ring, x)
    del x
    child_topo = Topology(edges, *_half_edges(mesh, ring, right))
    child_topo.__dict__["boundary_edges"] = boundary
    child_topo.__dict__["edge_half_edges"] = _edge_half_edges(mesh, ring, right)
    offsets = np.arange(0, faces.size + 1, 5, dtype=np.int64)
    child = Mesh.trusted(vertices, offsets, faces.reshape(-1), child_topo)
    child.__dict__["face_degree"] = 5
    return Level(child, ring.face_ids(), ring.positions(), parent_edge, edge_part)


def _new_vertices(mesh: Mesh, right: bool, centre: str) -> NDArray[np.float64]:
    """Operations 1 and 2: ``[old | z0, z1 of every edge | face centres]``, (V + 2E + F, 2)."""
    topo = mesh.topology
    n_v, n_e = mesh.n_vertices, topo.n_edges
    vertices = np.empty((n_v + 2 * n_e + mesh.n_faces, 2))
    vertices[:n_v] = mesh.vertices
    vx, vy = np.ascontiguousarray(mesh.vertices.T)
    u, w = (np.ascontiguousarray(topo.edges[:, c], dtype=np.intp) for c in (0, 1))
    ux, uy = vx.take(u, mode="clip"), vy.take(u, mode="clip")
    dx, dy = vx.take(w, mode="clip"), vy.take(w, mode="clip")
    dx -= ux
    dy -= uy
    s = (-1.0 if right else 1.0) * np.sqrt(3.0)
    sdx, sdy = s * dx, s * dy
    z = np.empty((4, n_e))  # z0 x, z0 y, z1 x, z1 y
    for j, (base, along, across, factor, add) in enumerate((
            (ux, dx, sdy, 5, False), (uy, dy, sdx, 5, True),
            (ux, dx, sdy, 9, True), (uy, dy, sdx, 9, False))):
        np.multiply(factor, along, out=z[j])  # u + (factor d -+ s d_perp) / 14
        (np.add if add else np.subtract)(z[j], across, out=z[j])
        z[j] /= 14
        z[j] += base
    interleave(z, out=vertices[n_v:n_v + 2 * n_e].reshape(n_e, 4))
    centre_of = area_centroids if centre == "area" else face_centroids
    vertices[n_v + 2 * n_e:] = centre_of(mesh)
    return vertices


def _new_surface_vertices(mesh: Mesh, right: bool, centre: str) -> NDArray[np.float64]:
    """:func:`_new_vertices` on a surface in space, (V + 2E + F, 3): the Z-triplet of edge
    (u, w) in the plane of its edge normal n, with ``t = n x d`` scaled to ``|d|`` for
    ``i d``."""
    topo = mesh.topology
    u, w = mesh.vertices[topo.edges[:, 0]], mesh.vertices[topo.edges[:, 1]]
    d = w - u
    t = np.cross(edge_normals(mesh), d)
    t *= ((-1.0 if right else 1.0) * np.sqrt(3.0) * np.linalg.norm(d, axis=1)
          / np.linalg.norm(t, axis=1))[:, None]
    z = np.stack([u + (5 * d + t) / 14, u + (9 * d - t) / 14], axis=1)
    return np.concatenate([mesh.vertices, z.reshape(-1, 3), face_centroids(mesh)])


def _smooth_surface(mesh: Mesh, ring: Corners, vertices, x, y, old, right: bool) -> None:
    """Operation 4 on a surface, in place: the planar smoothing on the (x, y) and the (z, 0)
    columns (it is linear in the coordinates)."""
    planes = (np.ascontiguousarray(vertices[:, :2]),
              np.column_stack([vertices[:, 2], np.zeros(len(vertices))]))
    for plane in planes:
        _smooth(mesh, ring, plane, _vertex_centres(mesh, ring, plane, x, y, old, right), old,
                right)
    vertices[:, :2] = planes[0]
    vertices[:, 2] = planes[1][:, 0]


def _corner_vertices(mesh: Mesh, ring: Corners, right: bool):
    """(x, y, old): per parent corner h, the child vertex ids of x_h and y_h (int32) and of
    P_h's old vertex (intp): a, the start of h (right), or b, its end (left)."""
    topo = mesh.topology
    face_side = 1 - topo.half_edge_side if right else topo.half_edge_side  # x_h is z0 or z1
    x = 2 * topo.half_edge_edge.astype(np.int32, copy=False)
    x += mesh.n_vertices
    y = x + 1
    x += face_side
    y -= face_side
    old = np.empty(mesh.n_corners, dtype=np.intp)
    if right:
        old[:] = mesh.face_indices
    else:
        ring.shifted(mesh.face_indices, 1, out=old)
    return x, y, old


def _faces(mesh: Mesh, ring: Corners, x, y, old, right: bool) -> NDArray[np.int32]:
    """Operation 3: (H, 5) the pentagons P_h."""
    centre = np.empty_like(x)
    ring.face_values(mesh.n_vertices + 2 * mesh.topology.n_edges, out=centre)
    tip = np.empty_like(x)
    ring.shifted(x, -1 if right else 1, out=tip)
    columns = [old, y, x, centre, tip] if right else [centre, x, y, old, tip]
    return interleave(columns, out=np.empty((mesh.n_corners, 5), dtype=np.int32))


def _half_edges(mesh: Mesh, ring: Corners, right: bool) -> tuple[NDArray[np.int32], NDArray]:
    """The child's half-edge -> edge map and sides, (5H,) each (see the module docstring)."""
    topo = mesh.topology
    sides = np.empty((mesh.n_corners, 5), dtype=np.int8)  # one row per P_h, written directly
    e3 = 3 * topo.half_edge_edge.astype(np.int32, copy=False)
    side2 = 2 * topo.half_edge_side
    near_start = e3 + side2  # the Z part at a, the start of h
    near_end = e3 - side2    # the Z part at b, its end
    near_end += 2
    middle = e3
    middle += MIDDLE

    def spoke(shift: int) -> NDArray[np.int32]:  # of the corner itself, its next or previous
        out = np.empty_like(e3)
        ring.corner_ids(shift, out, offset=3 * topo.n_edges)
        return out

    def neighbours(parts: NDArray[np.int32], shift: int) -> NDArray[np.int32]:
        out = np.empty_like(parts)
        ring.shifted(parts, shift, out=out)
        return out

    if right:  # (near_start, middle, spoke, spoke[prev], near_end[prev]), sides (0 s 0 1 1)
        parts = [near_start, middle, spoke(0), spoke(-1), neighbours(near_end, -1)]
        fill_rows(sides, np.array([0, 0, 0, 1, 1], np.int8))
    else:  # (spoke, middle, near_end, near_start[next], spoke[next]), sides (1 s 1 0 0)
        parts = [spoke(0), middle, near_end, neighbours(near_start, 1), spoke(1)]
        fill_rows(sides, np.array([1, 0, 1, 0, 0], np.int8))
    sides[:, 1] = topo.half_edge_side
    edge = interleave(parts, out=np.empty((mesh.n_corners, 5), dtype=np.int32))
    return edge.reshape(-1), sides.reshape(-1)


def _edges(mesh: Mesh, ring: Corners, x: NDArray[np.int32]):
    """(edges, parent_edge, edge_part, boundary) of the child: 3 Z parts per edge, then spokes."""
    topo = mesh.topology
    n_v, n_e, n_h = mesh.n_vertices, topo.n_edges, mesh.n_corners
    edges = np.empty((3 * n_e + n_h, 2), dtype=np.int32)
    z0 = np.arange(n_v, n_v + 2 * n_e, 2, dtype=np.int32)
    z1 = z0 + 1  # FIRST (u, z0), MIDDLE (z0, z1), LAST (w, z1)
    interleave([topo.edges[:, 0], z0, z0, z1, topo.edges[:, 1], z1],
               out=edges[:3 * n_e].reshape(n_e, 6))
    centre = np.empty_like(x)
    ring.face_values(n_v + 2 * n_e, out=centre)
    interleave([x, centre], out=edges[3 * n_e:])
    parent_edge = np.empty(len(edges), dtype=np.int32)
    interleave([np.arange(n_e, dtype=np.int32)] * 3, out=parent_edge[:3 * n_e].reshape(n_e, 3))
    ring.face_values(0, out=parent_edge[3 * n_e:])
    edge_part = np.empty(len(edges), dtype=np.int8)
    fill_rows(edge_part[:3 * n_e].reshape(n_e, 3), np.array([FIRST, MIDDLE, LAST], np.int8))
    edge_part[3 * n_e:] = SPOKE
    boundary = np.empty(len(edges), dtype=bool)
    interleave([topo.boundary_edges] * 3, out=boundary[:3 * n_e].reshape(n_e, 3))
    boundary[3 * n_e:] = False
    return edges, parent_edge, edge_part, boundary


def _edge_half_edges(mesh: Mesh, ring: Corners, right: bool) -> NDArray[np.int32]:
    """The child's ``Topology.edge_half_edges`` (E', 2), from the parent's by arithmetic.

    Child half-edge 5h + j is corner j of P_h. The three Z parts of parent edge e come from
    its half-edges h0 (u -> w) and h1 (w -> u) and their neighbours in their faces, the spoke
    of h from h and its neighbour: every row is written in edge order, with no scatter.
    """
    topo = mesh.topology
    n_e = topo.n_edges
    pair = topo.edge_half_edges
    h0, h1 = pair[:, 0] * 5, pair[:, 1] * 5
    z = np.empty((3, 2, n_e), dtype=np.int32)  # (FIRST, MIDDLE, LAST) x (u -> w, w -> u)
    np.add(h0, 1, out=z[MIDDLE, 0])
    np.add(h1, 1, out=z[MIDDLE, 1])
    spokes = np.empty((2, mesh.n_corners), dtype=np.int32)
    if right:  # FIRST: (5 h0, 5 next(h1) + 4), LAST: (5 h1, 5 next(h0) + 4)
        z[FIRST, 0], z[LAST, 0] = h0, h1
        np.add(5 * ring.neighbour(pair[:, 1], 1), 4, out=z[FIRST, 1])
        np.add(5 * ring.neighbour(pair[:, 0], 1), 4, out=z[LAST, 1])
        ring.corner_ids(0, spokes[0], scale=5, offset=2)
        ring.corner_ids(1, spokes[1], scale=5, offset=3)
    else:  # FIRST: (5 prev(h0) + 3, 5 h1 + 2), LAST: (5 prev(h1) + 3, 5 h0 + 2)
        np.add(5 * ring.neighbour(pair[:, 0], -1), 3, out=z[FIRST, 0])
        np.add(5 * ring.neighbour(pair[:, 1], -1), 3, out=z[LAST, 0])
        np.add(h1, 2, out=z[FIRST, 1])
        np.add(h0, 2, out=z[LAST, 1])
        ring.corner_ids(-1, spokes[0], scale=5, offset=4)
        ring.corner_ids(0, spokes[1], scale=5)
    for col in (0, 1):  # outer edges: no half-edge on one side
        e = np.flatnonzero(pair[:, col] < 0)
        z[FIRST, col, e] = z[MIDDLE, col, e] = z[LAST, 1 - col, e] = -1
    out = np.empty((3 * n_e + mesh.n_corners, 2), dtype=np.int32)
    interleave(z.reshape(6, n_e), out=out[:3 * n_e].reshape(n_e, 6))
    interleave(spokes, out=out[3 * n_e:])
    return out


def _divide(values: NDArray[np.complex128], by) -> None:
    """``values /= by`` in place for real ``by``, with the bits numpy's complex division gives
    (it multiplies by the reciprocal), on the float view: a third of the time."""
    floats = values.view(np.float64).reshape(-1, 2)
    floats *= (1.0 / np.asarray(by, dtype=np.float64))[..., None]


def _vertex_centres(mesh: Mesh, ring: Corners, vertices, x, y, old, right: bool):
    """(H,) complex vertex mean of every child face before smoothing.

    The five corners are added in face order, exactly as ``face_centroids`` of the child would,
    but read from where they are known: the parent's centre (per face), the old vertex and the
    Z vertices x_h and y_h (once per corner; the last corner, x of the neighbour, by shifting
    x along the face).
    """
    points = vertices.view(np.complex128).ravel()
    centre = points[mesh.n_vertices + 2 * mesh.topology.n_edges:]
    xs = np.take(points, x, mode="clip")
    scratch = np.take(points, y, mode="clip")
    if right:  # a + y + x + c + x[prev]
        out = np.take(points, old, mode="clip")
        out += scratch
        out += xs
        ring.plus_face_values(out, centre, out=out)
    else:  # c + x + y + b + x[next] (c + x is x + c: a sum of two rounds the same both ways)
        out = np.empty_like(xs)
        ring.plus_face_values(xs, centre, out=out)
        out += scratch
        out += np.take(points, old, out=scratch, mode="clip")
    ring.shifted(xs, -1 if right else 1, out=out, plus=out)
    _divide(out, 5)
    return out


def _smooth(parent: Mesh, ring: Corners, vertices, centres, old, right: bool) -> None:
    """Operation 4, in place: every inner vertex moves to the mean centre of its faces.

    The faces around each kind of child vertex are known from the parent, so the sums run
    over parent corners (H) instead of child corners (5H), from ``centres``, the child face
    centres before smoothing: a Z vertex x_h lies in P_h, P_around(h) and (inner edges)
    P_twin(h), summed in that order edge by edge; a centre in the faces of its parent face; an
    old vertex in one face per parent corner at it.
    """
    topo = parent.topology
    n_v, n_e = parent.n_vertices, topo.n_edges
    flat = vertices.view(np.complex128).ravel()
    z = flat[n_v:n_v + 2 * n_e].reshape(n_e, 2)
    lone = np.flatnonzero(topo.boundary_edges)  # outer Z vertices stay
    keep = z[lone]
    near = np.empty_like(centres)  # c_h + c_around(h)
    ring.shifted(centres, 1 if right else -1, out=near, plus=centres)
    h0, h1 = (np.ascontiguousarray(topo.edge_half_edges[:, c], dtype=np.intp) for c in (0, 1))
    first, other = np.empty(n_e, dtype=np.complex128), np.empty(n_e, dtype=np.complex128)
    for h, twin, col in ((h0, h1, int(right)), (h1, h0, 1 - int(right))):  # x_h0 is z0 (left)
        np.add(np.take(near, h, out=first, mode="clip"),
               np.take(centres, twin, out=other, mode="clip"), out=z[:, col])
    del near, first, other
    _divide(z.ravel(), 3)
    z[lone] = keep
    if ring.k:
        face_sum = centres.reshape(-1, ring.k).sum(axis=1)
    else:
        face_sum = np.add.reduceat(centres, parent.face_offsets[:-1])
    _divide(face_sum, ring.k or parent.face_sizes)
    flat[n_v + 2 * n_e:] = face_sum
    inner = ~outer_vertices(parent)
    scale = 1.0 / np.bincount(old, minlength=n_v)[inner]  # as _divide: times the reciprocal
    for c, part in ((0, centres.real), (1, centres.imag)):
        vertices[:n_v, c][inner] = np.bincount(old, weights=part, minlength=n_v)[inner] * scale
