"""The SVG writer's text against svgwrite's (the oracle, ``svgwrite_writer``): any drawing (one
sheet or several, of int or float sizes; lines, rings with holes, fills, texts turned or not,
hidden layers, names and texts with the characters XML escapes, empty shapes and lines) gets
the same bytes."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.export import svg
from weavecut.layout.drawing import (
    Drawing, Layer, Polygons, Polylines, Sheet, Style, Text,
)
from weavecut.text import clean

from tests.export import svgwrite_writer

words = st.text(alphabet=st.sampled_from(list("aZ 09&<>\"'é字-_;:\t\n")), max_size=8).map(clean)
colours = st.sampled_from(["#000000", "#ff0000", "#12ab9f"])
number = st.one_of(st.floats(-1e3, 1e3), st.integers(-50, 50))


@st.composite
def shapes(draw):
    kind = draw(st.sampled_from(["lines", "rings", "text"]))
    if kind == "text":
        return Text(draw(number), draw(number), draw(words), draw(st.floats(0.5, 9)),
                    draw(st.sampled_from(["start", "middle", "end"])),
                    draw(st.sampled_from([0, 0.0, 45, -12.5])), draw(colours))
    sizes = draw(st.lists(st.integers(0 if kind == "lines" else 1, 4), max_size=4))
    n = sum(sizes)
    coords = np.array(draw(st.lists(st.tuples(number, number), min_size=n, max_size=n)),
                      dtype=float).reshape(-1, 2)
    offsets = np.r_[0, np.cumsum(sizes)].astype(np.int64)
    style = Style(draw(st.one_of(st.none(), colours)), draw(st.sampled_from([0, 0.25, 1])),
                  draw(st.one_of(st.none(), colours)), draw(st.sampled_from([1.0, 0.4])))
    if kind == "lines":
        return Polylines(coords, offsets, style)
    holes = draw(st.booleans()) and len(sizes) > 1
    po = np.array([0, 1, len(sizes)], dtype=np.int64) if holes else None
    polygons = 2 if holes else len(sizes)
    fills = draw(st.one_of(st.none(), st.lists(colours, min_size=polygons,
                                                   max_size=polygons).map(tuple)))
    return Polygons(coords, offsets, style, po, fills)


layers = st.builds(Layer, words, st.sampled_from(["cut", "paint", "label", "guide"]),
                   st.lists(shapes(), max_size=3).map(tuple), st.booleans())
sheets = st.builds(Sheet, st.one_of(st.floats(1, 900), st.integers(1, 900)),
                   st.one_of(st.floats(1, 900), st.integers(1, 900)),
                   st.lists(layers, max_size=3).map(tuple), words)


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(st.lists(sheets, min_size=1, max_size=3), words,
       st.lists(st.tuples(words, words), max_size=2).map(tuple))
def test_the_same_text_as_svgwrite(sheets, title, metadata):
    drawing = Drawing(tuple(sheets), title, metadata)
    mine = svg.render(drawing)
    original = svg._document
    try:
        svg._document = svgwrite_writer.document
        theirs = svg.render(drawing)
    finally:
        svg._document = original
    assert mine == theirs
