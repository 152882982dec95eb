"""Array helpers shared by the classic schemes (no Python loop over mesh elements)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..errors import MeshError
from ..mesh import Mesh, Topology

BLOCK = 32768  # rows of an interleaved output written at once (< 1 MiB: within the L2 cache)


def require_degree(mesh: Mesh, k: int, scheme: str) -> NDArray[np.int32]:
    """(F, k) dense faces, or MeshError naming the first face of another degree."""
    dense = mesh.dense_faces()
    if mesh.n_faces and (dense is None or dense.shape[1] != k):
        f = int(np.flatnonzero(mesh.face_sizes != k)[0])
        raise MeshError(f"{scheme} needs faces with {k} corners; face {f} has "
                        f"{mesh.face_sizes[f]}")
    return mesh.face_indices.reshape(-1, k)


class Corners:
    """Corner (half-edge) arithmetic of a mesh: the face of a corner, its next and previous.

    When every face has k corners, corner h is position ``h % k`` of face ``h // k``, so the
    next corner is the next element (but at the end of a face) and no index array is needed;
    otherwise the mesh's ``next_half_edge``, ``prev_half_edge`` and ``half_edge_face`` are
    used. Methods take and write (H,) per-corner arrays, which may be strided views.

    Examples
    --------
    >>> from weavecut.mesh import Mesh
    >>> ring = Corners(Mesh.from_faces([(0, 0), (1, 0), (1, 1), (0, 1)], [[0, 1, 2, 3]]))
    >>> out = np.empty(4, dtype=np.int32)
    >>> ring.corner_ids(1, out, offset=10); out
    array([11, 12, 13, 10], dtype=int32)
    """

    def __init__(self, mesh: Mesh) -> None:
        self.mesh = mesh
        self.k = mesh.face_degree

    def grid(self, a: NDArray) -> NDArray:
        """(F, k) view of a per-corner array when faces have one degree (never a copy)."""
        view = a.view()
        view.shape = (-1, self.k)  # raises rather than copy
        return view

    def shifted(self, src: NDArray, shift: int, out: NDArray, plus: NDArray | None = None) -> None:
        """``out[h] = src[h']`` (``plus[h] + src[h']`` with ``plus``, which may be ``out``), h'
        the next (shift 1) or previous (-1) corner of h's face. With one degree k this is one
        contiguous operation over all corners, the first or last of every face redone."""
        if not self.k:
            value = src[self.mesh.next_half_edge if shift == 1 else self.mesh.prev_half_edge]
            if plus is None:
                out[...] = value
            else:
                np.add(plus, value, out=out)
            return
        k = self.k
        if shift == 1:  # h' = h + 1, but the last corner of a face takes its first
            to, frm, ends, starts = slice(0, -1), slice(1, None), slice(k - 1, None, k), \
                slice(0, None, k)
        else:
            to, frm, ends, starts = slice(1, None), slice(0, -1), slice(0, None, k), \
                slice(k - 1, None, k)
        if plus is None:
            out[to] = src[frm]
            out[ends] = src[starts]
        else:
            wrapped = plus[ends] + src[starts]  # before ``out`` (maybe ``plus``) changes
            np.add(plus[to], src[frm], out=out[to])
            out[ends] = wrapped

    def plus_face_values(self, src: NDArray, values: NDArray, out: NDArray) -> None:
        """``out[h] = src[h] + values[face of h]`` (``out`` may be ``src``). With one degree k
        the (F,) values are broadcast over the (F, k) grid, with no per-corner copy."""
        if self.k:
            np.add(self.grid(src), values[:, None], out=self.grid(out))
        else:
            np.add(src, np.repeat(values, self.mesh.face_sizes), out=out)

    def face_values(self, offset: int, out: NDArray) -> None:
        """``out[h] = offset + (face of h)``."""
        if self.k:
            face = np.arange(offset, offset + self.mesh.n_faces, dtype=out.dtype)
            interleave([face] * self.k, out=self.grid(out))
        else:
            np.add(self.mesh.half_edge_face, offset, out=out)

    def corner_ids(self, shift: int, out: NDArray, scale: int = 1, offset: int = 0) -> None:
        """``out[h] = scale * h' + offset``, h' = h (shift 0), its next (1) or previous (-1)
        corner."""
        n = self.mesh.n_corners
        if self.k:  # h + shift, but for the corner that wraps around its face
            start = scale * shift + offset
            out[...] = np.arange(start, start + scale * n, scale, dtype=out.dtype)
            if shift:
                out[self.k - 1 if shift == 1 else 0::self.k] -= scale * shift * self.k
        else:
            ids = np.arange(n, dtype=np.int32)
            np.add(scale * (ids if shift == 0 else self.neighbour(ids, shift)), offset, out=out)

    def neighbour(self, ids: NDArray[np.int32], shift: int) -> NDArray[np.int32]:
        """The next (shift 1) or previous (-1) corner of each corner in ``ids`` (any value
        where ``ids`` is negative)."""
        if not self.k:
            return (self.mesh.next_half_edge if shift == 1 else self.mesh.prev_half_edge)[ids]
        wrap = (ids % self.k) == (self.k - 1 if shift == 1 else 0)
        out = ids + shift
        out -= shift * self.k * wrap
        return out

    def face_ids(self) -> NDArray[np.int32]:
        """(H,) face of every corner."""
        if not self.k:
            return self.mesh.half_edge_face
        return np.repeat(np.arange(self.mesh.n_faces, dtype=np.int32), self.k)

    def positions(self) -> NDArray[np.int32]:
        """(H,) position of every corner within its face."""
        if not self.k:
            return corner_index(self.mesh)
        out = np.empty(self.mesh.n_corners, dtype=np.int32)
        fill_rows(self.grid(out), np.arange(self.k, dtype=np.int32))
        return out


def interleave(columns, out: NDArray | None = None) -> NDArray:
    """The (n, m) array whose column j is ``columns[j]`` ((m, n) array or m arrays (n,)),
    written in blocks of ``BLOCK`` rows, each column by one strided copy: the block stays in
    the cache while its m columns arrive, and every copy is one long loop (a transposed
    ``copyto`` or a broadcast runs its inner loop over the m elements of a row, at about five
    times the instructions).

    Examples
    --------
    >>> interleave(np.array([[1, 2, 3], [4, 5, 6]]))
    array([[1, 4],
           [2, 5],
           [3, 6]])
    """
    if out is None:
        first = np.asarray(columns[0])
        out = np.empty((len(first), len(columns)), dtype=first.dtype)
    for start in range(0, len(out), BLOCK):
        rows = out[start:start + BLOCK]
        for j, column in enumerate(columns):
            rows[:, j] = column[start:start + BLOCK]
    return out


def fill_rows(out: NDArray, row) -> None:
    """Set every row of the C-contiguous (n, m) ``out`` to ``row``, by doubling block copies
    (a few contiguous copies instead of one short copy per row)."""
    n = len(out)
    out[:min(n, 1024)] = row
    done = min(n, 1024)
    while done < n:
        step = min(done, n - done)
        out[done:done + step] = out[:step]
        done += step


def corner_index(mesh: Mesh) -> NDArray[np.int32]:
    """(H,) position of every corner within its face (0 .. n_f - 1)."""
    start = np.repeat(mesh.face_offsets[:-1], mesh.face_sizes)
    return (np.arange(mesh.n_corners, dtype=np.int64) - start).astype(np.int32)


def child_topology(face_indices: NDArray[np.int32], next_half_edge: NDArray[np.int32],
                   half_edge_edge: NDArray[np.int32], n_edges: int) -> Topology:
    """Topology of a child mesh whose half-edge -> edge map the step knows already.

    Sorting the endpoints per half-edge gives ``edges`` (u < w) and the sides without the
    ``np.unique`` of ``Topology.build``.
    """
    a = face_indices
    b = face_indices[next_half_edge]
    side = a > b
    edges = np.empty((n_edges, 2), dtype=np.int32)
    edges[half_edge_edge, 0] = np.minimum(a, b)
    edges[half_edge_edge, 1] = np.maximum(a, b)
    return Topology(edges, half_edge_edge.astype(np.int32, copy=False), side.view(np.int8))


def trusted_dense(vertices: NDArray[np.float64], faces: NDArray[np.int32], topology: Topology,
                  boundary: NDArray[np.bool_] | None = None) -> Mesh:
    """A trusted mesh of (F, k) faces with a topology the step built itself."""
    n_f, k = faces.shape
    if boundary is not None:
        topology.__dict__["boundary_edges"] = boundary
    offsets = np.arange(0, k * n_f + 1, k, dtype=np.int64)
    return Mesh.trusted(vertices, offsets, faces.reshape(-1), topology)


def ragged_mesh(vertices: NDArray[np.float64], offsets: NDArray[np.int64],
                face_indices: NDArray[np.int32], half_edge_edge: NDArray[np.int32],
                n_edges: int) -> Mesh:
    """A trusted mesh of ragged faces with its topology attached."""
    mesh = Mesh.trusted(vertices, offsets.astype(np.int64), face_indices.astype(np.int32))
    mesh.__dict__["topology"] = child_topology(mesh.face_indices, mesh.next_half_edge,
                                               half_edge_edge.astype(np.int32), n_edges)
    return mesh


def is_outer(mesh: Mesh) -> NDArray[np.bool_]:
    """(V,) True for vertices on an outer edge, and for vertices no face uses."""
    topo = mesh.topology
    mask = np.bincount(mesh.face_indices, minlength=mesh.n_vertices) == 0
    mask[topo.edges[topo.boundary_edges].ravel()] = True
    return mask


def rotate_ccw(mesh: Mesh) -> NDArray[np.int32]:
    """(H,) the next outgoing half-edge counter-clockwise around its start vertex (-1: none)."""
    return mesh.topology.twin[mesh.prev_half_edge]


def vertex_rings(mesh: Mesh, vertices: NDArray[np.int64]) -> tuple[NDArray, NDArray]:
    """Outgoing half-edges (corners) of the given vertices, counter-clockwise.

    Returns ``(offsets, half_edges)`` in CSR form, ring ``i`` belonging to ``vertices[i]``.
    The ring of an outer vertex starts at its outgoing outer half-edge, so it is the fan of
    its faces in order. The walk is one array step per ring position (a loop over the largest
    valence only).
    """
    first = np.full(mesh.n_vertices, -1, dtype=np.int64)
    first[mesh.face_indices[::-1]] = np.arange(mesh.n_corners - 1, -1, -1)
    twin = mesh.topology.twin
    lone = np.flatnonzero(twin < 0)
    first[mesh.face_indices[lone]] = lone
    valence = np.bincount(mesh.face_indices, minlength=mesh.n_vertices)[vertices]
    offsets = np.zeros(len(vertices) + 1, dtype=np.int64)
    np.cumsum(valence, out=offsets[1:])
    ring = np.empty(offsets[-1], dtype=np.int32)
    rot = rotate_ccw(mesh)
    active = np.arange(len(vertices))
    current = first[vertices]
    j = 0
    while len(active):
        ring[offsets[active] + j] = current
        j += 1
        keep = valence[active] > j
        active, current = active[keep], rot[current[keep]]
    return offsets, ring


def boundary_successor(mesh: Mesh) -> NDArray[np.int64]:
    """(V,) for an outer vertex the next outer vertex along the boundary (face on the left)."""
    topo = mesh.topology
    out = np.full(mesh.n_vertices, -1, dtype=np.int64)
    lone = topo.edge_half_edges[topo.boundary_edges].max(axis=1)
    out[mesh.face_indices[lone]] = mesh.face_indices[mesh.next_half_edge[lone]]
    return out


def boundary_predecessor(mesh: Mesh) -> NDArray[np.int64]:
    """(V,) for an outer vertex the previous outer vertex along the boundary."""
    succ = boundary_successor(mesh)
    out = np.full(mesh.n_vertices, -1, dtype=np.int64)
    has = np.flatnonzero(succ >= 0)
    out[succ[has]] = has
    return out


def vertex_sums(n: int, index: NDArray, values: NDArray[np.float64]) -> NDArray[np.float64]:
    """(n, 2) sums of (m, 2) ``values`` grouped by ``index`` (bincount per coordinate)."""
    out = np.empty((n, 2))
    out[:, 0] = np.bincount(index, weights=values[:, 0], minlength=n)
    out[:, 1] = np.bincount(index, weights=values[:, 1], minlength=n)
    return out


def neighbour_sums(mesh: Mesh, edge_mask: NDArray[np.bool_] | None = None):
    """(V, 2) sum of neighbour positions and (V,) neighbour counts over (selected) edges."""
    e = mesh.topology.edges
    if edge_mask is not None:
        e = e[edge_mask]
    n = mesh.n_vertices
    ends = np.concatenate([e[:, 0], e[:, 1]])
    other = np.concatenate([e[:, 1], e[:, 0]])
    sums = vertex_sums(n, ends, np.take(mesh.vertices, other, axis=0))
    return sums, np.bincount(ends, minlength=n)
