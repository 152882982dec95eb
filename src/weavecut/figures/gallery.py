"""Every figure weave-cut reproduces, by name: the subdivision and fractal figures of
``figures.subdivision``, the weave figures of ``figures.weaving`` and the classic schemes'
stages and weaves of ``figures.schemes``."""

from __future__ import annotations

from . import schemes, subdivision, weaving

FIGURES = {**subdivision.FIGURES, **weaving.FIGURES, **schemes.FIGURES}
