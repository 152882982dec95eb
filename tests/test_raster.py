"""``layout.raster``: a picture of fine lines has their ink (length times width, as grey) where
the lines are, in a box that holds them; checked against shapely's distances and lengths, not
against the sampling the rasteriser does."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from weavecut.layout import raster
from weavecut.layout.drawing import Polygons, Polylines, Raster, Style, polylines_from_lines

PITCH = 25.4 / raster.DPI


@st.composite
def fine_lines(draw):
    """A few random straight lines in a 6 mm square, a width that is a whole number of the
    rasteriser's grid steps (so the test's own arithmetic needs no rounding of it)."""
    n = draw(st.integers(1, 6))
    xy = np.array(draw(st.lists(st.tuples(*[st.floats(0, 6, allow_nan=False)] * 4),
                                min_size=n, max_size=n))).reshape(n, 2, 2)
    steps = draw(st.integers(2, raster.SUB))  # up to a pixel wide
    return Polylines(xy.reshape(-1, 2) + 3.0, np.arange(0, 2 * n + 1, 2),
                     Style("#000000", steps * PITCH / raster.SUB))


def _centres(r: Raster) -> np.ndarray:
    """(H, W, 2) every pixel's centre in mm."""
    h, w = r.pixels.shape
    cols = r.x + (np.arange(w) + 0.5) * r.width / w
    rows = r.y + r.height - (np.arange(h) + 0.5) * r.height / h  # row 0 at the top
    return np.stack(np.meshgrid(cols, rows), axis=-1)


@given(fine_lines())
def test_the_ink_is_where_the_lines_are(shape):
    r = raster.picture([shape])
    lines = shapely.multilinestrings(shape.coords.reshape(-1, 2, 2))
    inked = r.pixels < 255
    far = shapely.distance(shapely.points(_centres(r)[inked]), lines)
    # a pixel's centre is at most half its diagonal from ink in it (and the grid rounding)
    assert (far <= PITCH * (np.sqrt(0.5) + 1 / raster.SUB) + shape.style.stroke_width / 2
            ).all()
    # the midpoint of every line drawn longer than two pixels is inked (in its pixel or next)
    h, w = r.pixels.shape
    for a, b in shape.coords.reshape(-1, 2, 2):
        if np.hypot(*(b - a)) > 2 * PITCH:
            mid = (a + b) / 2
            col = int((mid[0] - r.x) / PITCH)
            row = int((r.y + r.height - mid[1]) / PITCH)
            assert inked[max(0, row - 1):row + 2, max(0, col - 1):col + 2].any(), (a, b)


@given(fine_lines())
def test_the_grey_is_the_share_of_each_pixel_the_lines_cover(shape):
    r = raster.picture([shape])
    length = shapely.length(shapely.linestrings(shape.coords.reshape(-1, 2, 2))).sum()
    area = length * shape.style.stroke_width / PITCH**2  # in pixels
    ink = (255 - r.pixels.astype(np.int64)).sum() / 255
    n = len(shape.coords) // 2
    # each pixel's grey is rounded (half a level); each line's ends are rounded to the grid
    # (its length to a grid step either way) and its length floored: 2 steps per line
    slack = 0.5 / 255 * (r.pixels < 255).sum() + 3 * n * shape.style.stroke_width / PITCH \
        / raster.SUB
    saturated = (r.pixels == 0).any()  # crossings may pass black, and are cut there
    assert ink <= area + slack
    if not saturated:
        assert ink >= area - slack


@given(fine_lines())
def test_the_box_holds_the_lines_on_the_pixel_grid(shape):
    r = raster.picture([shape])
    h, w = r.pixels.shape
    assert r.width == pytest.approx(w * PITCH, rel=1e-12)
    assert r.height == pytest.approx(h * PITCH, rel=1e-12)
    assert round(r.x, 3) == pytest.approx(r.x, abs=1e-9)  # the corner the writers write
    lo, hi = shape.coords.min(axis=0), shape.coords.max(axis=0)
    assert r.x <= lo[0] - PITCH and r.y <= lo[1] - PITCH
    assert r.x + r.width >= hi[0] + PITCH and r.y + r.height >= hi[1] + PITCH
    assert r.x + r.width <= hi[0] + 3 * PITCH  # no more than a pixel to spare, and rounding
    assert r.vector == (shape,)


def test_a_colour_inks_as_its_grey_and_a_ring_closes():
    square = Polygons(np.array([[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]]),
                      np.array([0, 4]), Style("#808080", PITCH / 2))
    black = Polygons(square.coords, square.ring_offsets, Style("#000000", PITCH / 2))
    grey, full = raster.picture([square]), raster.picture([black])
    ink = lambda r: (255 - r.pixels.astype(np.int64)).sum()  # noqa: E731
    assert ink(grey) == pytest.approx(ink(full) * (255 - 128) / 255, rel=0.02)
    # the closing side (1, 3) -> (1, 1) is drawn: the left column of the box has ink
    centres = _centres(full)
    left = np.abs(centres[..., 0] - 1.0) < PITCH / 2
    assert (full.pixels[left & (centres[..., 1] > 1.2) & (centres[..., 1] < 2.8)] < 255).all()


def test_what_a_picture_cannot_draw_is_refused():
    line = polylines_from_lines([[(0, 0), (1, 1)]], Style("#000000", 2 * PITCH))
    with pytest.raises(ValueError, match="wider than a pixel"):
        raster.picture([line])
    filled = Polygons(np.array([[0.0, 0], [1, 0], [0, 1]]), np.array([0, 3]),
                      Style(None, 0, fill="#ff0000"))
    with pytest.raises(ValueError, match="strokes only"):
        raster.picture([filled])


def test_too_fine_is_thinner_than_a_dot_or_too_many_segments():
    line = lambda width, n=1: polylines_from_lines(  # noqa: E731
        [np.c_[np.arange(n + 1), np.zeros(n + 1)]], Style("#000000", width))
    assert raster.too_fine([line(0.9 * PITCH)])
    assert not raster.too_fine([line(1.1 * PITCH)])
    assert not raster.too_fine([line(0.0)])  # a hairline is a cut line
    assert raster.too_fine([line(0.1, raster.MAX_SEGMENTS + 1)])
    assert not raster.too_fine([line(0.1, raster.MAX_SEGMENTS)])


def test_a_crop_is_the_pixels_in_the_window():
    pixels = np.arange(12 * 20, dtype=np.uint8).reshape(12, 20)
    r = Raster(10.0, 5.0, 20.0, 12.0, pixels)  # 1 mm pixels
    part = r.cropped(14.5, 6.5, 18.0, 9.2)
    # columns 4..7 (x 14-18); rows counted down from the top (y 17): y 9.2 is in row 7,
    # y 6.5 in row 10
    assert (part.x, part.y, part.width, part.height) == (14.0, 6.0, 4.0, 4.0)
    assert (part.pixels == pixels[7:11, 4:8]).all() and part.vector == ()
    assert r.cropped(0, 0, 9, 9) is None
    moved = part.moved(1.0, -2.0)
    assert (moved.x, moved.y) == (15.0, 4.0) and moved.pixels is not None
