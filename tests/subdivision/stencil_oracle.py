"""An independent reference for the classic schemes' positions: the published stencils written
out per vertex, per edge and per face with plain Python loops over tuples.

Nothing here is shared with ``weavecut.subdivision``: adjacency comes from the face lists
(a dict of directed edges), rings are ordered by angle around their vertex, and every weight is
written out from the paper that defines it (cited at each function), not from the code's
docstring. The values are keyed by what they belong to (a vertex id, an edge as the sorted pair
of its ends, a face id, a corner (face, position)), so a test maps them onto the code's
numbering by the documented layout alone.
"""

from __future__ import annotations

import math


class Adjacency:
    """Neighbours, faces, outer edges and outer vertices of a 2-D polygon mesh (CCW faces)."""

    def __init__(self, vertices, faces):
        self.p = [(float(x), float(y)) for x, y in vertices]
        self.faces = [tuple(int(i) for i in f) for f in faces]
        self.face_of = {}                      # directed edge (a, b) -> face
        for fid, f in enumerate(self.faces):
            for i, a in enumerate(f):
                self.face_of[(a, f[(i + 1) % len(f)])] = fid
        self.nbrs = {v: set() for v in range(len(self.p))}
        for a, b in self.face_of:
            self.nbrs[a].add(b)
            self.nbrs[b].add(a)
        self.edges = sorted({(min(a, b), max(a, b)) for a, b in self.face_of})
        self.outer_edges = [(a, b) for a, b in self.face_of if (b, a) not in self.face_of]
        self.outer = {v for e in self.outer_edges for v in e}
        self.outer |= {v for v in self.nbrs if not self.nbrs[v]}

    def valence(self, v):
        return len(self.nbrs[v])

    def is_outer_edge(self, u, w):
        return (u, w) not in self.face_of or (w, u) not in self.face_of

    def outer_nbrs(self, v):
        """The ends of v's outer edges other than v (two on a manifold boundary)."""
        return [b if a == v else a for a, b in self.outer_edges if v in (a, b)]

    def opposite(self, u, w):
        """The third corner of the triangle on the left of u -> w (None: no face there)."""
        f = self.face_of.get((u, w))
        if f is None:
            return None
        return next(x for x in self.faces[f] if x not in (u, w))

    def ring_from(self, v, start):
        """v's neighbours counter-clockwise by angle, beginning with ``start``."""
        px, py = self.p[v]
        a0 = math.atan2(self.p[start][1] - py, self.p[start][0] - px)
        turn = lambda n: (math.atan2(self.p[n][1] - py, self.p[n][0] - px) - a0) % (2 * math.pi)  # noqa: E731
        return sorted(self.nbrs[v], key=lambda n: (n != start, turn(n)))

    def boundary_next(self, v):
        """The next outer vertex after v along the boundary (the face on the left)."""
        return next(b for a, b in self.outer_edges if a == v)

    def boundary_prev(self, v):
        return next(a for a, b in self.outer_edges if b == v)

    def centre(self, f):
        pts = [self.p[i] for i in self.faces[f]]
        return (sum(x for x, _ in pts) / len(pts), sum(y for _, y in pts) / len(pts))


def comb(*terms):
    """sum of w * point over (w, point) pairs."""
    return (sum(w * p[0] for w, p in terms), sum(w * p[1] for w, p in terms))


def mid(a, b):
    return comb((0.5, a), (0.5, b))


def loop_beta(n):
    """C. Loop, "Smooth subdivision surfaces based on triangles" (MS thesis, Utah 1987), p. 55:
    beta_n = (5/8 - (3/8 + 1/4 cos(2 pi / n))^2) / n. (Warren's simpler 3/(8n) differs from it
    at every valence but 3 and 6.)"""
    return (0.625 - (0.375 + 0.25 * math.cos(2 * math.pi / n)) ** 2) / n


def warren_beta(n):
    """J. Warren, "Subdivision methods for geometric design" (1995): 3/16 at n = 3, else 3/(8n)."""
    return 3 / 16 if n == 3 else 3 / (8 * n)


def cubic_bspline_vertex(adj, v):
    """Hoppe et al. 1994 / DeRose et al. 1998 crease rule: 3/4 v + 1/8 (its two outer
    neighbours); a vertex with other than two outer neighbours (a non-manifold end) stays."""
    ends = adj.outer_nbrs(v)
    if len(ends) != 2:
        return adj.p[v]
    return comb((0.75, adj.p[v]), (0.125, adj.p[ends[0]]), (0.125, adj.p[ends[1]]))


def per_vertex(adj, inner, outer=cubic_bspline_vertex):
    """{v: outer(adj, v)} for outer vertices, {v: inner(v, valence)} for inner ones."""
    return {v: outer(adj, v) if v in adj.outer else inner(v, adj.valence(v))
            for v in range(len(adj.p))}


def loop(adj, beta=loop_beta):
    """(even, odd): new positions of the old vertices and one point per edge (Loop 1987;
    boundary: Hoppe et al. 1994)."""
    even = per_vertex(adj, lambda v, n: comb((1 - n * beta(n), adj.p[v]),
                                             *[(beta(n), adj.p[u]) for u in adj.nbrs[v]]))
    odd = {}
    for u, w in adj.edges:
        if adj.is_outer_edge(u, w):
            odd[(u, w)] = mid(adj.p[u], adj.p[w])
        else:
            c, d = adj.opposite(u, w), adj.opposite(w, u)
            odd[(u, w)] = comb((3 / 8, adj.p[u]), (3 / 8, adj.p[w]), (1 / 8, adj.p[c]),
                               (1 / 8, adj.p[d]))
    return even, odd


def zorin_weights(k):
    """Zorin, Schroeder, Sweldens 1996, sec. 4 ("extraordinary vertices"): the weights of the
    ring n_0 .. n_{k-1} of an extraordinary vertex, the vertex itself weighing 3/4."""
    if k == 3:
        return [5 / 12, -1 / 12, -1 / 12]
    if k == 4:
        return [3 / 8, 0.0, -1 / 8, 0.0]
    return [(1 / 4 + math.cos(2 * math.pi * j / k) + 1 / 2 * math.cos(4 * math.pi * j / k)) / k
            for j in range(k)]


def butterfly(adj):
    """One point per edge of the modified butterfly (Zorin et al. 1996), with the boundary
    handling the code documents: the 4-point rule on outer edges (Dyn, Levin, Gregory 1987),
    the ring stencil of the inner end(s) (an inner regular end counting as k = 6 when the other
    end is outer), the Loop edge rule when both ends are outer."""
    out = {}
    for u, w in adj.edges:
        pu, pw = adj.p[u], adj.p[w]
        if adj.is_outer_edge(u, w):
            a, b = (u, w) if (u, w) in adj.face_of else (w, u)
            p, q = adj.boundary_prev(a), adj.boundary_next(b)
            out[(u, w)] = comb((-1 / 16, adj.p[p]), (9 / 16, adj.p[a]), (9 / 16, adj.p[b]),
                               (-1 / 16, adj.p[q]))
            continue
        inner = [x for x in (u, w) if x not in adj.outer]
        regular = [x for x in inner if adj.valence(x) == 6]
        if len(regular) == 2:
            c, d = adj.opposite(u, w), adj.opposite(w, u)
            wings = [adj.opposite(u, c), adj.opposite(c, w), adj.opposite(d, u),
                     adj.opposite(w, d)]
            out[(u, w)] = comb((1 / 2, pu), (1 / 2, pw), (1 / 8, adj.p[c]), (1 / 8, adj.p[d]),
                               *[(-1 / 16, adj.p[x]) for x in wings])
            continue
        ends = [x for x in inner if adj.valence(x) != 6] or inner
        if not ends:
            c, d = adj.opposite(u, w), adj.opposite(w, u)
            out[(u, w)] = comb((3 / 8, pu), (3 / 8, pw), (1 / 8, adj.p[c]), (1 / 8, adj.p[d]))
            continue
        pts = []
        for x in ends:
            ring = adj.ring_from(x, w if x == u else u)
            s = zorin_weights(len(ring))
            pts.append(comb((3 / 4, adj.p[x]), *[(s[j], adj.p[n]) for j, n in enumerate(ring)]))
        out[(u, w)] = comb(*[(1 / len(pts), q) for q in pts])
    return out


def sqrt3(adj):
    """(even, centres) of Kobbelt's sqrt(3) (SIGGRAPH 2000, eq. 6): an inner vertex of valence
    n moves to (1 - a_n) p + a_n / n sum(neighbours), a_n = (4 - 2 cos(2 pi / n)) / 9; outer
    vertices stay (the code's documented boundary); a face gets its vertex mean."""
    def relaxed(v, n):
        a = (4 - 2 * math.cos(2 * math.pi / n)) / 9
        return comb((1 - a, adj.p[v]), *[(a / n, adj.p[u]) for u in adj.nbrs[v]])

    even = per_vertex(adj, relaxed, outer=lambda adj, v: adj.p[v])
    return even, {f: adj.centre(f) for f in range(len(adj.faces))}


def catmull_clark(adj):
    """(vertex, edge, face) points of Catmull and Clark 1978 with the crease boundary (DeRose
    et al. 1998): face point the vertex mean, inner edge point the mean of its ends and its two
    face points, inner vertex (Q + 2R + (n - 3) S) / n, outer edge its midpoint, outer vertex
    the cubic B-spline rule."""
    face = {f: adj.centre(f) for f in range(len(adj.faces))}
    edge = {}
    for u, w in adj.edges:
        if adj.is_outer_edge(u, w):
            edge[(u, w)] = mid(adj.p[u], adj.p[w])
        else:
            cf, cg = face[adj.face_of[(u, w)]], face[adj.face_of[(w, u)]]
            edge[(u, w)] = comb((1 / 4, adj.p[u]), (1 / 4, adj.p[w]), (1 / 4, cf), (1 / 4, cg))
    def moved(v, n):
        fs = [f for (a, _), f in adj.face_of.items() if a == v]
        q = comb(*[(1 / len(fs), face[f]) for f in fs])
        r = comb(*[(1 / n, mid(adj.p[v], adj.p[u])) for u in adj.nbrs[v]])
        return comb((1 / n, q), (2 / n, r), ((n - 3) / n, adj.p[v]))

    return per_vertex(adj, moved), edge, face


def doo_sabin(adj):
    """{(face, i): point} of Doo and Sabin 1978, eq. (2): corner i of an n-gon goes to
    sum_j a_ij v_j, a_ii = (n + 5) / (4n), a_ij = (3 + 2 cos(2 pi (i - j) / n)) / (4n)."""
    out = {}
    for fid, f in enumerate(adj.faces):
        n = len(f)
        for i in range(n):
            terms = []
            for j in range(n):
                a = (n + 5) / (4 * n) if i == j else (3 + 2 * math.cos(2 * math.pi * (i - j) / n)) / (4 * n)
                terms.append((a, adj.p[f[j]]))
            out[(fid, i)] = comb(*terms)
    return out


def akleman(adj, t):
    """{(face, i): copy} of Akleman et al. 2004 as the paper states it: the midpoint of the edge
    leaving corner i moved by t towards the face's vertex mean."""
    out = {}
    for fid, f in enumerate(adj.faces):
        c = adj.centre(fid)
        for i, a in enumerate(f):
            m = mid(adj.p[a], adj.p[f[(i + 1) % len(f)]])
            out[(fid, i)] = comb((1 - t, m), (t, c))
    return out
