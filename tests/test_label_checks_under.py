"""What lies under a label, found for all labels at once (``label_checks._under``), is what the
plain walk down the fills finds for each label's ink alone (``fills_under``), fill for fill and
in order, on random stacks of fills with words and texts on them, across their edges, on a
plate, on the paper, and on a fill that a later one covers in part."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout import label_checks as lc
from weavecut.layout.drawing import (Layer, Sheet, Style, Text, polygons_from_shapely,
                                     polylines_from_lines)
from weavecut.layout.labels import centred_text

COLOURS = ("#203060", "#e0c040", "#ffffff", "#a03030", "#30a040")


def _fill(rng, k):
    """A square or a ring (a square with a hole), somewhere on a 60 mm sheet."""
    x, y = rng.uniform(0, 50, 2)
    side = rng.uniform(4, 40)
    square = shapely.box(x, y, x + side, y + side)
    if k % 3 == 2:
        square = square.difference(shapely.box(x + side / 3, y + side / 3, x + 2 * side / 3,
                                               y + 2 * side / 3))
    return square


def _word(rng):
    """A number's strokes, a few short lines near a random spot."""
    x, y = rng.uniform(0, 60, 2)
    lines = [np.array([(x, y), (x + rng.uniform(0.5, 3), y + rng.uniform(-1, 3))]),
             np.array([(x + 1, y), (x + 1, y + rng.uniform(0.5, 3)), (x + 2, y + 2)])]
    return polylines_from_lines(lines, Style(COLOURS[rng.integers(5)], rng.uniform(0.1, 1.2)))


def _sheet(seed, n_fills, n_words, n_texts, plates):
    rng = np.random.default_rng(seed)
    fills = [polygons_from_shapely([_fill(rng, k)], Style(None, 0.0), [COLOURS[k % 5]])
             for k in range(n_fills)]
    shapes = []
    for k in range(n_words):
        word = _word(rng)
        if k < plates:  # a white plate round its strokes (their box, just or a bit wider)
            x0, y0 = word.coords.min(axis=0) - word.style.stroke_width / 2 - rng.uniform(0, 1)
            x1, y1 = word.coords.max(axis=0) + word.style.stroke_width / 2 + rng.uniform(0, 1)
            plate = shapely.box(x0, y0, x1, y1)
            shapes.append(polygons_from_shapely([plate], Style(None, 0.0), ["#ffffff"]))
        shapes.append(word)
    texts = [centred_text(tuple(rng.uniform(0, 60, 2)), "A7", rng.uniform(1, 6),
                          rng.uniform(-90, 90), COLOURS[k % 5]) for k in range(n_texts)]
    cover = polygons_from_shapely([_fill(rng, 0)], Style(None, 0.0), ["#101010"])
    return Sheet(60.0, 60.0, (Layer("paint", "paint", tuple(fills)),
                              Layer(lc.WORDS, "label", tuple(shapes)),
                              Layer("texts", "label", tuple(texts) + (Text(5, 5, "", 2.0),)),
                              Layer("arrows", "paint", (cover,))))


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(0, 12), st.integers(0, 12), st.integers(0, 4),
       st.integers(0, 4))
def test_all_labels_at_once_as_each_alone(seed, n_fills, n_words, n_texts, plates):
    sheet = _sheet(seed, n_fills, n_words, n_texts, plates)
    polys, fills = lc.filled(sheet)
    found = lc.labels(sheet)
    tree = shapely.STRtree(polys) if polys else None
    want = [lc.fills_under(polys, fills, tree, f.ink()) for f in found]
    assert lc._under(polys, fills, found) == want


def test_a_word_inside_one_fill_and_one_reaching_over_its_edge():
    """Inside: that fill alone; a stroke end half its width from the edge: the paper too."""
    square = polygons_from_shapely([shapely.box(0, 0, 20, 20)], Style(None, 0.0), ["#203060"])
    inside = polylines_from_lines([np.array([(5.0, 5.0), (10.0, 5.0)])], Style("#ffffff", 1.0))
    over = polylines_from_lines([np.array([(5.0, 10.0), (19.8, 10.0)])], Style("#ffffff", 1.0))
    sheet = Sheet(30.0, 30.0, (Layer("paint", "paint", (square,)),
                               Layer(lc.WORDS, "label", (inside, over))))
    polys, fills = lc.filled(sheet)
    assert lc._under(polys, fills, lc.labels(sheet)) == [["#203060"], ["#203060", lc.PAPER]]
