"""Every figure weave-cut reproduces, by name: the subdivision, fractal and level-image
figures of ``figures.subdivision`` (built there and in ``figures.fractal`` and
``figures.level_image``), the weave figures of ``figures.weaving``, the classic schemes'
stages and weaves of ``figures.schemes`` (built there and in ``figures.scheme_stages``) and
the jigsaw puzzle's of ``figures.jigsaw``."""

from __future__ import annotations

import typing

from . import jigsaw, schemes, subdivision, weaving

FIGURES = {**subdivision.FIGURES, **weaving.FIGURES, **schemes.FIGURES, **jigsaw.FIGURES}


def is_picture(name: str) -> bool:
    """Whether figure ``name`` is a PNG picture (its builder returns bytes) rather than a
    Drawing, known from the builder's return type before anything is drawn."""
    return typing.get_type_hints(FIGURES[name][1]).get("return") is bytes
