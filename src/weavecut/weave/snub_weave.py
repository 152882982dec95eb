"""The weave of a pentagon snub level (paper section 5): octagons, strands, crossings, lineage.

Tiles: the two pentagons that share a Z middle edge glue into an octagon; a pentagon whose
middle edge is on the boundary is a tile of its own. Every pentagon has one tip (local vertex 4);
it pokes into the notch at one end of another tile U's middle edge. The strand passes under U
and continues in the tile whose pentagon has its tip at the other end of U's middle edge
("partner"), leaving that tile through its other pentagon ("sibling"). So a directed walk is a
successor map on pentagons, ``succ(p) = sibling(partner(p))``, ordered by pointer jumping.

Everything is read off the level's mesh: middle edges are local edge 1 of every pentagon, tips
local vertex 4 (the snub step's numbering), so no parent data is needed. Tiles are numbered by
middle edge and list their pentagons in increasing order (drawings and puzzle guides read a
tile's first face). Of a strand's two walking directions the one with more pentagons is
kept, so a strand whose own lone tile is at one end only is walked from there.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from ..errors import MeshError
from ..graphs import components
from ..mesh import Mesh
from ..subdivision.hierarchy import Level
from .model import Weave
from .paths import rank_paths


def _graph_components(n: int, a: NDArray, b: NDArray) -> NDArray[np.int64]:
    """Connected-component label of n nodes joined by edges (a, b), numbered in the order of
    each component's smallest node."""
    return components(n, a, b)[1]


def snub_weave(mesh: Mesh) -> Weave:
    """The weave of a mesh made by a snub step (pentagons in the step's local order)."""
    faces = mesh.dense_faces()
    if faces is None or faces.shape[1] != 5:
        raise MeshError("the snub weave needs a level made by a pentagon snub step (level >= 1)")
    n_p = len(faces)
    topo = mesh.topology
    pent = np.arange(n_p, dtype=np.int64)
    middle_he = 5 * pent + 1
    middle = topo.half_edge_edge[middle_he].astype(np.int64)
    is_middle = np.zeros(topo.n_edges, dtype=bool)
    is_middle[middle] = True
    tile_of_edge = np.cumsum(is_middle) - 1
    tile = tile_of_edge[middle]  # own tile of every pentagon
    n_t = int(is_middle.sum())
    side = topo.half_edge_side[middle_he].astype(np.int64)
    tile_pents = np.full((n_t, 2), -1, dtype=np.int64)
    tile_pents[tile, side] = pent
    if (np.bincount(tile * 2 + side, minlength=2 * n_t) > 1).any():
        raise MeshError("a middle edge is local edge 1 of two pentagons on the same side")
    sibling = tile_pents[tile, 1 - side]

    ends = topo.edges[np.flatnonzero(is_middle)].astype(np.int64)  # (T, 2) middle edge ends
    vertex_tile = np.full(mesh.n_vertices, -1, dtype=np.int64)
    vertex_tile[ends.ravel()] = np.repeat(np.arange(n_t), 2)
    tip = faces[:, 4].astype(np.int64)
    under = vertex_tile[tip]
    if (under < 0).any():
        raise MeshError(f"pentagon {int(np.flatnonzero(under < 0)[0])} has no middle edge at "
                        "its tip: not a snub level")
    tip_owner = np.full(mesh.n_vertices, -1, dtype=np.int64)
    tip_owner[tip] = pent
    other_end = ends[under].sum(axis=1) - tip
    partner = tip_owner[other_end]
    succ = np.where(partner >= 0, sibling[np.maximum(partner, 0)], -1)

    root, rank, on_cycle = rank_paths(succ)
    # strands: tiles joined through their crossings; keep one walking direction per strand
    linked = partner >= 0
    strand_of_tile = _graph_components(n_t, tile[linked], tile[partner[linked]])
    length = np.bincount(root, minlength=n_p)
    strand = strand_of_tile[tile[root]]
    # per strand, the direction with more pentagons, then the smaller first pentagon
    heads = np.flatnonzero(root == pent)
    order = np.lexsort((heads, -length[heads], strand[heads]))
    first_head = order[np.r_[True, strand[heads][order][1:] != strand[heads][order][:-1]]]
    chosen_root = np.zeros(n_p, dtype=bool)
    chosen_root[heads[first_head]] = True
    keep = chosen_root[root]

    p = pent[keep]
    s_root, s_rank = root[keep], rank[keep]
    last = rank[keep] == length[s_root] - 1
    closed = on_cycle[keep]
    # visits: (T(p) over, U(p) under) per pentagon, plus the ends of open strands
    pre = keep & (root == pent) & ~on_cycle & (sibling >= 0)
    pre &= np.where(sibling >= 0, partner[np.maximum(sibling, 0)] < 0, False)
    pre_p = pent[pre]
    post_p = p[last & ~closed & (partner[p] >= 0)]
    strand_root = np.concatenate([s_root, s_root, root[pre_p], root[post_p]])
    position = np.concatenate([2 * s_rank + 1, 2 * s_rank + 2, np.zeros(len(pre_p), np.int64),
                               2 * rank[post_p] + 3])
    visit_tile = np.concatenate([tile[p], under[p], under[sibling[pre_p]],
                                 tile[partner[post_p]]])
    over = np.concatenate([np.ones(len(p), bool), np.zeros(len(p), bool),
                           np.zeros(len(pre_p), bool), np.ones(len(post_p), bool)])
    # strands numbered by their smallest tile, visits in walking order
    strand_key = strand[strand_root]
    idx = np.lexsort((position, strand_key))
    keys = strand_key[idx]
    starts = np.flatnonzero(np.r_[True, keys[1:] != keys[:-1]])
    offsets = np.r_[starts, len(idx)].astype(np.int64)
    strand_closed = on_cycle[strand_root[idx][starts]]

    tile_offsets = np.zeros(n_t + 1, dtype=np.int64)
    np.cumsum(np.bincount(tile, minlength=n_t), out=tile_offsets[1:])
    tile_faces = np.argsort(tile, kind="stable").astype(np.int32)
    return Weave(mesh, tile_offsets, tile_faces, offsets, visit_tile[idx].astype(np.int32),
                 over[idx], strand_closed)


def snub_weaves(hierarchy: tuple[Level, ...]) -> list[Weave]:
    """The weave of every level >= 1, each with the lineage to the level before."""
    weaves: list[Weave] = []
    for level in hierarchy[1:]:
        weave = snub_weave(level.mesh)
        if weaves:
            weave = replace(weave, parent_strand=lineage(weaves[-1], weave, level.parent_face))
        weaves.append(weave)
    return weaves


def lineage(parent: Weave, child: Weave, parent_face: NDArray) -> NDArray[np.int32]:
    """(S_child,) the parent strand each child strand follows (-1: none).

    Most child octagons straddle two parent tiles, so a vote over parent octagons is ambiguous;
    instead every pentagon of a child strand's own tiles votes for the parent strands that own
    or pass under the parent tile its parent face lies in, and the most votes win (ties: the
    smaller parent strand).
    """
    own = child.visit_over
    v_strand = child.visit_strand[own]
    v_tile = child.strand_visits[own]
    counts = np.diff(child.tile_offsets)[v_tile]
    rows = np.repeat(v_strand, counts)
    starts = child.tile_offsets[v_tile]
    within = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    faces = child.tile_faces[np.repeat(starts, counts) + within]
    ptile = parent.face_tile[parent_face[faces]]
    cand = np.concatenate([parent.tile_over[ptile], parent.tile_under[ptile]])
    rows = np.concatenate([rows, rows])
    ok = cand >= 0
    key = rows[ok].astype(np.int64) * (parent.n_strands + 1) + cand[ok]
    uniq, votes = np.unique(key, return_counts=True)
    c_strand, p_strand = np.divmod(uniq, parent.n_strands + 1)
    order = np.lexsort((p_strand, -votes, c_strand))
    best = order[np.r_[True, c_strand[order][1:] != c_strand[order][:-1]]]
    out = np.full(child.n_strands, -1, dtype=np.int32)
    out[c_strand[best]] = p_strand[best]
    return out
