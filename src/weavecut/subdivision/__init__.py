"""Subdivision schemes: each a pure ``step(mesh, **options) -> Level``; ``subdivide`` runs one."""

from __future__ import annotations

import sys

from ..mesh import Mesh
from . import akleman, butterfly, catmull_clark, doo_sabin, dual, loop, midedge, snub, sqrt3
from .hierarchy import Hierarchy, Level, check_fits

SCHEMES = {
    "snub": snub.step,
    "loop": loop.step,
    "butterfly": butterfly.step,
    "sqrt3": sqrt3.step,
    "catmull-clark": catmull_clark.step,
    "midedge": midedge.step,
    "doo-sabin": doo_sabin.step,
    "dual": dual.step,
    "akleman": akleman.step,
}


def _counts(scheme: str):
    """The scheme's ``counts(V, E, F, H)`` recursion (every scheme module defines one)."""
    return sys.modules[SCHEMES[scheme].__module__].counts


def subdivide(mesh: Mesh, levels: int, scheme: str = "snub", *, steps=None,
              **options) -> Hierarchy:
    """Levels 0..``levels`` of ``scheme`` applied to ``mesh`` (checked to fit in memory first).

    ``steps`` may wrap ``range(levels)`` (a progress bar, say); it is iterated once per step.
    """
    if scheme not in SCHEMES:
        raise ValueError(f"unknown scheme {scheme!r}; choose one of {', '.join(SCHEMES)}")
    if levels < 0:
        raise ValueError(f"levels must be >= 0, got {levels}")
    check_fits(mesh, levels, _counts(scheme))
    out = [Level(mesh)]
    for _ in range(levels) if steps is None else steps:
        out.append(SCHEMES[scheme](out[-1].mesh, **options))
    return tuple(out)


__all__ = ["SCHEMES", "Hierarchy", "Level", "akleman", "butterfly", "catmull_clark",
           "doo_sabin", "dual", "loop", "midedge", "snub", "sqrt3", "subdivide"]
