"""Subdivision schemes: each a pure ``step(mesh, **options) -> Level``."""

from __future__ import annotations

from . import snub
from .hierarchy import Hierarchy, Level

SCHEMES = {"snub": snub.step}

__all__ = ["SCHEMES", "Hierarchy", "Level", "snub"]
