"""Every figure weave-cut reproduces, by name: the subdivision and fractal figures of
``figures.subdivision``, the weave and scheme figures of ``figures.weaving`` and the
jigsaw puzzle's of ``figures.jigsaw``."""

from __future__ import annotations

from . import jigsaw, subdivision, weaving

FIGURES = {**subdivision.FIGURES, **weaving.FIGURES, **jigsaw.FIGURES}
