"""Clipping a printed page's window: what tiling keeps of every line is what GEOS's
intersection with the window gives, to the last bit, whether GEOS is asked (lines across the
edge, lines that touch or cross themselves, closed ones, ones with a point twice in a row)
or the line is kept as it is (simple, open, strictly inside); a layer's shapes clipped
together are each clipped as alone; and a word is printed whole or not at all."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout.drawing import Drawing, Layer, Sheet, Style, Text, polygons_from_rings
from weavecut.layout.drawing import polylines_from_lines
from weavecut.layout.label_checks import WORDS
from weavecut.layout.tiling import _clip, _cover, grid, tile, word_overlap

inside = st.sampled_from([1.0, 2.0, 3.0, 5.5, 9.5])  # a coarse grid: repeats and crossings
point = st.one_of(st.tuples(inside, inside), st.tuples(
    st.sampled_from([0.0, -0.0, 10.0, 11.0, 2.0]), st.floats(-1.0, 11.0)))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.lists(point, min_size=2, max_size=6), max_size=8), st.booleans())
def test_lines_kept_as_geos_clips_them(lines, close):
    geoms = np.array([shapely.LineString(line + line[:1] if close else line) for line in lines],
                     dtype=object)
    window = shapely.box(0.0, 0.0, 10.0, 10.0)
    got = _clip(geoms, shapely.bounds(geoms).reshape(-1, 4), window, True)
    want = shapely.intersection(geoms, window)
    for g, w in zip(got, want):
        assert shapely.get_type_id(g) == shapely.get_type_id(w)
        assert np.array_equal(shapely.get_coordinates(g), shapely.get_coordinates(w))
        assert shapely.equals_exact(g, w, tolerance=0.0) or (g.is_empty and w.is_empty)


def _key(shape) -> tuple:
    """A shape as comparable values: every field, arrays by their bytes."""
    return (type(shape).__name__, *((v.dtype.str, v.shape, v.tobytes())
                                   if isinstance(v, np.ndarray) else v
                                   for v in vars(shape).values()))


square = st.tuples(st.floats(0.0, 400.0), st.floats(0.0, 400.0), st.floats(1.0, 60.0))
fill = st.sampled_from(["#aa0000", "#00aa00", "#0000aa"])


@settings(max_examples=25, deadline=None)
@given(st.lists(st.lists(st.tuples(square, fill), min_size=1, max_size=4), min_size=1,
                max_size=4),
       st.lists(st.lists(st.tuples(square, square), min_size=1, max_size=3), max_size=3),
       st.lists(square, max_size=4), st.booleans())
def test_a_layer_clipped_at_once_is_its_shapes_clipped_each_alone(polys, lines, words, fills):
    """tile clips all the shapes of a layer together: every page holds, shape for shape and
    byte for byte, what it holds when each shape is a layer of its own (fills follow their
    polygons, lines and words stay with their shapes, in order)."""
    def ring(x, y, s):
        return np.array([[x, y], [x + s, y], [x + s, y + s], [x, y + s]])

    layers = []
    for group in polys:
        layers.append(("paint", "paint", polygons_from_rings(
            [ring(*sq) for sq, _ in group], Style(None, 0.0, "#ffffff"),
            [f for _, f in group] if fills else None)))
        layers.append(("paint", "paint", Text(*group[0][0][:2], "a", 2.0)))
    for group in lines:
        layers.append(("lines", "guide", polylines_from_lines(
            [np.array([a[:2], b[:2], (b[0], a[1])]) for a, b in group], Style("#000000", 0.2))))
    for x, y, s in words:
        layers.append((WORDS, "label", polygons_from_rings([ring(x, y, s / 4)])))
        layers.append((WORDS, "label", polylines_from_lines(
            [np.array([[x, y], [x + s / 4, y + s / 4]])], Style("#000000", 0.4))))
    together, alone = [], []
    for name, role, shape in layers:
        if together and together[-1].name == name:
            together[-1] = Layer(name, role, together[-1].shapes + (shape,))
        else:
            together.append(Layer(name, role, (shape,)))
        alone.append(Layer(name, role, (shape,)))
    a, b = (tile(Drawing((Sheet(500.0, 500.0, tuple(ls)),), "t"), (210.0, 297.0), 12.0).sheets
            for ls in (together, alone))
    assert len(a) == len(b)
    for page_a, page_b in zip(a, b):
        assert [_key(s) for layer in page_a.layers for s in layer.shapes] == \
            [_key(s) for layer in page_b.layers for s in layer.shapes]


def test_a_word_is_on_a_page_whole_inside_its_window_or_left_to_the_next():
    # words of every length on a 3 mm grid, so that many cross a window's edge; each is known
    # by its length (0.01 mm apart)
    words = [np.array([[x, y], [x + 1 + 0.01 * k, y]]) for k, (x, y) in enumerate(
        (x, y) for x in np.arange(5.0, 495.0, 3.0) for y in np.arange(5.0, 495.0, 29.0))]
    drawing = Drawing((Sheet(500.0, 500.0, tuple(Layer(WORDS, "label", (polylines_from_lines(
        [w], Style("#000000", 0.4)),)) for w in words)),), "t")
    page, overlap = (210.0, 297.0), word_overlap(drawing)
    margin = grid(_cover(drawing.sheets[0]), page, overlap, 10.0)[2]  # the window's, on a page
    seen = set()
    for sheet in tile(drawing, page, overlap, 10.0).sheets:
        for layer in sheet.layers:
            for shape in layer.shapes if layer.name == WORDS else ():
                (x0, y0), (x1, y1) = shape.coords.min(axis=0), shape.coords.max(axis=0)
                assert x0 - 0.2 >= margin and y0 - 0.2 >= margin  # its ink, on the window
                assert x1 + 0.2 <= page[0] - margin and y1 + 0.2 <= page[1] - margin
                seen.add(round((x1 - x0 - 1) / 0.01))
    assert seen == set(range(len(words)))
