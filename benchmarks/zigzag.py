"""The strands of a snub weave from the parent mesh alone, as a plain Python walk: the
independent oracle of tests/weave/test_snub_weave.py and the peer of bench_weave.py. Needs
nothing but weave-cut's Mesh (no pytest), so the benchmark runs anywhere weave-cut does."""

from __future__ import annotations


def zigzag_strands(parent):
    """Strands from the parent mesh alone: walk edge, next edge in its face, previous edge in
    the face across, ... (a plain loop, sharing no code with the weave). Every parent edge is a
    tile; returns {frozenset(over edges): frozenset(all edges)}."""
    topo = parent.topology
    nxt, prv, twin, edge = (parent.next_half_edge.tolist(), parent.prev_half_edge.tolist(),
                            topo.twin.tolist(), topo.half_edge_edge.tolist())

    def walk(a):
        over, every, seen = [], [], set()
        cur = a
        while cur >= 0 and cur not in seen:
            seen.add(cur)
            over.append(edge[cur])
            b = nxt[cur]
            every.append(edge[b])
            t = twin[b]
            if t < 0:
                break
            c = prv[t]
            cur = twin[c]
            if cur < 0:
                over.append(edge[c])
        return over, every

    strands = {}
    for a in range(parent.n_corners):
        if twin[a] >= 0 and a > twin[a]:
            continue  # each tile once: from one of its half-edges
        o1, e1 = walk(a)
        o2, e2 = walk(twin[a]) if twin[a] >= 0 else ([], [])
        over = frozenset(o1 + o2)
        strands.setdefault(over, frozenset(o1 + o2 + e1 + e2))
    return strands
