"""The mesh: vertices plus ragged counter-clockwise faces, with topology derived once.

A mesh is planar (vertices (V, 2)) or a surface in space (vertices (V, 3), faces
counter-clockwise seen from outside). Topology code never looks at coordinates; geometry code
(``mesh_geometry``) takes the dimension from the array, so the planar scheme is the 3-D scheme
on z = 0.

Face ``f`` is ``face_indices[face_offsets[f]:face_offsets[f + 1]]``. Corner ``h`` of the mesh
(an index into ``face_indices``) is also half-edge ``h``: it runs from ``face_indices[h]`` to
the next corner of the same face. Letters: V vertices, E edges, F faces, H corners (half-edges).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from .errors import MeshError, NonManifoldError


@dataclass(frozen=True)
class Numbering:
    """How error messages name faces and vertices: from 0, as the arrays (and weave-cut's JSON)
    count them, or from 1 with the line that defines each face, as an OBJ file counts them.

    Examples
    --------
    >>> Numbering().face(4), Numbering(first=1, face_lines=np.array([7, 9])).face(1)
    ('face 4', 'face 2 (line 9)')
    """

    first: int = 0
    face_lines: NDArray[np.int64] | None = None

    def number(self, index) -> int:
        """The number a reader of the source gives element ``index``."""
        return int(index) + self.first

    def face(self, f) -> str:
        line = "" if self.face_lines is None else f" (line {self.face_lines[f]})"
        return f"face {self.number(f)}{line}"

    def vertex(self, v) -> str:
        return f"vertex {self.number(v)}"

    def edge(self, u, w) -> str:
        return f"edge ({self.number(u)}, {self.number(w)})"


ZERO_BASED = Numbering()


@dataclass(frozen=True, eq=False)
class Mesh:
    """Planar mesh or surface with faces of any degree.

    Parameters
    ----------
    vertices : (V, 2) or (V, 3) float64
    face_offsets : (F + 1,) int64, starting at 0 and ending at H
    face_indices : (H,) int32, vertex of every corner
    """

    vertices: NDArray[np.float64]
    face_offsets: NDArray[np.int64]
    face_indices: NDArray[np.int32]

    def __post_init__(self) -> None:
        for name, dtype in (
            ("vertices", np.float64),
            ("face_offsets", np.int64),
            ("face_indices", np.int32),
        ):
            arr = np.array(getattr(self, name), dtype=dtype)  # a private copy
            arr.flags.writeable = False
            object.__setattr__(self, name, arr)
        check_structure(self)

    @classmethod
    def from_faces(cls, vertices, faces) -> Mesh:
        """Build a mesh from a vertex list and a list of faces (lists of vertex indices).

        Examples
        --------
        >>> Mesh.from_faces([(0, 0), (1, 0), (1, 1), (0, 1)], [[0, 1, 2, 3]]).n_faces
        1
        """
        faces = [list(f) for f in faces]
        sizes = np.fromiter(map(len, faces), dtype=np.int64, count=len(faces))
        offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
        try:
            flat = np.array([i for f in faces for i in f], dtype=np.int64)
        except (OverflowError, TypeError, ValueError):
            raise MeshError("face vertex indices must be integers in range") from None
        if len(flat) and np.abs(flat).max() >= 2**31:
            raise MeshError(f"vertex index {flat[np.abs(flat).argmax()]} is out of range")
        vertices = np.asarray(vertices, dtype=np.float64)
        if vertices.ndim != 2:  # an empty list
            vertices = vertices.reshape(-1, 2)
        return cls(vertices, offsets, flat)

    @classmethod
    def trusted(cls, vertices, face_offsets, face_indices, topology: Topology | None = None) -> Mesh:
        """Wrap arrays that a subdivision step built correct by construction (no copy, no checks)."""
        mesh = object.__new__(cls)
        for name, arr in (
            ("vertices", vertices),
            ("face_offsets", face_offsets),
            ("face_indices", face_indices),
        ):
            arr.flags.writeable = False
            object.__setattr__(mesh, name, arr)
        if topology is not None:
            mesh.__dict__["topology"] = topology
        return mesh

    # -- sizes ------------------------------------------------------------------------------
    @property
    def n_vertices(self) -> int:
        return len(self.vertices)

    @property
    def dim(self) -> int:
        """2 for a planar mesh, 3 for a surface in space."""
        return self.vertices.shape[1]

    @property
    def n_faces(self) -> int:
        return len(self.face_offsets) - 1

    @property
    def n_corners(self) -> int:
        return len(self.face_indices)

    @cached_property
    def face_sizes(self) -> NDArray[np.int64]:
        """(F,) number of corners of every face."""
        return np.diff(self.face_offsets)

    @cached_property
    def face_degree(self) -> int | None:
        """The common degree k of all faces, or None when degrees differ."""
        if self.n_faces == 0:
            return None
        lo, hi = self.face_sizes.min(), self.face_sizes.max()
        return int(lo) if lo == hi else None

    def dense_faces(self) -> NDArray[np.int32] | None:
        """(F, k) view of the faces when all have degree k, else None."""
        k = self.face_degree
        return None if k is None else self.face_indices.reshape(-1, k)

    def faces(self) -> list[list[int]]:
        """Faces as Python lists (for small meshes, I/O and tests)."""
        return [
            self.face_indices[a:b].tolist()
            for a, b in zip(self.face_offsets[:-1].tolist(), self.face_offsets[1:].tolist())
        ]

    # -- corners ----------------------------------------------------------------------------
    @cached_property
    def half_edge_face(self) -> NDArray[np.int32]:
        """(H,) face of every corner."""
        return np.repeat(np.arange(self.n_faces, dtype=np.int32), self.face_sizes)

    @cached_property
    def next_half_edge(self) -> NDArray[np.int32]:
        """(H,) next corner of the same face (counter-clockwise)."""
        nxt = np.arange(1, self.n_corners + 1, dtype=np.int32)
        if self.n_faces:
            nxt[self.face_offsets[1:] - 1] = self.face_offsets[:-1]
        return nxt

    @cached_property
    def prev_half_edge(self) -> NDArray[np.int32]:
        """(H,) previous corner of the same face."""
        prev = np.empty(self.n_corners, dtype=np.int32)
        prev[self.next_half_edge] = np.arange(self.n_corners, dtype=np.int32)
        return prev

    @cached_property
    def topology(self) -> Topology:
        """Edges, twins and boundary, built on first use."""
        return Topology.build(self)

    def moved(self, vertices: NDArray[np.float64]) -> Mesh:
        """The same faces with new vertex positions; the topology is shared."""
        vertices = np.asarray(vertices, dtype=np.float64)
        if vertices.shape != self.vertices.shape:
            raise MeshError(f"moved() needs {self.vertices.shape} vertices, got {vertices.shape}")
        mesh = Mesh.trusted(vertices.copy(), self.face_offsets, self.face_indices)
        for name in ("topology", "face_sizes", "half_edge_face", "next_half_edge"):
            if name in self.__dict__:
                mesh.__dict__[name] = self.__dict__[name]
        return mesh

    def reversed(self) -> Mesh:
        """Every face with its corner order reversed (orientation flipped)."""
        first = np.repeat(self.face_offsets[:-1], self.face_sizes)
        last = np.repeat(self.face_offsets[1:] - 1, self.face_sizes)
        order = first + last - np.arange(self.n_corners)
        return Mesh(self.vertices, self.face_offsets, self.face_indices[order])


MAX_COMPARED = 16  # faces of more corners are checked for repeats by sorting


def check_structure(mesh: Mesh, numbering: Numbering = ZERO_BASED) -> None:
    """Raise MeshError for bad shapes, indices, short faces, repeated corners or coordinates."""
    n = numbering
    v, off, idx = mesh.vertices, mesh.face_offsets, mesh.face_indices
    if v.ndim != 2 or v.shape[1] not in (2, 3):
        raise MeshError(f"vertices must have shape (V, 2) or (V, 3), got {v.shape}")
    if len(v) >= 2**31:
        raise MeshError(f"{len(v)} vertices is more than weave-cut indexes ({2**31 - 1})")
    bad = np.flatnonzero(~np.isfinite(v).all(axis=1))
    if len(bad):
        raise MeshError(f"{n.vertex(bad[0])} has a non-finite coordinate {tuple(v[bad[0]].tolist())}")
    if off.ndim != 1 or len(off) < 1 or off[0] != 0 or off[-1] != len(idx):
        raise MeshError("face offsets must start at 0 and end at the number of corners")
    sizes = np.diff(off)
    if (sizes < 3).any():
        f = int(np.flatnonzero(sizes < 3)[0])
        raise MeshError(f"{n.face(f)} has {sizes[f]} corner{'' if sizes[f] == 1 else 's'}; a face "
                        "needs at least 3")
    if len(idx) and (idx.min() < 0 or idx.max() >= len(v)):
        h = int(np.flatnonzero((idx < 0) | (idx >= len(v)))[0])
        f = int(np.searchsorted(off, h, side="right") - 1)
        raise MeshError(f"{n.face(f)} uses vertex {n.number(idx[h])}, out of range "
                        f"{n.number(0)}..{n.number(len(v) - 1)}")
    f = _first_repeating_face(off, idx, sizes)
    if f is not None:
        corners = np.sort(idx[off[f]:off[f + 1]])
        vtx = corners[np.flatnonzero(corners[1:] == corners[:-1])[0]]
        raise MeshError(f"{n.face(f)} visits {n.vertex(vtx)} more than once")


def _first_repeating_face(off, idx, sizes) -> int | None:
    """The first face that visits a vertex twice, or None: the faces of each degree up to
    ``MAX_COMPARED`` as a table whose columns are compared with their shifts, larger faces
    by sorting (face, vertex) keys."""
    repeating = []
    degrees = np.flatnonzero(np.bincount(np.minimum(sizes, MAX_COMPARED + 1)))
    for k in degrees[degrees <= MAX_COMPARED].tolist():
        faces = np.flatnonzero(sizes == k) if len(degrees) > 1 else None
        table = idx.reshape(-1, k) if faces is None else idx[off[faces, None] + np.arange(k)]
        same = np.zeros(len(table), dtype=bool)
        for shift in range(1, k):
            same |= (table[:, shift:] == table[:, :-shift]).any(axis=1)
        if same.any():
            first = int(np.flatnonzero(same)[0])
            repeating.append(first if faces is None else int(faces[first]))
    large = np.flatnonzero(sizes > MAX_COMPARED)
    if len(large):
        n_v = max(int(idx.max()) + 1, 1)
        ks = sizes[large]
        corner = np.repeat(off[large] - np.cumsum(ks) + ks, ks) + np.arange(ks.sum())
        key = np.sort(np.repeat(large, ks) * n_v + idx[corner])
        dup = np.flatnonzero(key[1:] == key[:-1])
        if len(dup):
            repeating.append(int(key[dup[0]] // n_v))
    return min(repeating, default=None)


@dataclass(frozen=True, eq=False)
class Topology:
    """Undirected edges and their half-edges.

    Parameters
    ----------
    edges : (E, 2) int32, ``u < w``
    half_edge_edge : (H,) int32, edge of every half-edge
    half_edge_side : (H,) int8, 0 when the half-edge runs u -> w (its face is left of u -> w)
    """

    edges: NDArray[np.int32]
    half_edge_edge: NDArray[np.int32]
    half_edge_side: NDArray[np.int8]

    @classmethod
    def build(cls, mesh: Mesh, numbering: Numbering = ZERO_BASED) -> Topology:
        """Derive the topology with one sort; raise NonManifoldError on a bad edge or vertex
        (elements named by ``numbering``)."""
        n = numbering
        u = mesh.face_indices.astype(np.int64)
        w = u[mesh.next_half_edge]
        n_v = max(mesh.n_vertices, 1)
        key = np.minimum(u, w) * n_v + np.maximum(u, w)
        edge_key, he_edge = np.unique(key, return_inverse=True)
        he_edge = he_edge.reshape(-1).astype(np.int32)
        edges = np.column_stack(np.divmod(edge_key, n_v)).astype(np.int32)
        side = (u > w).astype(np.int8)
        uses = np.bincount(he_edge, minlength=len(edges))
        if (uses > 2).any():
            e = int(np.flatnonzero(uses > 2)[0])
            raise NonManifoldError(
                f"{n.edge(*edges[e])} is in {uses[e]} faces; at most 2 allowed"
            )
        taken = np.bincount(2 * he_edge.astype(np.int64) + side, minlength=2 * len(edges))
        if (taken > 1).any():
            e = int(np.flatnonzero(taken > 1)[0] // 2)
            faces = mesh.half_edge_face[he_edge == e].tolist()
            raise NonManifoldError(
                f"{n.edge(*edges[e])} runs the same way in {n.face(faces[0])} and "
                f"{n.face(faces[1])} (the two faces are inconsistently oriented)"
            )
        topo = cls(edges, he_edge, side)
        _check_vertex_fans(mesh, topo, n)
        return topo

    @property
    def n_edges(self) -> int:
        return len(self.edges)

    @cached_property
    def edge_half_edges(self) -> NDArray[np.int32]:
        """(E, 2) the half-edge running u -> w (column 0) and w -> u (column 1); -1 if none."""
        out = np.full((len(self.edges), 2), -1, dtype=np.int32)
        out[self.half_edge_edge, self.half_edge_side] = np.arange(
            len(self.half_edge_edge), dtype=np.int32
        )
        return out

    @cached_property
    def twin(self) -> NDArray[np.int32]:
        """(H,) the opposite half-edge, -1 on the boundary."""
        return self.edge_half_edges[self.half_edge_edge, 1 - self.half_edge_side]

    @cached_property
    def boundary_edges(self) -> NDArray[np.bool_]:
        """(E,) True for outer edges (one face)."""
        return (self.edge_half_edges < 0).any(axis=1)


def _check_vertex_fans(mesh: Mesh, topo: Topology, numbering: Numbering) -> None:
    """A vertex where two boundary fans meet (a bow-tie) is not 2-manifold."""
    he = topo.edge_half_edges
    lone = he[(he < 0).any(axis=1)].max(axis=1)
    starts = np.bincount(mesh.face_indices[lone], minlength=mesh.n_vertices)
    if (starts > 1).any():
        v = int(np.flatnonzero(starts > 1)[0])
        raise NonManifoldError(f"{numbering.vertex(v)} joins {starts[v]} separate fans of faces "
                               "(a bow-tie)")


def edge_faces(mesh: Mesh) -> NDArray[np.int32]:
    """(E, 2) face left of u -> w (column 0) and right of it (column 1); -1 if none."""
    he = mesh.topology.edge_half_edges
    return np.where(he >= 0, mesh.half_edge_face[np.maximum(he, 0)], -1).astype(np.int32)


def outer_vertices(mesh: Mesh) -> NDArray[np.bool_]:
    """(V,) True for vertices on an outer edge."""
    topo = mesh.topology
    mask = np.zeros(mesh.n_vertices, dtype=bool)
    mask[topo.edges[topo.boundary_edges].ravel()] = True
    return mask


def vertex_degrees(mesh: Mesh) -> NDArray[np.int64]:
    """(V,) number of edges at every vertex."""
    degrees = np.zeros(mesh.n_vertices, dtype=np.int64)
    np.add.at(degrees, mesh.topology.edges.ravel(), 1)  # no intp copy of the edges (bincount)
    return degrees
