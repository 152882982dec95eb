"""What the tool measures about the paper, stated exactly as measured (``weave-cut findings``).

Every finding is a function that measures and then words what it measured, so the numbers in
the statement are the numbers computed. The README's findings section is this module's
Markdown output, and ``tests/analysis/test_findings.py`` recomputes the fast findings and
compares them with the README line for line. Findings marked slow (level 7 of every input,
levels 7-10 of the pentagon: a few minutes and about 3.5 GB) run only in ``weave-cut findings``.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, replace

import numpy as np

from .. import inputs
from ..mesh import outer_vertices, vertex_degrees
from ..subdivision import subdivide
from ..weave.report import weave_summaries
from ..weave.snub_weave import snub_weaves
from . import boxcount as bc
from . import fractal as fr
from . import lsystem as ls
from .convexity import nonconvex_levels


@dataclass(frozen=True)
class Finding:
    """One row of the findings table: a key, its topic, the measured statement, how to repeat."""

    key: str
    topic: str
    statement: str
    repeat: str
    slow: bool = False


CONVEXITY_INPUTS = ("pentagon", "square-grid", "tiling-8-4", "ngon:24", "triangulated-ngon:24")
CONVEXITY_LEVELS = 6
COUNT_LEVELS = 5
LINEAGE_CASES = (("pentagon", 5), ("square-grid:6x6", 5), ("pentagon-flower", 5))
DIMENSION_LEVELS = range(6, 11)
CURVE_LEVELS = 10
DEEP_LEVEL = 7


def _levels_text(levels) -> str:
    levels = list(levels)
    return f"{levels[0]}–{levels[-1]}" if len(levels) > 1 else str(levels[0])


def counts() -> Finding:
    """Eq. (2), the degrees of new vertices and the boundary length, on every built-in input."""
    failures, inner_degrees, outer_degrees, deviation = [], set(), set(), 0.0
    for name in inputs.FLAT:  # a loop over inputs and levels
        h = subdivide(inputs.get(name), COUNT_LEVELS)
        for parent, child in zip(h, h[1:]):
            p, c = parent.mesh, child.mesh
            n_corners = len(p.face_indices)
            expected = (p.n_vertices + 2 * p.topology.n_edges + p.n_faces,
                        3 * p.topology.n_edges + n_corners, n_corners)
            if (c.n_vertices, c.topology.n_edges, c.n_faces) != expected:
                failures.append(f"{name} level {h.index(child)}")
        last = h[-1].mesh
        degree, outer = vertex_degrees(last), outer_vertices(last)
        if (degree[:h[0].mesh.n_vertices] != vertex_degrees(h[0].mesh)).any():
            failures.append(f"{name}: an input vertex changed its degree")
        born = np.arange(last.n_vertices) >= h[1].mesh.n_vertices   # born in step 2 or later
        inner_degrees |= set(np.unique(degree[born & ~outer]).tolist())
        outer_degrees |= set(np.unique(degree[born & outer]).tolist())
        length0 = _boundary_length(h[0].mesh)
        for t, lv in enumerate(h):
            expected_length = length0 * (3 / math.sqrt(7)) ** t
            deviation = max(deviation, abs(_boundary_length(lv.mesh) / expected_length - 1))
    held = ("holds (and so eq. (1) for the pentagon)" if not failures
            else f"fails at {', '.join(failures)}")
    return Finding(
        "counts", "Eq. (1)/(2) and degrees",
        f"Eq. (2) {held} at levels 0–{COUNT_LEVELS} of all {len(inputs.FLAT)} flat built-in "
        f"inputs; input vertices keep their degree; vertices born in step 2 or later have "
        f"degree {_set(inner_degrees)} inside and {_set(outer_degrees)} on the boundary; the "
        f"boundary is (3/√7)^t times as long at level t (largest relative deviation "
        f"{deviation:.0e}).",
        f"`weave-cut stats INPUT --levels {COUNT_LEVELS} --json`")


def _set(values) -> str:
    values = sorted(values)
    return " or ".join(str(v) for v in values) if values else "(none)"


def _boundary_length(mesh) -> float:
    seg = bc.boundary_segments(mesh)
    return float(np.hypot(*(seg[:, 1] - seg[:, 0]).T).sum())


def lineage() -> Finding:
    """Long children per parent strand, whether siblings cross, parents without children."""
    parts, orphans, exact, childless = [], [], True, set()
    for name, levels in LINEAGE_CASES:
        weaves = snub_weaves(subdivide(inputs.get(name), levels))
        rows = [s["lineage"] for s in weave_summaries(weaves)[1:]]
        first = next((i for i, r in enumerate(rows) if r["parents_with_exactly_two_long_children"]),
                     len(rows))
        rows, start = rows[first:], first + 2
        for r in rows:
            childless |= {int(k) for k in r["childless_parent_length_histogram"]}
            with_long = sum(r["long_children_per_parent_with_long_children"].values())
            exact &= (with_long == r["parents_with_exactly_two_long_children"]
                      == r["long_sibling_pairs_that_cross"])
        span = _levels_text(range(start, levels + 1))
        parts.append(f"{name} levels {span}: "
                     + ", ".join(str(r["parents_with_exactly_two_long_children"]) for r in rows))
        orphans.append(f"{name} " + ", ".join(f"{r['parents_without_children']} of "
                                              f"{r['parents']}" for r in rows))
    verdict = ("has exactly two, and those two cross each other" if exact else
               "does not always have exactly two crossing ones")
    return Finding(
        "lineage", "strands and lineage",
        f"Every parent strand with long children (≥ 3 own tiles) {verdict}: "
        f"{'; '.join(parts)} parents. A child strand goes to the parent strand that owns or "
        f"passes under most of its pentagons' parent tiles, and some parents get none: "
        f"{'; '.join(orphans)} (same levels); each of those is on top of "
        f"{_set(childless)} tile(s).",
        "`weave-cut weave INPUT --levels 5 --json` (lineage)")


def _convexity(smooth: bool, centre: str, where: bool) -> tuple[str, set[str]]:
    """Per input the non-convex faces by level (and with ``where`` the kinds of reflex-corner
    vertex); also the set of all those kinds."""
    parts, places = [], set()
    for name in CONVEXITY_INPUTS:
        h = subdivide(inputs.get(name), CONVEXITY_LEVELS, smooth=smooth, centre=centre)
        rows = nonconvex_levels(h, first=0)
        if not rows:
            parts.append(f"{name} none")
            continue
        text = ", ".join(f"{r['nonconvex_faces']:,} at level {r['level']}" for r in rows)
        here = sorted({w for r in rows for _, w in r["where"]})
        places |= set(here)
        parts.append(f"{name} {text}" + (f" (all at {' or '.join(here)})" if where else ""))
    return "; ".join(parts), places


def convexity_smoothed() -> Finding:
    text, places = _convexity(True, "vertex", True)
    outer = all(p.startswith("outer") for p in places)
    verdict = (("So smoothing does not always keep tiles convex; every reflex corner found is "
                "an outer vertex." if outer else "So smoothing does not always keep tiles "
                "convex.") if places else "No face turned non-convex.")
    return Finding(
        "convexity", "convexity, open question 1",
        f"With smoothing and vertex-mean centres (the default), non-convex faces at levels "
        f"0–{CONVEXITY_LEVELS}: {text}. {verdict}",
        f"`weave-cut convexity INPUT --levels {CONVEXITY_LEVELS}`")


def convexity_area() -> Finding:
    return Finding(
        "convexity-area", "convexity with area centroids",
        f"With smoothing and area centroids, non-convex faces at levels "
        f"0–{CONVEXITY_LEVELS}: {_convexity(True, 'area', False)[0]}.",
        f"`weave-cut convexity INPUT --levels {CONVEXITY_LEVELS} --centre area`")


def convexity_unsmoothed() -> Finding:
    return Finding(
        "convexity-unsmoothed", "convexity without smoothing",
        f"Without smoothing (operations 1–3 only), non-convex faces at levels "
        f"0–{CONVEXITY_LEVELS}: {_convexity(False, 'vertex', False)[0]}.",
        f"`weave-cut convexity INPUT --levels {CONVEXITY_LEVELS} --no-smooth`")


def convexity_deep() -> Finding:
    """Open question 1 beyond level 6: every input at level 7, the pentagon up to level 10."""
    parts = []
    for name in CONVEXITY_INPUTS:
        h = _pentagon() if name == "pentagon" else subdivide(inputs.get(name), DEEP_LEVEL)
        rows = nonconvex_levels(h, first=DEEP_LEVEL)
        text = " and ".join(f"{r['nonconvex_faces']:,} of {r['faces']:,} at level {r['level']} "
                         f"({', '.join(f'{n:,} at {w}' for n, w in r['where'])})" for r in rows)
        parts.append(f"{name} {text or 'none'}")
    return Finding(
        "convexity-deep", "convexity beyond level 6",
        f"With smoothing and vertex-mean centres, non-convex faces at level {DEEP_LEVEL} "
        f"(the pentagon: levels {DEEP_LEVEL}–{CURVE_LEVELS}): {'; '.join(parts)}.",
        f"`weave-cut convexity INPUT --levels {DEEP_LEVEL}`; `weave-cut findings` (slow)")


@functools.lru_cache(maxsize=1)
def _pentagon():
    """The pentagon to level CURVE_LEVELS, shared by the slow findings (about 3 GB)."""
    return subdivide(inputs.get("pentagon"), CURVE_LEVELS)


def dimension() -> Finding:
    """Box counting on the pentagon's boundary at levels 6-10 (the L-system curves)."""
    pentagon = inputs.get("pentagon")
    error = max(fr.boundary_lsystem_error(subdivide(pentagon, 8)))
    rows = [(t, bc.box_counting(bc.lsystem_boundary(pentagon, t))) for t in DIMENSION_LEVELS]
    values = ", ".join(f"{t}: {r['dimension']:.4f} ± {r['stderr']:.4f} "
                       f"(halves {r['halves'][0]:.3f}/{r['halves'][1]:.3f})" for t, r in rows)
    last = rows[-1][1]
    estimates = np.array([r["dimension"] for _, r in rows])
    trend = "rises" if (np.diff(estimates) > 0).all() else "does not rise steadily"
    return Finding(
        "dimension", "boundary dimension",
        f"Estimator: box counting, the least-squares slope of log N(ε) against log 1/ε, N "
        f"averaged over {last['grids']} shifted grids, 4 box sizes per halving from 1/32 of "
        f"the curve's extent down to 2 mean edge lengths; ± is the slope's standard error, "
        f"'halves' the slopes fitted to the coarser and finer half of the sizes alone (the "
        f"real uncertainty: the counts wave with log ε). On the pentagon's boundary at level "
        f"t (the L-system curve; it equals the mesh boundary to {error:.0e} up to level 8): "
        f"{values}. The estimate {trend} with the level; the analytic value is "
        f"log 3/log √7 = {ls.DIMENSION:.5f}, {ls.DIMENSION - last['dimension']:.4f} above the "
        f"level-{rows[-1][0]} estimate.",
        "`weave-cut fractal pentagon --levels 8 --json` (level 8); `weave-cut findings` "
        "(slow)")


def inner_curves() -> Finding:
    """Whether the inner curves' growth per level changes monotonically (pentagon, level 10)."""
    h = _pentagon()
    rows = {(r["born"], r["kind"]): r for born in (1, 2, 3)
            for r in fr.growth_monotonicity(h, born)}
    spokes, inner2, inner3 = rows[1, "outer-inner"], rows[2, "inner-inner"], rows[3, "inner-inner"]

    def seq(r):
        return ", ".join(f"{g:.4f}" for g in r["growth"])

    aggregate = all(r["aggregate_rising"] for k, r in rows.items() if k[1] != "boundary")
    return Finding(
        "inner-curves", "inner curves, open question 2",
        f"Measured: the length L(t) of the curve grown from one edge born at level s (its "
        f"3^(t−s) edges at level t), and the growth L(t)/L(t−1), on the pentagon up to level "
        f"{CURVE_LEVELS}. Summed over all curves of a kind, the growth "
        f"{'rises at every level' if aggregate else 'does not always rise'}: the 5 centre-to-"
        f"boundary curves born at level 1: {seq(spokes)} (levels 2–{CURVE_LEVELS}); the "
        f"{inner2['curves']} curves between inner vertices born at level 2: {seq(inner2)} "
        f"(levels 3–{CURVE_LEVELS}); if the last growth g held at every scale, the dimension "
        f"would be log 3/log(3/g) = {fr.implied_dimension(spokes['growth'][-1]):.4f} and "
        f"{fr.implied_dimension(inner2['growth'][-1]):.4f}. "
        f"Single curves: of those {inner2['curves']}, {inner2['rising']} rise at every level "
        f"and {inner2['curves'] - inner2['rising']} do not (their growth falls at some "
        f"level); of the {inner3['curves']} born at level 3, {inner3['rising']} rise and "
        f"{inner3['curves'] - inner3['rising']} do not; of the 5 centre-to-boundary curves "
        f"{spokes['rising']} rise. The boundary grows by 3/√7 = {3 / math.sqrt(7):.4f} at "
        f"every level ({rows[1, 'boundary']['constant']} of {rows[1, 'boundary']['curves']} "
        "curves constant to 1e-9).",
        "`weave-cut fractal pentagon --levels 8 --born 2 --json` (to level 8); "
        "`weave-cut findings` (slow)")


FINDINGS: tuple[Callable[[], Finding], ...] = (
    counts, lineage, convexity_smoothed, convexity_area, convexity_unsmoothed, convexity_deep,
    dimension, inner_curves)
SLOW = (convexity_deep, dimension, inner_curves)


def findings(fast: bool = False) -> list[Finding]:
    """Measure every finding (``fast``: only those not in SLOW)."""
    try:
        return [replace(f(), slow=f in SLOW) for f in FINDINGS if not (fast and f in SLOW)]
    finally:
        _pentagon.cache_clear()


def markdown_rows(rows: list[Finding]) -> list[str]:
    """One Markdown table row per finding."""
    return [f"| {r.topic} | {r.statement} | {r.repeat} |" for r in rows]


def markdown(rows: list[Finding]) -> str:
    """The findings table as Markdown (what the README's findings section holds)."""
    head = ["| finding | measured | repeat with |", "| --- | --- | --- |"]
    return "\n".join(head + markdown_rows(rows)) + "\n"


def as_json(rows: list[Finding]) -> list[dict]:
    return [asdict(r) for r in rows]
