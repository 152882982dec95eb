"""Curves through the levels of the snub scheme (paper section 4): following, inner curves, report.

Every edge of level t is replaced by a Z-triplet in each later step, so it becomes a curve of
3^(t'-t) edges at level t'. On the boundary that curve is the Lindenmayer system of
``analysis.lsystem`` (:func:`boundary_lsystem_error` checks it). Inside, smoothing moves the
vertices; :func:`inner_curves` measures what that does to the lengths (the paper's open
question). :func:`fractal_report` gathers both with the box-counting dimensions of
``analysis.boxcount``.

Curves are followed through the snub numbering (``subdivision.snub``): the Z vertices of parent
edge e are ``V + 2e`` (near u) and ``V + 2e + 1`` (near w), its Z edges ``3e + part``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh, outer_vertices
from ..subdivision import Level
from ..subdivision.snub import FIRST, LAST, MIDDLE, SPOKE
from .boxcount import boundary_segments, box_counting, mesh_segments
from .lsystem import ALPHA, AXIOM, DIMENSION, RULE, SCALE, alpha_from_z_triplet, lsystem_curve


# -- following curves through the levels ---------------------------------------------------

def _check_snub(level: Level, parent: Mesh) -> None:
    if level.parent_edge is None or level.edge_part is None:
        raise ValueError("curves need levels with edge provenance (a subdivided hierarchy)")
    n_e = parent.topology.n_edges
    parts = level.edge_part[:3 * n_e]
    if len(level.edge_part) < 3 * n_e or (parts[1::3] != MIDDLE).any():
        raise ValueError("curves follow the snub numbering (edge 3e + part); "
                         "this hierarchy is not a snub subdivision")


def follow_curves(hierarchy, level: int, start_vertices, edge_ids, to_level: int | None = None):
    """Vertex and edge ids of the curves grown from edges of ``level``, at every later level.

    Parameters
    ----------
    hierarchy : sequence of Level (a snub subdivision)
    level : the level t the curves start at
    start_vertices : (n,) int, the end each curve starts from (an endpoint of its edge)
    edge_ids : (n,) int, the level-t edges
    to_level : last level (default: the last of ``hierarchy``)

    Returns
    -------
    list over levels t..to_level of (vertices (n, m + 1), edges (n, m)), m = 3**(t' - t),
    both in order along each curve.
    """
    to_level = len(hierarchy) - 1 if to_level is None else to_level
    edge_ids = np.asarray(edge_ids, dtype=np.int64).reshape(-1, 1)
    starts = np.asarray(start_vertices, dtype=np.int64).reshape(-1, 1)
    edges = hierarchy[level].mesh.topology.edges
    ends_of = edges[edge_ids[:, 0]]
    if not ((ends_of[:, 0] == starts[:, 0]) | (ends_of[:, 1] == starts[:, 0])).all():
        raise ValueError("every start vertex must be an end of its edge")
    ends = np.where(edges[edge_ids[:, 0], 0] == starts[:, 0], edges[edge_ids[:, 0], 1],
                    edges[edge_ids[:, 0], 0])
    verts = np.column_stack([starts[:, 0], ends])
    out = [(verts, edge_ids)]
    for t in range(level, to_level):
        parent = hierarchy[t].mesh
        _check_snub(hierarchy[t + 1], parent)
        n_v = parent.n_vertices
        e = out[-1][1]
        a = out[-1][0][:, :-1]
        forward = parent.topology.edges[e, 0] == a      # walking u -> w
        z_near_a = n_v + 2 * e + np.where(forward, 0, 1)
        z_near_b = n_v + 2 * e + np.where(forward, 1, 0)
        n, m = e.shape
        new_v = np.empty((n, 3 * m + 1), dtype=np.int64)
        new_v[:, 0::3] = out[-1][0]
        new_v[:, 1::3] = z_near_a
        new_v[:, 2::3] = z_near_b
        new_e = np.empty((n, 3 * m), dtype=np.int64)
        new_e[:, 0::3] = 3 * e + np.where(forward, FIRST, LAST)
        new_e[:, 1::3] = 3 * e + MIDDLE
        new_e[:, 2::3] = 3 * e + np.where(forward, LAST, FIRST)
        out.append((new_v, new_e))
    return out


def curve_points(mesh: Mesh, vertices: NDArray[np.int64]) -> NDArray[np.float64]:
    """(n, m + 1, 2) coordinates of curves given as (n, m + 1) vertex ids."""
    return np.take(mesh.vertices, vertices, axis=0)


def boundary_lsystem_error(hierarchy, chirality: str = "left") -> list[float]:
    """Largest distance, per level, between the boundary curves and the L-system curves.

    Every boundary edge of level 0 is followed to each level t and compared point by point
    with the L-system of level t drawn between the edge's ends (in its face's direction).
    Zero up to rounding means the level-t boundary *is* the L-system curve.
    """
    mesh0 = hierarchy[0].mesh
    topo = mesh0.topology
    lone = topo.edge_half_edges[topo.boundary_edges].max(axis=1)  # the half-edge with a face
    a = mesh0.face_indices[lone]
    e = topo.half_edge_edge[lone]
    curves = follow_curves(hierarchy, 0, a, e)
    errors = []
    for t, (verts, _) in enumerate(curves):
        pts = curve_points(hierarchy[t].mesh, verts)
        ref = lsystem_curve(t, (0.0, 0.0), (1.0, 0.0), chirality)
        p0, p1 = pts[:, :1, :], pts[:, -1:, :]
        chord = (p1 - p0)[..., 0] + 1j * (p1 - p0)[..., 1]                  # (n, 1)
        expected = p0[..., 0] + 1j * p0[..., 1] + chord * (ref[:, 0] + 1j * ref[:, 1])
        got = pts[..., 0] + 1j * pts[..., 1]
        errors.append(float(np.abs(got - expected).max()) if got.size else 0.0)
    return errors


# -- inner curves ------------------------------------------------------------------------

CURVE_KINDS = ("boundary", "outer-outer", "outer-inner", "inner-inner")


def ancestors(hierarchy, level: int) -> list[NDArray[np.int64]]:
    """For every later level, the level-``level`` edge each edge descends from (-1: born later)."""
    n_e = hierarchy[level].mesh.topology.n_edges
    out = [np.arange(n_e, dtype=np.int64)]
    for t in range(level + 1, len(hierarchy)):
        lv = hierarchy[t]
        _check_snub(lv, hierarchy[t - 1].mesh)
        parent = lv.parent_edge.astype(np.int64)
        inherited = lv.edge_part != SPOKE
        out.append(np.where(inherited, out[-1][np.where(inherited, parent, 0)], -1))
    return out


def edge_kinds(mesh: Mesh) -> NDArray[np.int8]:
    """(E,) index into CURVE_KINDS: boundary edge, or inner edge by its ends' outerness."""
    outer = outer_vertices(mesh)
    e = mesh.topology.edges
    n_outer = outer[e[:, 0]].astype(np.int8) + outer[e[:, 1]]
    kind = np.select([n_outer == 2, n_outer == 1], [1, 2], 3).astype(np.int8)
    kind[mesh.topology.boundary_edges] = 0
    return kind


def curve_lengths(hierarchy, level: int) -> NDArray[np.float64]:
    """(E_t, T - t + 1) length of the curve grown from every level-t edge, at levels t..T."""
    anc = ancestors(hierarchy, level)
    n_e = len(anc[0])
    cols = []
    for t, a in zip(range(level, len(hierarchy)), anc):
        mesh = hierarchy[t].mesh
        e = mesh.topology.edges
        length = np.hypot(*(mesh.vertices[e[:, 1]] - mesh.vertices[e[:, 0]]).T)
        keep = a >= 0
        cols.append(np.bincount(a[keep], weights=length[keep], minlength=n_e))
    return np.column_stack(cols)


def chord_lengths(hierarchy, level: int) -> NDArray[np.float64]:
    """(E_t, T - t + 1) distance between the two ends of every curve, at levels t..T."""
    e = hierarchy[level].mesh.topology.edges
    cols = [np.hypot(*(hierarchy[t].mesh.vertices[e[:, 1]]
                       - hierarchy[t].mesh.vertices[e[:, 0]]).T)
            for t in range(level, len(hierarchy))]
    return np.column_stack(cols)


def inner_curves(hierarchy, level: int = 1) -> list[dict]:
    """Lengths of the curves born as one edge at ``level``, by kind, at every later level.

    One row per (kind, level t'): the number of curves, their edges each (3^(t'-t)), total
    and mean length, mean chord (end-to-end distance), and growth factors L(t')/L(t'-1):
    of the total and the min / median / max over curves. The boundary grows by exactly
    3/sqrt(7) = 1.1339 per level; the paper asks what the inner curves do.
    ``implied_dimension`` = log 3 / log(3 / growth) is the dimension that growth would give
    if it held at every scale.
    """
    if not 0 <= level < len(hierarchy):
        raise ValueError(f"level must be 0..{len(hierarchy) - 1}, got {level}")
    lengths = curve_lengths(hierarchy, level)
    chords = chord_lengths(hierarchy, level)
    kinds = edge_kinds(hierarchy[level].mesh)
    rows = []
    for k, name in enumerate(CURVE_KINDS):
        sel = kinds == k
        if not sel.any():
            continue
        lk, ck = lengths[sel], chords[sel]
        for j in range(lk.shape[1]):
            row = {"kind": name, "born": level, "level": level + j, "curves": int(sel.sum()),
                   "edges_each": 3 ** j, "total_length": float(lk[:, j].sum()),
                   "mean_length": float(lk[:, j].mean()), "mean_chord": float(ck[:, j].mean())}
            if j:
                g = lk[:, j] / lk[:, j - 1]
                growth = float(lk[:, j].sum() / lk[:, j - 1].sum())
                row.update(growth=growth, implied_dimension=implied_dimension(growth),
                           growth_min=float(g.min()), growth_median=float(np.median(g)),
                           growth_max=float(g.max()))
            rows.append(row)
    return rows


def growth_monotonicity(hierarchy, level: int) -> list[dict]:
    """Whether the growth of the curves born at ``level`` changes monotonically, by kind.

    For every curve (one per level-t edge, see :func:`curve_lengths`) the growth factors
    g(t') = L(t') / L(t' - 1) for t' = t + 1 .. T form a sequence; it is *rising* when every
    step is >= the one before, *falling* when every step is <=, *constant* when both (the
    boundary: 3/sqrt 7 every step), each up to a relative 1e-9 for rounding. One row per
    kind: the total growth per level (sum of lengths, as in :func:`inner_curves`), whether
    that aggregate sequence rises, and how many single curves are constant, rise, fall, or do
    neither (turn).
    """
    tol = 1e-9
    lengths = curve_lengths(hierarchy, level)
    kinds = edge_kinds(hierarchy[level].mesh)
    rows = []
    for k, name in enumerate(CURVE_KINDS):
        sel = kinds == k
        if not sel.any() or lengths.shape[1] < 3:
            continue
        lk = lengths[sel]
        total = lk.sum(axis=0)
        aggregate = total[1:] / total[:-1]
        g = lk[:, 1:] / lk[:, :-1]
        step = np.diff(g, axis=1)
        rising = (step >= -tol).all(axis=1)
        falling = (step <= tol).all(axis=1)
        rows.append({"kind": name, "born": level, "levels": [level + 1, len(hierarchy) - 1],
                     "curves": int(sel.sum()), "growth": [float(x) for x in aggregate],
                     "aggregate_rising": bool((np.diff(aggregate) >= -tol).all()),
                     "constant": int((rising & falling).sum()),
                     "rising": int((rising & ~falling).sum()),
                     "falling": int((falling & ~rising).sum()),
                     "turning": int((~rising & ~falling).sum()),
                     "growth_min": [float(x) for x in g.min(axis=0)],
                     "growth_max": [float(x) for x in g.max(axis=0)]})
    return rows


def implied_dimension(growth: float) -> float | None:
    """log 3 / log(3 / g): the dimension of a curve whose 3x more edges make it g x longer
    each step (for the boundary, g = 3/sqrt 7 gives log 3 / log sqrt 7)."""
    return math.log(3.0) / math.log(3.0 / growth) if 0 < growth < 3 else None


def default_inner_curve(hierarchy, level: int = 1) -> int:
    """A representative inner curve: the longest inner edge of ``level`` with an outer end
    (for a single pentagon, a centre-to-boundary curve)."""
    mesh = hierarchy[level].mesh
    kinds = edge_kinds(mesh)
    e = mesh.topology.edges
    length = np.hypot(*(mesh.vertices[e[:, 1]] - mesh.vertices[e[:, 0]]).T)
    for k in (2, 3, 1):
        if (kinds == k).any():
            return int(np.flatnonzero(kinds == k)[np.argmax(length[kinds == k])])
    raise ValueError(f"level {level} has no inner edge to follow")


def curve_box_counting(hierarchy, level: int, edge: int) -> dict:
    """Box-counting dimension of the curve grown from edge ``edge`` of ``level``."""
    n_e = hierarchy[level].mesh.topology.n_edges
    if not 0 <= edge < n_e:
        raise ValueError(f"level {level} has edges 0..{n_e - 1}, got {edge}")
    anc = ancestors(hierarchy, level)[-1]
    return box_counting(mesh_segments(hierarchy[-1].mesh, np.flatnonzero(anc == edge)))


def fractal_report(hierarchy, chirality: str = "left", curve: tuple[int, int] | None = None,
                   born=(1, 2)) -> dict:
    """Everything ``weave-cut fractal`` prints: alpha, L-system check, dimensions, curves.

    ``born`` lists the levels whose edges start inner-curve rows (the boundary rows come from
    the first only: they are the same curves cut finer).
    """
    born = (born,) if isinstance(born, int) else tuple(born)
    last = len(hierarchy) - 1
    report = {
        "alpha_rad": ALPHA, "alpha_deg": math.degrees(ALPHA),
        "alpha_from_z_triplet_deg": math.degrees(alpha_from_z_triplet()),
        "lsystem": {"axiom": AXIOM, "rule": f"F -> {RULE}",
                    "symbols": {"v": "rot(+alpha)", "^": "rot(-alpha)",
                                "+": "rot(+pi/3)", "-": "rot(-pi/3)"},
                    "scale": SCALE},
        "analytic_dimension": DIMENSION,
        "levels": last,
        "boundary_lsystem_max_error": boundary_lsystem_error(hierarchy, chirality),
    }
    mesh = hierarchy[-1].mesh
    try:
        report["boundary_box_counting"] = box_counting(boundary_segments(mesh))
    except ValueError as exc:
        report["boundary_box_counting"] = {"skipped": str(exc)}
    first = min(born) if born else 1
    chosen = curve is not None
    if not chosen and 0 <= first < last:
        try:
            curve = (first, default_inner_curve(hierarchy, first))
        except ValueError:
            curve = None
    if curve is not None:
        try:
            counted = curve_box_counting(hierarchy, *curve)
        except ValueError as exc:
            if chosen:
                raise
            counted = {"skipped": str(exc)}
        report["inner_curve"] = {"level": curve[0], "edge": curve[1], **counted}
    rows = []
    for k, b in enumerate(sorted(set(born))):
        if 0 <= b < last:
            rows += [r for r in inner_curves(hierarchy, b) if k == 0 or r["kind"] != "boundary"]
    if rows:
        report["inner_curves"] = rows
        report["growth_monotonicity"] = [
            m for b in sorted(set(born)) if 0 <= b < last
            for m in growth_monotonicity(hierarchy, b) if m["kind"] != "boundary"]
    return report
