"""What a maker reads on a card sheet's page or a strip's colour key: each colour of a strip
palette by the name a shop sells it under ("steel blue", not "navy 2" for a mid blue), every
name its palette's only one, and a name's light or dark word true to the colour's CIELAB
lightness (computed by ``colour_difference``, not read from the preset)."""

from __future__ import annotations

import re

import pytest

from weavecut.layout.colour_difference import srgb_to_lab
from weavecut.weave.colour import palette

STRIP_PALETTES = ("maritime-4", "maritime-12", "okabe-ito")
DARK = {"navy", "forest", "black"}  # L* under 45
LIGHT = {"aqua", "sage", "salmon", "sand", "lavender", "sky", "yellow"}  # L* over 65


@pytest.mark.parametrize("name", STRIP_PALETTES)
def test_every_strip_colour_has_a_shop_name_of_its_own(name):
    """Planted: maritime-12 named by its families ("navy 1", "navy 2") fails."""
    pal = palette(name)
    assert len(pal.names) == len(pal.flat) and all(pal.names)
    assert len(set(pal.names)) == len(pal.names)
    assert not any(re.search(r"\d", n) for n in pal.names)  # a shade number is no name
    for colour, called, (lightness, _, _) in zip(pal.flat, pal.names, srgb_to_lab(pal.flat)):
        words = set(called.split())
        assert not words & DARK or lightness < 45, (called, colour, lightness)
        assert not words & LIGHT or lightness > 65, (called, colour, lightness)
