"""The weaving page's diagrams of a four-copy pattern tell the warp (copies A and C) from the
weft (copies B and D), and A from C, whatever the palette and layout: read from the diagrams'
fills on the Drawing, each tile's copy from the weave (the strand on top there) and the module
plan, colours compared by CIEDE2000."""

from __future__ import annotations

import numpy as np
import pytest

from weavecut.inputs import get
from weavecut.layout.colour_difference import colour_difference
from weavecut.papermodel.book import strand_book
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

APART = 10.0  # CIEDE2000: colours this far apart are told apart at a glance


@pytest.fixture(scope="module")
def weaves():
    return snub_weaves(subdivide(get("square-grid:2x2"), 2))


def copy_fills(weaves, book) -> list[set[str]]:
    """The fills of the last diagram (every strand in) by the copy (0-3) of the strand on top
    of each tile."""
    page = book.drawing.sheets[1]
    (layer,) = [lay for lay in page.layers if lay.name == "diagrams"]
    fills = layer.shapes[-1].fills
    weave = weaves[-1]
    assert len(fills) == weave.n_tiles
    copy_of = np.full(weave.n_strands, -1)
    for j, row in enumerate(book.plan.copies.tolist()):
        copy_of[row] = j
    out: list[set[str]] = [set() for _ in range(4)]
    for fill, top in zip(fills, weave.tile_over.tolist()):
        if top >= 0 and copy_of[top] >= 0:
            out[copy_of[top]].add(fill)
    return out


@pytest.mark.parametrize("pal, layout", [("maritime-12", "module"), ("maritime-12", "mixed"),
                                         ("maritime-4", "module"), ("okabe-ito", "module")])
def test_the_diagrams_tell_the_warp_from_the_weft(weaves, pal, layout):
    book = strand_book(list(weaves), palette(pal), layout=layout)
    assert book.plan.k == 4
    a, b, c, d = copy_fills(weaves, book)
    warp, weft = a | c, b | d
    assert warp and weft and not warp & weft and not a & c
    apart = min(float(colour_difference(x, y)) for x in warp for y in weft)
    assert apart >= APART, (sorted(warp), sorted(weft))


def test_a_module_layout_says_its_diagrams_are_coloured_by_copy(weaves):
    # the strips of the module layout are printed in the module's colours, every copy alike:
    # the step that lays the warp says the diagrams colour the copies apart; a layout whose
    # strips carry those colours does not
    words = {}
    for layout in ("module", "mixed"):
        book = strand_book(list(weaves), palette("maritime-12"), layout=layout)
        page = book.drawing.sheets[1]
        words[layout] = " ".join(t.text for lay in page.layers if lay.name == "steps"
                                 for t in lay.shapes)
    assert "hue of its own" in " ".join(words["module"].split())
    assert "hue of its own" not in words["mixed"]
