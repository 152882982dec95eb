"""Geometric checks on input meshes: orientation, degenerate, non-convex and overlapping faces.

A surface in space (vertices (V, 3)) is checked as an oriented 2-manifold only: no zero-area
face or zero-length edge, no unused vertex, no non-manifold edge or vertex, consistent
orientation (outwards on a closed surface).

The Mesh constructor already refuses bad indices, short faces, repeated corners and
non-finite coordinates; ``Topology.build`` refuses non-manifold edges and bow-tie vertices.
Every check is vectorised over corners; shapely (GEOS) decides only the faces that simple
arithmetic cannot certify, so a million faces take a second or two.
"""

from __future__ import annotations

import numpy as np
import shapely
from numpy.typing import NDArray

from .errors import MeshError
from .graphs import components
from .mesh import ZERO_BASED, Mesh, Numbering, Topology, outer_vertices
from .mesh_geometry import face_perimeters, signed_areas
from .surface import signed_volume, vector_areas

AREA_EPS = 1e-12
MAX_COORDINATE = 1e9


class _Corners:
    """Per-corner geometry shared by the checks: position, outgoing edge, turn and angle."""

    def __init__(self, mesh: Mesh) -> None:
        p = np.take(mesh.vertices, mesh.face_indices, axis=0)
        x, y = p[:, 0], p[:, 1]
        nxt, prev = mesh.next_half_edge, mesh.prev_half_edge
        self.x, self.y = x, y
        ex, ey = x[nxt] - x, y[nxt] - y  # edge to the next corner
        px, py = ex[prev], ey[prev]  # edge from the previous corner
        self.turn = px * ey - py * ex  # cross product, negative at a reflex corner
        self.dot = px * ex + py * ey
        self.cross_next = x * y[nxt] - y * x[nxt]  # shoelace terms

    def angles(self) -> NDArray[np.float64]:
        """(H,) interior angle at every corner in radians, as ``mesh_geometry.corner_angles``."""
        return np.mod(np.arctan2(self.turn, -self.dot), 2 * np.pi)


def validate(mesh: Mesh, *, allow_nonconvex: bool = False,
             numbering: Numbering = ZERO_BASED) -> Mesh:
    """Return ``mesh`` (re-oriented if consistently clockwise) or raise MeshError.

    Parameters
    ----------
    mesh : Mesh
    allow_nonconvex : bool
        Accept faces with reflex corners (they must still be simple and not overlap).
    numbering : Numbering
        How messages name faces and vertices (1-based with line numbers for an OBJ file).
    """
    n = numbering
    if mesh.n_faces == 0:
        raise MeshError("the mesh has no faces")
    huge = np.abs(mesh.vertices).max(axis=1) > MAX_COORDINATE
    if huge.any():
        raise MeshError(f"{n.vertex(np.flatnonzero(huge)[0])} has a coordinate beyond "
                        f"{MAX_COORDINATE:g}; scale the mesh down")
    if mesh.dim == 3:
        return _validate_surface(mesh, n)
    corners = _Corners(mesh)
    areas = 0.5 * np.add.reduceat(corners.cross_next, mesh.face_offsets[:-1])
    scale = max(float(np.ptp(mesh.vertices, axis=0).max()), 1e-300) ** 2
    flat = np.abs(areas) <= AREA_EPS * scale
    if flat.any():
        raise MeshError(f"{n.face(np.flatnonzero(flat)[0])} has zero area")
    if (areas < 0).all():
        mesh = mesh.reversed()
        areas = -areas
        corners = _Corners(mesh)
    elif (areas < 0).any():
        f = int(np.flatnonzero(areas < 0)[0])
        raise MeshError(f"{n.face(f)} is clockwise while others are counter-clockwise "
                        f"({int((areas < 0).sum())} of {mesh.n_faces} faces are clockwise)")
    if "topology" not in mesh.__dict__:  # non-manifold edges and vertices raise here
        mesh.__dict__["topology"] = Topology.build(mesh, n)
    if not allow_nonconvex:
        reflex = corners.turn < -AREA_EPS * scale
        if reflex.any():
            h = int(np.flatnonzero(reflex)[0])
            raise MeshError(f"{n.face(mesh.half_edge_face[h])} is not convex at "
                            f"{n.vertex(mesh.face_indices[h])}: the snub scheme assumes convex "
                            "faces (deep levels of some inputs have a few non-convex faces, see "
                            "weave-cut convexity); pass --allow-nonconvex to use the mesh anyway")
    _check_overlaps(mesh, corners, scale, n)
    return mesh


def _validate_surface(mesh: Mesh, n: Numbering) -> Mesh:
    """``mesh``, a surface in space, turned outwards if closed and inside-out; or MeshError."""
    scale = max(float(np.ptp(mesh.vertices, axis=0).max()), 1e-300) ** 2
    flat = np.linalg.norm(vector_areas(mesh), axis=1) <= AREA_EPS * scale
    if flat.any():
        raise MeshError(f"{n.face(np.flatnonzero(flat)[0])} has zero area")
    ends = mesh.face_indices, mesh.face_indices[mesh.next_half_edge]
    d = mesh.vertices[ends[1]] - mesh.vertices[ends[0]]
    short = np.flatnonzero((d * d).sum(axis=1) <= AREA_EPS * scale)
    if len(short):  # the snub step turns every edge by its direction
        h = short[0]
        raise MeshError(f"{n.face(mesh.half_edge_face[h])} has an edge of zero length: "
                        f"{n.edge(ends[0][h], ends[1][h])} joins two vertices at one point")
    _check_every_vertex_used(mesh, n)  # an unused vertex has no place to be smoothed to
    if "topology" not in mesh.__dict__:  # non-manifold and inconsistently oriented edges raise
        mesh.__dict__["topology"] = Topology.build(mesh, n)
    if not mesh.topology.boundary_edges.any() and signed_volume(mesh) < 0:
        mesh = mesh.reversed()
    return mesh


def _check_overlaps(mesh: Mesh, corners: _Corners, scale: float, n: Numbering) -> None:
    """Faces may touch along edges and at corners, never share interior points.

    A manifold mesh of counter-clockwise faces is embedded (no two faces overlap) when every
    face is simple, the corner angles around every inner vertex add up to one full turn (at
    most one at a boundary vertex), the boundary edges cross nowhere, and no boundary vertex
    lies inside a face. These are local checks plus a search over the boundary only.
    """
    angles = corners.angles()
    simple = _certainly_simple(mesh, corners, angles, scale)
    unsure = np.flatnonzero(~simple)
    if len(unsure):
        invalid = ~shapely.is_valid(_polygons(mesh, unsure))
        if invalid.any():
            raise MeshError(f"{n.face(unsure[np.flatnonzero(invalid)[0]])} intersects itself")
    _check_every_vertex_used(mesh, n)  # its angles add up to nothing: not a fan that overlaps
    topo = mesh.topology
    outer = outer_vertices(mesh)
    turn = np.bincount(mesh.face_indices, weights=angles, minlength=mesh.n_vertices) / (2 * np.pi)
    bad = np.flatnonzero(np.where(outer, turn > 1 + 1e-9, np.abs(turn - 1) > 1e-9))
    if len(bad):
        v = int(bad[0])
        raise MeshError(f"faces around {n.vertex(v)} overlap (their angles add up to "
                        f"{360 * turn[v]:.1f} degrees)")
    edges = topo.edges[topo.boundary_edges]
    segments = shapely.linestrings(mesh.vertices[edges.ravel()],
                                   indices=np.repeat(np.arange(len(edges)), 2))
    a, b = shapely.STRtree(segments).query(segments, predicate="intersects")
    apart = (a < b) & (edges[a][:, :, None] != edges[b][:, None, :]).all(axis=(1, 2))
    if apart.any():
        i, j = edges[a[apart][0]], edges[b[apart][0]]
        raise MeshError(f"faces overlap: boundary edges ({n.number(i[0])}, {n.number(i[1])}) "
                        f"and ({n.number(j[0])}, {n.number(j[1])}) cross")
    _check_boundary_vertices_outside(mesh, corners, np.unique(edges), n)


def _check_every_vertex_used(mesh: Mesh, n: Numbering) -> None:
    unused = np.flatnonzero(np.bincount(mesh.face_indices, minlength=mesh.n_vertices) == 0)
    if len(unused):
        raise MeshError(f"{n.vertex(unused[0])} is in no face")


def _certainly_simple(mesh: Mesh, corners: _Corners, angles, scale: float) -> NDArray[np.bool_]:
    """(F,) True for faces that turn left at every corner and go round exactly once.

    A closed polygon whose every corner turns strictly left and whose interior angles add up
    to (k - 2) pi (total turning one full turn) is convex, hence simple; GEOS decides the rest.
    """
    k = mesh.face_sizes
    left = np.minimum.reduceat(corners.turn, mesh.face_offsets[:-1]) > AREA_EPS * scale
    total = np.add.reduceat(angles, mesh.face_offsets[:-1])
    return left & (np.abs(total - (k - 2) * np.pi) < np.pi)


def _polygons(mesh: Mesh, faces: NDArray[np.int64]) -> NDArray[np.object_]:
    """Shapely polygons of the given faces."""
    sizes = mesh.face_sizes[faces]
    corners = np.repeat(mesh.face_offsets[faces] - np.cumsum(sizes) + sizes, sizes)
    corners += np.arange(len(corners))
    rings = shapely.linearrings(mesh.vertices[mesh.face_indices[corners]],
                                indices=np.repeat(np.arange(len(faces)), sizes))
    return shapely.polygons(rings)


def _check_boundary_vertices_outside(mesh: Mesh, corners: _Corners, boundary, n: Numbering):
    """No boundary vertex lies inside a face: a tree of the boundary vertices finds the faces
    whose circumscribing circle (centred on the vertex mean) holds one, GEOS decides those."""
    starts = mesh.face_offsets[:-1]
    k = mesh.face_sizes
    cx = np.add.reduceat(corners.x, starts) / k
    cy = np.add.reduceat(corners.y, starts) / k
    dist = np.hypot(corners.x - np.repeat(cx, k), corners.y - np.repeat(cy, k))
    radius = np.maximum.reduceat(dist, starts) * (1 + 1e-9)
    points = shapely.STRtree(shapely.points(mesh.vertices[boundary]))
    near = np.unique(points.query(shapely.points(cx, cy), predicate="dwithin",
                                  distance=radius)[0])
    if not len(near):
        return
    # boxes first (a thin face's circle holds many boundary vertices, its box few), then GEOS
    which, hit = points.query(_polygons(mesh, near), predicate="contains_properly")
    if len(hit):
        face, point = near[which], boundary[hit]
        first = np.lexsort((face, point))[0]
        raise MeshError(f"{n.vertex(point[first])} lies inside {n.face(face[first])} "
                        "(faces overlap)")


THINNEST = 1e-3  # isoperimetric quotient 4 pi A / P^2 of the thinnest face a layout accepts


def check_layout(mesh: Mesh, what: str, connected: bool = False) -> Mesh:
    """``mesh`` if ``what`` (the puzzle, the paper model) can lay it out: no sliver face (its
    strips and pieces would be thinner than floating point keeps apart) and, if
    ``connected``, one piece; otherwise a MeshError naming the face or the parts."""
    if mesh.dim == 3:
        raise MeshError(f"the mesh is a surface in space (x, y, z vertices); {what} needs a "
                        "flat mesh so far")
    quotient = 4 * np.pi * np.abs(signed_areas(mesh)) / face_perimeters(mesh) ** 2
    worst = int(np.argmin(quotient))
    if quotient[worst] < THINNEST:
        raise MeshError(f"face {worst + 1} is a sliver (area {quotient[worst]:.1e} of a circle "
                        f"with its perimeter); {what} needs faces at least {THINNEST:g} of that")
    if connected:
        twin = mesh.topology.twin
        inner = twin >= 0
        face = mesh.half_edge_face
        parts = components(mesh.n_faces, face[inner], face[twin[inner]])[0]
        if parts > 1:
            raise MeshError(f"the mesh has {parts} separate parts; {what} needs one piece")
    return mesh
