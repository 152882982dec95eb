"""Every figure weave-cut reproduces, by name: the mesh and fractal figures of
``layout.figures`` and the weave and scheme figures of ``layout.weave_figures``."""

from __future__ import annotations

from . import figures, weave_figures

FIGURES = {**figures.FIGURES, **weave_figures.FIGURES}
