"""Subdivision schemes: each a pure ``step(mesh, **options) -> Level``."""

from __future__ import annotations

from . import akleman, butterfly, catmull_clark, doo_sabin, dual, loop, midedge, snub, sqrt3
from .hierarchy import Hierarchy, Level

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

__all__ = ["SCHEMES", "Hierarchy", "Level", "akleman", "butterfly", "catmull_clark",
           "doo_sabin", "dual", "loop", "midedge", "snub", "sqrt3"]
