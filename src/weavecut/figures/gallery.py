"""Every figure weave-cut reproduces, by name: the subdivision, fractal and level-image
figures of ``figures.subdivision`` (built there and in ``figures.fractal`` and
``figures.level_image``), the weave figures of ``figures.weaving``, the classic schemes'
stages and weaves of ``figures.schemes`` (built there and in ``figures.scheme_stages``) and
the jigsaw puzzle's of ``figures.jigsaw``."""

from __future__ import annotations

from . import jigsaw, schemes, subdivision, weaving

FIGURES = {**subdivision.FIGURES, **weaving.FIGURES, **schemes.FIGURES, **jigsaw.FIGURES}
