"""Modified butterfly subdivision (Zorin, Schroeder, Sweldens 1996): interpolating 1-to-4 split.

Old vertices keep their positions; every edge gets one new point. Stencils from D. Zorin,
P. Schroeder, W. Sweldens, "Interpolating subdivision for meshes with arbitrary topology"
(SIGGRAPH 1996), with the tension parameter w = 0:

- inner edge (a, b), both ends inner of valence 6: the 8-point butterfly
  1/2 (a + b) + 1/8 (c + d) - 1/16 (the four wing vertices);
- inner edge with an inner end of valence k != 6: that end's stencil 3/4 a + sum_j s_j n_j over
  its ring n_0 = b, n_1, ... counter-clockwise, s = (5/12, -1/12, -1/12) for k = 3,
  (3/8, 0, -1/8, 0) for k = 4, and s_j = (1/4 + cos(2 pi j/k) + cos(4 pi j/k)/2)/k for k >= 5;
  when both ends are extraordinary, the mean of the two stencils;
- outer edge: the 4-point curve rule (Dyn, Levin, Gregory 1987)
  -1/16 p + 9/16 a + 9/16 b - 1/16 q along the boundary.

Simplified against Zorin's boundary rules (his thesis, 1998): an inner edge with an outer end
and a regular inner end uses the inner end's k = 6 ring stencil; an inner edge whose two ends
are both outer gets the Loop edge rule 3/8 (a + b) + 1/8 (c + d).

Numbering and counts are those of :mod:`weavecut.subdivision.loop` (the same 1-to-4 split):
V' = V + E, E' = 2E + H, F' = 4F.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ._common import (
    boundary_predecessor,
    boundary_successor,
    is_outer,
    require_degree,
    rotate_ccw,
)
from .hierarchy import Level
from .loop import EDGE_PARTS, counts, split_1_to_4

__all__ = ["EDGE_PARTS", "counts", "step", "edge_points", "ring_weights"]


def step(mesh: Mesh) -> Level:
    """One modified butterfly step on a triangle mesh."""
    require_degree(mesh, 3, "butterfly subdivision")
    vertices = np.empty((mesh.n_vertices + mesh.topology.n_edges, 2))
    vertices[:mesh.n_vertices] = mesh.vertices
    vertices[mesh.n_vertices:] = edge_points(mesh)
    return split_1_to_4(mesh, vertices)


def ring_weights(k: int) -> NDArray[np.float64]:
    """(k,) Zorin's weights s_j for the ring of an extraordinary vertex of valence k.

    Examples
    --------
    >>> ring_weights(4).tolist()
    [0.375, 0.0, -0.125, 0.0]
    """
    if k == 3:
        return np.array([5 / 12, -1 / 12, -1 / 12])
    if k == 4:
        return np.array([3 / 8, 0.0, -1 / 8, 0.0])
    j = np.arange(k)
    return (0.25 + np.cos(2 * np.pi * j / k) + 0.5 * np.cos(4 * np.pi * j / k)) / k


def edge_points(mesh: Mesh) -> NDArray[np.float64]:
    """(E, 2) the new point of every edge."""
    topo = mesh.topology
    v, fi = mesh.vertices, mesh.face_indices
    nxt, prv = mesh.next_half_edge, mesh.prev_half_edge
    e = topo.edges
    he = topo.edge_half_edges
    twin = topo.twin
    inner_edge = (he >= 0).all(axis=1)
    outer_v = is_outer(mesh)
    valence = np.bincount(e.ravel(), minlength=mesh.n_vertices)
    regular = ~outer_v & (valence == 6)
    out = np.empty((topo.n_edges, 2))

    # 8-point butterfly where both ends are regular inner vertices
    full = np.flatnonzero(inner_edge & regular[e[:, 0]] & regular[e[:, 1]])
    h0, h1 = he[full, 0], he[full, 1]
    pts = 0.5 * (np.take(v, e[full, 0], axis=0) + np.take(v, e[full, 1], axis=0))
    pts += 0.125 * (np.take(v, fi[prv[h0]], axis=0) + np.take(v, fi[prv[h1]], axis=0))
    for x in (nxt[h0], prv[h0], nxt[h1], prv[h1]):
        pts -= 0.0625 * np.take(v, fi[prv[twin[x]]], axis=0)
    out[full] = pts

    # outer edges: the 4-point rule along the boundary
    lone = np.flatnonzero(~inner_edge)
    if len(lone):
        h = he[lone].max(axis=1)
        a, b = fi[h], fi[nxt[h]]
        p, q = boundary_predecessor(mesh)[a], boundary_successor(mesh)[b]
        out[lone] = (9 * (v[a] + v[b]) - v[p] - v[q]) / 16

    # the rest: ring stencils of the inner extraordinary ends (or the regular inner end)
    rest = np.flatnonzero(inner_edge)
    rest = rest[~(regular[e[rest, 0]] & regular[e[rest, 1]])]
    if len(rest):
        ends = e[rest]
        usable = ~outer_v[ends] & ~regular[ends]
        only_regular = ~usable.any(axis=1)
        usable[only_regular] = ~outer_v[ends[only_regular]]
        acc = np.zeros((len(rest), 2))
        n_used = usable.sum(axis=1)
        for col in (0, 1):
            sel = np.flatnonzero(usable[:, col])
            start = he[rest[sel], col]  # half-edge leaving this end towards the other
            acc[sel] += _ring_stencil(mesh, start, valence[ends[sel, col]])
        none = n_used == 0
        acc[~none] /= n_used[~none, None]
        if none.any():
            h0, h1 = he[rest[none], 0], he[rest[none], 1]
            ab = np.take(v, ends[none], axis=0).sum(axis=1)
            cd = np.take(v, fi[prv[h0]], axis=0) + np.take(v, fi[prv[h1]], axis=0)
            acc[none] = 0.375 * ab + 0.125 * cd
        out[rest] = acc
    return out


def _ring_stencil(mesh: Mesh, start: NDArray, valence: NDArray) -> NDArray[np.float64]:
    """(n, 2) 3/4 a + sum_j s_j n_j for the half-edges ``start`` = a -> n_0, ring of size k."""
    fi, nxt = mesh.face_indices, mesh.next_half_edge
    rot = rotate_ccw(mesh)
    out = 0.75 * mesh.vertices[fi[start]]
    for k in np.unique(valence).tolist():
        sel = np.flatnonzero(valence == k)
        h = start[sel]
        acc = np.zeros((len(sel), 2))
        for s in ring_weights(k):
            acc += s * mesh.vertices[fi[nxt[h]]]
            h = rot[h]
        out[sel] += acc
    return out
