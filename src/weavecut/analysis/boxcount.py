"""Box-counting dimension of curves given as segments, and the segments to count.

:func:`box_counting` estimates a dimension as the slope of log N(eps) against log 1/eps; the
segments come from a mesh's edges or boundary, from curves of points, or from the L-system
drawn on a mesh's boundary edges (:func:`lsystem_boundary`: deep levels without the mesh).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..numeric import line_fit
from .lsystem import lsystem_curve

def _split_long(a, b, eps):
    """Cut segments into pieces shorter than ``eps`` (vectorised with repeat)."""
    length = np.hypot(*(b - a).T)
    pieces = np.maximum(1, np.ceil(length / (0.999 * eps)).astype(np.int64))
    if (pieces == 1).all():
        return a, b
    seg = np.repeat(np.arange(len(a)), pieces)
    k = np.arange(len(seg)) - np.repeat(np.cumsum(pieces) - pieces, pieces)
    t0 = (k / pieces[seg])[:, None]
    t1 = ((k + 1) / pieces[seg])[:, None]
    d = (b - a)[seg]
    return a[seg] + t0 * d, a[seg] + t1 * d


def box_count(segments: NDArray[np.float64], eps: float, origin=(0.0, 0.0)) -> int:
    """Number of grid boxes of side ``eps`` that the segments (n, 2, 2) meet.

    Exact for the union of segments: a segment shorter than a box meets the boxes of its
    ends and, when it changes both row and column, the one box it passes between them.
    """
    a, b = _split_long(segments[:, 0] - origin, segments[:, 1] - origin, eps)
    ia = np.floor(a / eps).astype(np.int64)
    ib = np.floor(b / eps).astype(np.int64)
    cells = [ia, ib]
    both = (ia[:, 0] != ib[:, 0]) & (ia[:, 1] != ib[:, 1])
    if both.any():
        pa, pb, ca, cb = a[both], b[both], ia[both], ib[both]
        gx = np.maximum(ca[:, 0], cb[:, 0]) * eps
        gy = np.maximum(ca[:, 1], cb[:, 1]) * eps
        tx = (gx - pa[:, 0]) / (pb[:, 0] - pa[:, 0])
        ty = (gy - pa[:, 1]) / (pb[:, 1] - pa[:, 1])
        x_first = (tx < ty)[:, None]
        cells.append(np.where(x_first, np.column_stack([cb[:, 0], ca[:, 1]]),
                              np.column_stack([ca[:, 0], cb[:, 1]])))
    c = np.concatenate(cells)
    c -= c.min(axis=0)
    return int(len(np.unique(c[:, 0] * (int(c[:, 1].max()) + 1) + c[:, 1])))


def box_sizes(segments: NDArray[np.float64], coarsest: float = 1 / 32,
              finest: float = 2.0, per_octave: int = 4) -> NDArray[np.float64]:
    """Box sizes from ``coarsest`` x the curve's extent down to ``finest`` x its mean segment.

    The default range (extent/32 .. 2 mean segments, four sizes per halving) keeps the fit
    inside the scales where the curve is resolved, and away from the coarse end where a
    curve a few boxes wide looks like a line (which pulls the slope towards 1).
    """
    pts = segments.reshape(-1, 2)
    extent = float(np.max(pts.max(axis=0) - pts.min(axis=0)))
    mean = float(np.hypot(*(segments[:, 1] - segments[:, 0]).T).mean())
    hi, lo = coarsest * extent, finest * mean
    if lo >= hi:
        raise ValueError("the curve has too few segments for box counting; use more levels")
    k = np.arange(0, int(np.floor(per_octave * np.log2(hi / lo))) + 1)
    return hi * 2.0 ** (-k / per_octave)


GRID_SHIFT = np.array([0.7548776662466927, 0.5698402909980532])  # Kronecker sequence step


def box_counting(segments: NDArray[np.float64], sizes=None, n_grids: int = 8) -> dict:
    """Box-counting dimension: slope of log N(eps) against log(1/eps), least squares.

    N(eps) is the mean count over ``n_grids`` grids shifted by a low-discrepancy sequence
    of fractions of a box (one grid's count jumps with its alignment).

    Parameters
    ----------
    segments : (n, 2, 2) float64, the curve as segments
    sizes : box sizes (default :func:`box_sizes`)
    n_grids : number of shifted grids averaged per size

    Returns
    -------
    dict with ``sizes``, ``counts`` (mean over grids), ``dimension`` (the slope),
    ``intercept``, ``r2``, ``grids``, ``stderr`` (the slope's standard error from the fit's
    residuals) and ``halves`` (the slopes fitted to the coarser and the finer half of the
    sizes alone: how much the answer depends on the fit range, usually far more than
    ``stderr``, because the counts of a self-similar curve wave with log eps); ``stderr`` is
    None with fewer than three sizes, a half's slope None with fewer than two.
    """
    segments = np.asarray(segments, dtype=np.float64).reshape(-1, 2, 2)
    sizes = box_sizes(segments) if sizes is None else np.asarray(sizes, dtype=float)
    if len(sizes) < 2:  # a slope needs two points
        raise ValueError(f"the curve has too few segments for box counting ({len(sizes)} box "
                         "size between its extent/32 and two segments); use more levels")
    lower = segments.reshape(-1, 2).min(axis=0)
    shifts = (np.arange(1, n_grids + 1)[:, None] * GRID_SHIFT) % 1.0
    counts = []
    for eps in sizes:  # loops over box sizes and grids, not over mesh elements
        counts.append(np.mean([box_count(segments, float(eps), lower - eps * s)
                               for s in shifts]))
    x = np.log(1.0 / sizes)
    y = np.log(np.asarray(counts, dtype=float))
    slope, intercept = line_fit(x, y)
    fit = slope * x + intercept
    ss = float(((y - y.mean()) ** 2).sum())
    r2 = 1.0 - float(((y - fit) ** 2).sum()) / ss if ss > 0 else 1.0
    dof = len(x) - 2
    stderr = (math.sqrt(float(((y - fit) ** 2).sum()) / dof / float(((x - x.mean()) ** 2).sum()))
              if dof > 0 else None)
    half = len(x) // 2
    halves = [line_fit(x[part], y[part])[0] if len(x[part]) > 1 else None
              for part in (slice(0, half + 1), slice(half, None))]
    return {"sizes": [float(s) for s in sizes], "counts": [float(c) for c in counts],
            "dimension": float(slope), "intercept": float(intercept), "r2": r2,
            "grids": n_grids, "stderr": stderr, "halves": halves}


def lsystem_boundary(mesh: Mesh, levels: int, chirality: str = "left") -> NDArray[np.float64]:
    """(n, 2, 2) segments of the L-system curves of ``levels`` on every boundary edge of
    ``mesh`` in its face's direction: the boundary of the snub level ``levels`` (see
    :func:`boundary_lsystem_error`) without building the mesh, so deep levels are cheap."""
    topo = mesh.topology
    lone = topo.edge_half_edges[topo.boundary_edges].max(axis=1)
    a = mesh.vertices[mesh.face_indices[lone]]
    b = mesh.vertices[mesh.face_indices[mesh.next_half_edge[lone]]]
    ref = lsystem_curve(levels, chirality=chirality)
    unit = ref[:, 0] + 1j * ref[:, 1]
    pts = (a[:, 0] + 1j * a[:, 1])[:, None] + ((b - a)[:, 0] + 1j * (b - a)[:, 1])[:, None] * unit[None]
    return curve_segments(np.stack([pts.real, pts.imag], axis=-1))


def mesh_segments(mesh: Mesh, edges: NDArray | None = None) -> NDArray[np.float64]:
    """(n, 2, 2) segments of the mesh's edges (all, or the ids / mask given)."""
    e = mesh.topology.edges if edges is None else mesh.topology.edges[edges]
    return np.stack([mesh.vertices[e[:, 0]], mesh.vertices[e[:, 1]]], axis=1)


def boundary_segments(mesh: Mesh) -> NDArray[np.float64]:
    return mesh_segments(mesh, mesh.topology.boundary_edges)


def curve_segments(points: NDArray[np.float64]) -> NDArray[np.float64]:
    """(n * m, 2, 2) segments of (n, m + 1, 2) curves (or one (m + 1, 2) curve)."""
    points = np.asarray(points, dtype=float)
    if points.ndim == 2:
        points = points[None]
    return np.stack([points[:, :-1], points[:, 1:]], axis=2).reshape(-1, 2, 2)
