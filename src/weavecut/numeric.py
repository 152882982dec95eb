"""Arithmetic with the same bits on every machine.

numpy hands ``@``, ``dot``, ``einsum`` and ``linalg`` to BLAS and LAPACK (or to SIMD loops),
whose kernels differ between CPUs in how they order and fuse multiply-adds: one product of two
matrices differs in its last bits on a laptop and on a workshop PC, and a decision made on it
(which piece goes first, where a strip is split, which way a pentagon's axis points) can flip.
Everything here is built from elementwise ``+ - * /`` and ``sqrt``, which IEEE 754 rounds
exactly, in a fixed order, so it gives the same bits everywhere. weave-cut uses these instead of
numpy's kernels (``tests/test_determinism.py`` keeps it so), and makes discrete decisions on
:func:`snap`-ped values, never on the last bits of a float.

>>> m = affine_matrix(0.5, 0.0, 0.0, 2.0, 3.0, -1.0)
>>> transform(m)(np.array([[1.0, 1.0]])).tolist()
[[3.5, 1.0]]
>>> matmul(affine_inverse(m), m).tolist()
[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
>>> solve([[2.0, 1.0], [1.0, 3.0]], [3.0, 5.0])
[0.8, 1.4]
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

GRID = 1e-6  # snap(): 1 nm (or nm², or a millionth of a mesh unit): far below what prints or
# cuts, far above the noise of kernels and SIMD paths (about 1e-13 mm at 100 mm)


def dot(a: ArrayLike, b: ArrayLike) -> NDArray[np.float64]:
    """Dot products along the last axis (broadcast): ``(a * b).sum(-1)``."""
    return (np.asarray(a, dtype=float) * np.asarray(b, dtype=float)).sum(axis=-1)


def distinct(values: ArrayLike, axis: int | None = None) -> NDArray:
    """``np.unique(values, axis=axis)``: the sorted distinct values (or rows), asked through
    its counting path, which, unlike the plain call, does not import numpy.ma (10 ms of a
    command) to check for masked input."""
    return np.unique(values, axis=axis, return_counts=True)[0]


def offsets_of(counts: ArrayLike) -> NDArray[np.int64]:
    """(n + 1,) where each of ``n`` runs of ``counts`` items starts, then where the last ends:
    ``np.r_[0, np.cumsum(counts)]`` without ``np.r_``'s parsing (8 us a call).

    >>> offsets_of([2, 0, 3]).tolist()
    [0, 2, 2, 5]
    """
    return np.concatenate([[0], np.cumsum(counts, dtype=np.int64)])


def median(values: ArrayLike) -> float:
    """``np.median`` of finite values (the mean of the middle two of an even count), without
    its NaN check, which imports numpy.ma (6 ms of a command).

    >>> median([3.0, 1.0, 2.0]), median([4.0, 1.0, 2.0, 3.0])
    (2.0, 2.5)
    """
    ordered = np.sort(np.asarray(values, dtype=float).ravel())
    half = len(ordered) // 2
    return float(ordered[half] if len(ordered) % 2 else ordered[half - 1:half + 1].mean())


def among(values: ArrayLike, keys: NDArray) -> NDArray[np.bool_]:
    """``np.isin(values, keys)`` for sorted distinct ``keys`` (:func:`distinct`'s), by a binary
    search (np.isin's sorting path imports numpy.ma).

    >>> among([3, 7, 1], np.array([1, 2, 3])).tolist()
    [True, False, True]
    """
    values = np.asarray(values)
    at = np.minimum(np.searchsorted(keys, values), max(len(keys) - 1, 0))
    return (keys[at] == values) if len(keys) else np.zeros(values.shape, dtype=bool)


def unique_rows(rows: NDArray[np.integer]) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """(first, inverse) of ``np.unique(rows, axis=0, return_index=True, return_inverse=True)``
    for integer rows (N, k): the first row of each distinct one, in ascending order, and which
    of them each row is; by a stable lexsort (np.unique's sort of structured rows is three
    times slower).

    >>> [a.tolist() for a in unique_rows(np.array([[2, 1], [0, 5], [2, 1]]))]
    [[1, 0], [1, 0, 1]]
    """
    rows = np.asarray(rows)
    order = np.lexsort(rows.T[::-1])
    ordered = rows[order]
    new = np.ones(len(rows), dtype=bool)
    new[1:] = (ordered[1:] != ordered[:-1]).any(axis=1)
    inverse = np.empty(len(rows), dtype=np.intp)
    inverse[order] = np.cumsum(new) - 1
    return order[new], inverse


def matmul(a: ArrayLike, b: ArrayLike) -> NDArray[np.float64]:
    """``a @ b`` for 1-D, 2-D and stacked arrays, as numpy defines it, without BLAS."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if b.ndim == 1:
        return dot(a, b)
    b_rows = np.swapaxes(b, -1, -2)  # (..., m, k): a row per column of b
    return dot(a, b_rows) if a.ndim == 1 else dot(a[..., :, None, :], b_rows[..., None, :, :])


def affine_matrix(a: float, b: float, c: float, d: float, xoff: float = 0.0,
                  yoff: float = 0.0) -> NDArray[np.float64]:
    """(3, 3) the map (x, y) -> (a x + b y + xoff, c x + d y + yoff)."""
    return np.array([[a, b, xoff], [c, d, yoff], [0.0, 0.0, 1.0]])


def cos_sin(angles: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(cos, sin) of ``angles`` in degrees, with the last-bit residues of quarter turns made
    zero, so a turn by 90 degrees is exact."""
    a = np.radians(np.asarray(angles, dtype=float))
    c, s = np.cos(a), np.sin(a)
    return np.where(np.abs(c) < 2.5e-16, 0.0, c), np.where(np.abs(s) < 2.5e-16, 0.0, s)


def turn(xy: ArrayLike, angles: ArrayLike, shift: ArrayLike = 0.0) -> NDArray[np.float64]:
    """The points ``xy`` (..., 2) turned about the origin by ``angles`` degrees (broadcast
    against ``xy[..., 0]``: one per point, per row, ...), quarter turns exact, plus ``shift``.

    >>> turn([[1.0, 2.0]], 90.0, (10.0, 0.0)).tolist()
    [[8.0, 1.0]]
    """
    xy = np.asarray(xy, dtype=float)
    c, s = cos_sin(angles)
    x, y = xy[..., 0], xy[..., 1]
    return np.stack([c * x - s * y, s * x + c * y], axis=-1) + np.asarray(shift, dtype=float)


def affine(angle: float = 0.0, shift=(0.0, 0.0), scale: float = 1.0) -> NDArray[np.float64]:
    """(3, 3) the map xy -> scale * turn(xy, ``angle`` degrees) + ``shift``; quarter turns
    are exact."""
    c, s = (float(v) * scale for v in cos_sin(angle))
    return affine_matrix(c, -s, s, c, shift[0], shift[1])


def transform(matrix: ArrayLike):
    """The function (N, 2) -> (N, 2) of the affine ``matrix`` (3, 3), for ``shapely.transform``."""
    m = np.asarray(matrix, dtype=float)

    def apply(xy: NDArray) -> NDArray[np.float64]:
        xy = np.asarray(xy, dtype=float)
        x, y = xy[..., 0], xy[..., 1]
        return np.stack([m[0, 0] * x + m[0, 1] * y + m[0, 2],
                         m[1, 0] * x + m[1, 1] * y + m[1, 2]], axis=-1)

    return apply


def affine_inverse(matrix: ArrayLike) -> NDArray[np.float64]:
    """The inverse of the affine ``matrix`` (3, 3) in closed form."""
    (a, b, x), (c, d, y) = np.asarray(matrix, dtype=float)[:2].tolist()
    det = a * d - b * c
    ia, ib, ic, id_ = d / det, -b / det, -c / det, a / det
    return affine_matrix(ia, ib, ic, id_, -(ia * x + ib * y), -(ic * x + id_ * y))


def plane_normals(points: ArrayLike, start: ArrayLike, rounds: int = 200) -> NDArray[np.float64]:
    """(F, 3) unit normals of the least-squares planes through the point sets ``points``
    (F, k, 3), each centred on its mean, on the side of ``start`` (F, 3), a normal near the
    answer (Newell's, say). The normal is the eigenvector of the smallest eigenvalue of the
    scatter matrix S: power iteration with S's adjugate, whose eigenvalues are the products of
    the other two, so each round shrinks the error by the ratio of S's two smallest (a nearly
    flat set converges in two or three); it stops when no normal moves, or after ``rounds``.
    A set with no plane (a line, a point) keeps ``start``."""
    x = np.asarray(points, dtype=float)
    s = (x[..., :, None] * x[..., None, :]).sum(axis=-3)  # (F, 3, 3)
    adjugate = np.stack([np.cross(s[..., 1, :], s[..., 2, :]), np.cross(s[..., 2, :], s[..., 0, :]),
                         np.cross(s[..., 0, :], s[..., 1, :])], axis=-2)
    m = n = start = np.asarray(start, dtype=float)
    for _ in range(rounds):
        m = matmul(adjugate, n[..., None])[..., 0]
        size = np.sqrt(dot(m, m))[..., None]
        m = np.where(size > 0, m / np.where(size > 0, size, 1.0), n)
        m *= np.where(dot(m, n) < 0, -1.0, 1.0)[..., None]
        if (np.abs(m - n) <= 4 * np.finfo(float).eps).all():
            break
        n = m
    return m * np.where(dot(m, start) < 0, -1.0, 1.0)[..., None]


def line_fit(x: ArrayLike, y: ArrayLike) -> tuple[float, float]:
    """(slope, intercept) of the least-squares line through the points (x, y), in closed form
    (``np.polyfit`` solves it with LAPACK)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    dx = x - x.mean()
    slope = float(dot(dx, y - y.mean()) / dot(dx, dx))
    return slope, float(y.mean() - slope * x.mean())


def solve(a: ArrayLike, b: ArrayLike) -> list[float]:
    """x with ``a x = b`` for a small square system (Gaussian elimination with partial
    pivoting, in Python floats); ValueError when ``a`` is singular."""
    rows = [[*map(float, r), float(v)] for r, v in zip(np.asarray(a).tolist(), np.asarray(b))]
    n = len(rows)
    for k in range(n):
        p = max(range(k, n), key=lambda i: (abs(rows[i][k]), -i))
        if rows[p][k] == 0.0:
            raise ValueError("singular system")
        rows[k], rows[p] = rows[p], rows[k]
        for i in range(k + 1, n):
            f = rows[i][k] / rows[k][k]
            rows[i] = [u - f * w for u, w in zip(rows[i], rows[k])]
    x = [0.0] * n
    for k in reversed(range(n)):
        x[k] = (rows[k][n] - sum(rows[k][j] * x[j] for j in range(k + 1, n))) / rows[k][k]
    return x


class SnapError(FloatingPointError):
    """A NaN, an infinity or a value beyond int64 reached :func:`snap`: a bug upstream, not
    a user's input. Its cast to an integer is whatever the CPU makes of it (the most negative
    int64 on x86, 0 on ARM), so a decision resting on it would differ between machines."""


def snap(values: ArrayLike, grid: float = GRID) -> NDArray[np.int64]:
    """Integer keys of ``values`` on a ``grid``: what a decision (a sort, a tie, a
    comparison) looks at, so that last-bit noise cannot flip it. Raises :class:`SnapError`,
    naming the value and the caller, on a value with no integer key (NaN, inf, beyond int64).

    >>> snap([0.1234567, -2e-7]).tolist()
    [123457, 0]
    """
    keys = np.rint(np.asarray(values, dtype=float) / grid)
    if keys.size and not np.abs(keys).max() < 2.0 ** 63:  # the max of a NaN is NaN
        raise SnapError(_keyless(np.asarray(values, dtype=float), keys, sys._getframe(1)))
    return keys.astype(np.int64)


def _keyless(values: NDArray[np.float64], keys: NDArray[np.float64], caller) -> str:
    """What :func:`snap` refuses: the first keyless value, where, and who asked."""
    keyless = ~(np.abs(keys) < 2.0 ** 63)  # NaN compares false
    first = tuple(int(i) for i in np.argwhere(keyless)[0])
    at = "" if not first else f" at index {first[0] if len(first) == 1 else first}"
    file = Path(caller.f_code.co_filename)
    file = "/".join(file.parts[file.parts.index("weavecut"):]) if "weavecut" in file.parts \
        else file.name
    return (f"snap() got {float(values[first]):g}{at} ({int(keyless.sum())} of {values.size} "
            f"values have no integer key), asked by {caller.f_code.co_name}() in "
            f"{file}:{caller.f_lineno}")


def root(f, a: float, b: float, xtol: float, rtol: float, iterations: int = 100) -> float:
    """x in [a, b] with ``f(x) = 0`` to within ``xtol + rtol |x|``, where ``f(a)`` and ``f(b)``
    differ in sign: Brent's method, step for step as ``scipy.optimize.brentq`` takes it (the
    same floats, so the same answer), without importing scipy.

    Each step tries the secant (or inverse quadratic) step from the best point; a step that
    is not short enough, or a point whose value does not fall, bisects the bracket instead.

    >>> round(root(lambda x: x * x - 2.0, 0.0, 2.0, 1e-12, 1e-15), 12)
    1.414213562373
    """
    pre, cur, fpre, fcur = float(a), float(b), float(f(a)), float(f(b))
    if fpre == 0:
        return pre
    if fcur == 0:
        return cur
    if (fpre < 0) == (fcur < 0):
        raise ValueError("f(a) and f(b) must differ in sign")
    blk = fblk = spre = scur = 0.0
    for _ in range(iterations):
        if fpre != 0 and fcur != 0 and (fpre < 0) != (fcur < 0):
            blk, fblk = pre, fpre  # the bracket's other end
            spre = scur = cur - pre
        if abs(fblk) < abs(fcur):  # cur: the best point so far
            pre, cur, blk = cur, blk, cur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(cur)) / 2
        sbis = (blk - cur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return cur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if pre == blk:  # secant
                stry = -fcur * (cur - pre) / (fcur - fpre)
            else:  # inverse quadratic
                dpre = (fpre - fcur) / (pre - cur)
                dblk = (fblk - fcur) / (blk - cur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            spre, scur = (scur, stry) if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta) \
                else (sbis, sbis)
        else:
            spre = scur = sbis
        pre, fpre = cur, fcur
        cur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = float(f(cur))
    raise RuntimeError(f"no root within {iterations} steps")
