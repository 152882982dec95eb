"""The Weave: tiles, strands that visit them over or under, and strand lineage.

Every weave (snub octagons, quad crossings, glued triangles, face-split quads) is this one
structure, so colouring, checks and layouts work for all of them.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..mesh_geometry import face_centroids


@dataclass(frozen=True, eq=False)
class Weave:
    """Tiles made of mesh faces, and strands as ordered tile visits.

    Parameters
    ----------
    mesh : Mesh the tiles are made of
    tile_offsets : (T + 1,) int64; tile t is faces ``tile_faces[tile_offsets[t]:tile_offsets[t+1]]``
    tile_faces : (sum,) int32
    strand_offsets : (S + 1,) int64; strand s visits ``strand_visits[strand_offsets[s]:...]``
    strand_visits : (sum,) int32, tile ids in walking order
    visit_over : (sum,) bool, True where the strand is on top at that visit
    strand_closed : (S,) bool, True for closed loops (the last visit connects to the first)
    parent_strand : (S,) int32 strand of the previous level each strand follows (-1: none),
        or None when no lineage was computed
    """

    mesh: Mesh
    tile_offsets: NDArray[np.int64]
    tile_faces: NDArray[np.int32]
    strand_offsets: NDArray[np.int64]
    strand_visits: NDArray[np.int32]
    visit_over: NDArray[np.bool_]
    strand_closed: NDArray[np.bool_]
    parent_strand: NDArray[np.int32] | None = None

    @property
    def n_tiles(self) -> int:
        return len(self.tile_offsets) - 1

    @property
    def n_strands(self) -> int:
        return len(self.strand_offsets) - 1

    @cached_property
    def visit_strand(self) -> NDArray[np.int32]:
        """(sum,) strand of every visit."""
        return np.repeat(np.arange(self.n_strands, dtype=np.int32), np.diff(self.strand_offsets))

    @cached_property
    def tile_over(self) -> NDArray[np.int32]:
        """(T,) strand on top at every tile (-1: none)."""
        out = np.full(self.n_tiles, -1, dtype=np.int32)
        out[self.strand_visits[self.visit_over]] = self.visit_strand[self.visit_over]
        return out

    @cached_property
    def tile_under(self) -> NDArray[np.int32]:
        """(T,) strand passing below at every tile (-1: none)."""
        out = np.full(self.n_tiles, -1, dtype=np.int32)
        under = ~self.visit_over
        out[self.strand_visits[under]] = self.visit_strand[under]
        return out

    @cached_property
    def face_tile(self) -> NDArray[np.int32]:
        """(F,) tile of every mesh face (-1: in no tile)."""
        out = np.full(self.mesh.n_faces, -1, dtype=np.int32)
        out[self.tile_faces] = np.repeat(np.arange(self.n_tiles, dtype=np.int32),
                                         np.diff(self.tile_offsets))
        return out

    @cached_property
    def tile_centres(self) -> NDArray[np.float64]:
        """(T, D) mean of the vertex means of every tile's faces."""
        if not self.n_tiles:
            return np.zeros((0, self.mesh.dim))
        sums = np.add.reduceat(face_centroids(self.mesh)[self.tile_faces],
                               self.tile_offsets[:-1], axis=0)
        return sums / np.diff(self.tile_offsets)[:, None]

    def strand_lengths(self) -> NDArray[np.float64]:
        """(S,) length of every strand's centre line: the polyline through the centres of the
        tiles it visits, in walking order, closed for a loop (mesh units)."""
        if not self.n_strands:
            return np.zeros(0)
        points = self.tile_centres[self.strand_visits]
        step = np.linalg.norm(np.roll(points, -1, axis=0) - points, axis=1)
        start, end = self.strand_offsets[:-1], self.strand_offsets[1:] - 1
        closing = np.linalg.norm(points[start] - points[end], axis=1)
        step[end] = np.where(self.strand_closed, closing, 0.0)  # the last visit: back or none
        return np.add.reduceat(step, start)

    def strand(self, s: int) -> tuple[NDArray[np.int32], NDArray[np.bool_]]:
        """Tiles visited by strand ``s`` and whether it is on top at each."""
        a, b = self.strand_offsets[s], self.strand_offsets[s + 1]
        return self.strand_visits[a:b], self.visit_over[a:b]


def tile_ring_ids(weave: Weave) -> tuple[NDArray[np.int32], NDArray[np.int64]]:
    """Vertex ids of the outline of every tile of a snub weave, counter-clockwise: the octagon
    (p2, p3, p4, p0, p1, q3, q4, q0) of two pentagons p, q glued along their middle edge
    p1 -> p2 (so entries 0 and 4 are the middle edge's ends), or the lone boundary pentagon
    (p2, p3, p4, p0, p1). Returns (ids, ring offsets)."""
    mesh = weave.mesh
    faces = mesh.dense_faces()
    sizes = np.diff(weave.tile_offsets)
    first = weave.tile_faces[weave.tile_offsets[:-1]]
    second = weave.tile_faces[np.minimum(weave.tile_offsets[:-1] + 1, len(weave.tile_faces) - 1)]
    p, q = faces[first], faces[second]
    # p = (p0 .. p4) with middle edge p1 -> p2; q runs it the other way: q1 = p2, q2 = p1
    octagon = np.column_stack([p[:, 2], p[:, 3], p[:, 4], p[:, 0], p[:, 1],
                               q[:, 3], q[:, 4], q[:, 0]])
    lone = sizes == 1
    counts = np.where(lone, 5, 8)
    offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    take = np.ones((len(first), 8), dtype=bool)
    take[lone, 5:] = False
    ids = octagon[take]
    return ids, offsets


