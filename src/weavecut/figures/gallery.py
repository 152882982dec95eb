"""Every figure weave-cut reproduces, by name: the subdivision and fractal figures of
``figures.subdivision`` and the weave and scheme figures of ``figures.weaving``."""

from __future__ import annotations

from . import subdivision, weaving

FIGURES = {**subdivision.FIGURES, **weaving.FIGURES}
