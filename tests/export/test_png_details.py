"""PNG details probed pixel by pixel (Pillow decodes, positions worked out by hand, y up in the
model): lines at their width and colour, open lines left open and rings closed, polygons with
several holes, turned text about its anchor as SVG and PDF turn it, text kept within the
width the layout reserved, sheets of different widths stacked, and the text chunks."""

from __future__ import annotations

import io
import struct
import zlib

import numpy as np
import pytest
import shapely
from PIL import Image, ImageDraw

from weavecut.errors import ExportError
from weavecut.export import png
from weavecut.layout.drawing import (
    Drawing, Layer, Sheet, Style, Text, polygons_from_shapely, polylines_from_lines,
)
from weavecut.layout.labels import text_width

from tests.export.test_raster_readback import DPI, PX, at, close, ink

BLUE, GREEN, WHITE = (0, 0, 255), (0, 160, 0), (255, 255, 255)


def pixels(drawing: Drawing) -> np.ndarray:
    with Image.open(io.BytesIO(png.render(drawing, dpi=DPI))) as im:
        return np.asarray(im.convert("RGB"))


def test_lines_open_rings_closed_at_their_width():
    layers = (Layer("fold", "score", (polylines_from_lines(
        [[(5, 5), (5, 25), (25, 25)]], Style("#0000ff", 1.0, "#00a000")),)),
              Layer("cut", "cut", (polygons_from_shapely(
                  [shapely.Polygon([(35, 5), (55, 5), (55, 25)])],
                  Style("#0000ff", 1.0, None)),)))
    img = pixels(Drawing((Sheet(60, 30, layers),)))
    for x, y in [(5, 15), (15, 25), (45, 5), (55, 15), (45, 15)]:  # on every drawn edge
        assert close(at(img, x, y, 30), BLUE, 30), (x, y)
    assert at(img, 15, 15, 30) == WHITE  # the open line is open: not joined, not filled
    assert at(img, 50, 10, 30) == WHITE  # the ring's inside: no fill
    # a 1 mm line is 4 px wide at 4 px/mm
    row = img[int((30 - 15) * PX), :10 * PX]
    assert (row[:, 2] - row[:, 0] > 128).sum() == pytest.approx(4, abs=1)


@pytest.mark.parametrize("kind", ["line", "ring"])
def test_a_hairline_is_the_thinnest_line_drawn_and_still_seen(kind):
    """Stroke width 0 is a hairline (what a laser cuts on): visible, and thinner than a stroke
    of 0.25 mm (two pixels of the supersampled picture at 4 px/mm)."""
    def ink_of(width):
        shape = (polylines_from_lines([[(2, 5), (28, 5)]], Style("#000000", width))
                 if kind == "line" else
                 polygons_from_shapely([shapely.box(2, 3, 28, 7)], Style("#000000", width)))
        img = pixels(Drawing((Sheet(30, 10, (Layer("cut", "cut", (shape,)),)),)))
        return (255 - img[:, 10 * PX:20 * PX].astype(int)).sum()

    hairline, quarter = ink_of(0.0), ink_of(0.25)
    assert 0 < hairline < 0.75 * quarter


def test_polygon_with_two_holes_keeps_both_open():
    frame = shapely.Polygon([(2, 2), (38, 2), (38, 18), (2, 18)],
                            [[(5, 5), (15, 5), (15, 15), (5, 15)],
                             [(25, 5), (35, 5), (35, 15), (25, 15)]])
    layer = Layer("tiles", "paint", (polygons_from_shapely(
        [frame], Style("#0000ff", 0.5), fills=["#00a000"]),))
    img = pixels(Drawing((Sheet(40, 20, (layer,)),)))
    assert close(at(img, 20, 10, 20), GREEN) and close(at(img, 3.5, 10, 20), GREEN)
    assert at(img, 10, 10, 20) == WHITE and at(img, 30, 10, 20) == WHITE
    for x, y in [(5, 10), (15, 10), (25, 10), (35, 10), (2, 10), (38, 10)]:
        assert close(at(img, x, y, 20), BLUE, 60), (x, y)  # every ring stroked
    assert at(img, 1, 1, 20) == WHITE


@pytest.mark.parametrize("anchor", ["start", "middle", "end"])
def test_turned_text_turns_about_its_anchor(anchor):
    # a line of capitals 2 mm high turned 90 degrees about (20, 20): it runs upwards from
    # (start), through (middle) or up to (end) the anchor, left of the anchor's vertical
    text = "HHHHHHHH"
    layer = Layer("l", "label", (Text(20, 20, text, 2.0, anchor, 90.0),))
    found = ink(pixels(Drawing((Sheet(40, 40, (layer,)),))), 0, 0, 40, 40, 40)
    lo, hi = found[:, 1].min(), found[:, 1].max()
    assert {"start": lo, "middle": (lo + hi) / 2, "end": hi}[anchor] == \
        pytest.approx(20, abs=0.6)
    assert hi - lo > 0.8 * text_width(text, 2.0)  # the whole line
    assert found[:, 0].max() == pytest.approx(20, abs=0.3)  # the baseline is x = 20
    assert found[:, 0].min() == pytest.approx(18, abs=0.4)  # capitals 2 mm high


@pytest.mark.parametrize("anchor", ["start", "middle", "end"])
def test_upright_text_stands_on_its_baseline_at_its_anchor(anchor):
    layer = Layer("l", "label", (Text(20, 10, "HHHH", 2.5, anchor),))
    found = ink(pixels(Drawing((Sheet(40, 20, (layer,)),))), 0, 0, 40, 20, 20)
    x0, x1 = found[:, 0].min(), found[:, 0].max()
    centre = {"start": x0, "middle": (x0 + x1) / 2, "end": x1}[anchor]
    assert centre == pytest.approx(20, abs=0.6)
    assert found[:, 1].min() == pytest.approx(10, abs=0.3)
    assert found[:, 1].max() == pytest.approx(12.5, abs=0.4)


def test_text_stays_within_the_width_the_layout_reserved():
    # DejaVu Sans runs wider than the Helvetica widths the layout reserves for some words
    for word in ("mmmmmmmm", "HHHHHHHH"):
        layer = Layer("l", "label", (Text(2, 10, word, 3.0),))
        found = ink(pixels(Drawing((Sheet(60, 20, (layer,)),))), 0, 0, 60, 20, 20)
        width = np.ptp(found[:, 0])
        assert 0.8 * text_width(word, 3.0) < width <= text_width(word, 3.0) + 0.25, word


@pytest.mark.parametrize("word, size", [("HIH", 0.12), ("mm", 0.125)])
def test_tiny_text_keeps_to_its_size_and_width_down_to_a_one_pixel_font(word, size):
    """At 150 dpi a text an eighth of a millimetre high is under two pixels to the em: the
    font (whole pixels, one at least) is no larger than the em asked for and runs no wider
    than the layout reserved unless it is down to one pixel ("mm": DejaVu Sans at two pixels
    would not fit). The font is asked of the writer itself: the pixels are too few to
    measure."""
    px = 150 / 25.4 * png.SUPERSAMPLE
    em = size / png.CAP_RATIO * px
    room = text_width(word, size) * px
    font = png._font(word, size, px)
    assert font.size <= max(1.0, em)
    assert font.size == 1 or font.getlength(word) <= room  # one pixel is the least there is


def test_sheets_of_different_widths_stack_left_aligned():
    a = Sheet(20, 10, (Layer("a", "paint", (polygons_from_shapely(
        [shapely.box(0, 0, 20, 10)], Style(None, 0, "#0000ff")),)),))
    b = Sheet(30, 5, (Layer("b", "paint", (polygons_from_shapely(
        [shapely.box(0, 0, 30, 5)], Style(None, 0, "#00a000")),)),))
    img = pixels(Drawing((a, b, a)))
    assert img.shape == (25 * PX + 20, 30 * PX, 3)
    assert close(img[5, 5], BLUE) and (img[:10 * PX, 20 * PX + 1:] == 255).all()
    assert (img[10 * PX:10 * PX + 10] == 255).all()
    assert close(img[10 * PX + 12, 30 * PX - 2], GREEN)
    assert close(img[-3, 3], BLUE) and (img[-10 * PX:, 20 * PX + 1:] == 255).all()
    third = 15 * PX + 20  # the third sheet's first row: two sheets and two 10 px gaps above
    assert (img[third - 10:third] == 255).all() and close(img[third + 1, 3], BLUE)


def chunks(data: bytes) -> list[tuple[bytes, bytes]]:
    """(type, body) of every PNG chunk, each CRC checked."""
    out, pos = [], 8
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        assert struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0] == zlib.crc32(kind + body)
        out.append((kind, body))
        pos += 12 + n
    return out


def test_text_chunks_latin1_or_utf8_after_the_header():
    drawing = Drawing((Sheet(5, 5),), "café", (("generator", "weave-cut"),
                                                ("command", "weave-cut x → y")))
    data = png.render(drawing)
    found = chunks(data)
    assert [k for k, _ in found[:4]] == [b"IHDR", b"tEXt", b"tEXt", b"iTXt"]
    assert found[1][1] == "Title\0café".encode("latin-1")
    assert found[3][1] == b"command\0\0\0\0\0" + "weave-cut x → y".encode("utf-8")
    with Image.open(io.BytesIO(data)) as im:
        assert im.text == {"Title": "café", "generator": "weave-cut",
                           "command": "weave-cut x → y"}
    with pytest.raises(ExportError) as err:
        png.with_text(b"GIF89a" + bytes(40), [("Title", "x")])
    assert str(err.value) == "not a PNG stream"
    assert png.with_text(data, []) == data


def test_default_resolution_is_150_dpi():
    with Image.open(io.BytesIO(png.render(Drawing((Sheet(25.4, 50.8),))))) as im:
        assert im.size == (150, 300)
        assert im.info["dpi"] == pytest.approx((150, 150), abs=0.02)  # stored per metre


def test_a_hidden_layer_hides_only_itself():
    hidden = Layer("help", "guide", (polygons_from_shapely([shapely.box(0, 0, 10, 10)],
                                                           Style(None, 0, "#000000")),),
                   visible=False)
    shown = Layer("tiles", "paint", (polygons_from_shapely([shapely.box(10, 0, 20, 10)],
                                                           Style(None, 0, "#0000ff")),))
    img = pixels(Drawing((Sheet(20, 10, (hidden, shown)),)))
    assert at(img, 5, 5, 10) == WHITE and close(at(img, 15, 5, 10), BLUE)


def test_thick_lines_turn_round_corners():
    # a 2 mm line turning a right angle at (10, 10): a round join leaves the far corner of
    # the square a mitre would fill white
    corner = Layer("cut", "cut", (polylines_from_lines(
        [[(10, 18), (10, 10), (18, 10)]], Style("#0000ff", 2.0)),))
    with Image.open(io.BytesIO(png.render(Drawing((Sheet(20, 20, (corner,)),)),
                                          dpi=25.4 * 20))) as im:
        img = np.asarray(im.convert("RGB"))
    probe = lambda x, y: tuple(img[int((20 - y) * 20), int(x * 20)].tolist())  # noqa: E731
    assert close(probe(9.5, 9.5), BLUE, 30) and close(probe(10, 14), BLUE, 30)
    assert probe(9.1, 9.1) == WHITE


@pytest.mark.parametrize("angle", [90.0, -45.0])
def test_a_narrow_turned_text_is_drawn_whole(angle):
    # one tall, narrow letter turned about its baseline start: all of its 5 mm shows
    layer = Layer("l", "label", (Text(10, 10, "I", 5.0, "start", angle),))
    with Image.open(io.BytesIO(png.render(Drawing((Sheet(20, 20, (layer,)),)),
                                          dpi=25.4 * 10))) as im:
        img = np.asarray(im.convert("RGB"))
    rows, cols = np.nonzero(img.max(axis=2) < 128)
    x, y = (cols + 0.5) / 10, 20 - (rows + 0.5) / 10
    along = (x - 10) * np.cos(np.radians(angle + 90)) + (y - 10) * np.sin(np.radians(angle + 90))
    assert along.max() == pytest.approx(5.0, abs=0.3) and along.min() == pytest.approx(0, abs=0.3)


def test_capitals_are_as_high_as_the_text_size():
    layer = Layer("l", "label", (Text(2, 5, "HHHH", 5.0),))
    with Image.open(io.BytesIO(png.render(Drawing((Sheet(40, 15, (layer,)),)),
                                          dpi=25.4 * 20))) as im:
        img = np.asarray(im.convert("RGB"))
    rows = np.flatnonzero((img.max(axis=2) < 128).any(axis=1))
    assert (rows[-1] - rows[0] + 1) / 20 == pytest.approx(5.0, abs=0.15)


@pytest.mark.parametrize("anchor", ["ls", "ms"])
@pytest.mark.parametrize("angle", [30.0, 135.0])
def test_turned_text_loses_no_ink_even_at_the_corners_of_its_box(anchor, angle):
    """A full block (ink to the corners of its box) turned about its anchor: the same pixels
    as the text drawn on a canvas far larger than it and turned by Pillow about the same
    point, so the writer's tile cuts nothing off."""
    font = png._face(40)
    size, centre = 480, (240, 240)
    big = Image.new("RGBA", (size, size), (0, 0, 0, 0))
    ImageDraw.Draw(big).text(centre, "\u2588", fill="#000000", font=font, anchor=anchor)
    big = big.rotate(angle, center=centre)
    want = Image.new("RGB", (size, size), "white")
    want.paste(big, (0, 0), big)
    got = Image.new("RGB", (size, size), "white")
    png._rotated_text(got, centre, "\u2588", font, "#000000", angle, anchor)
    assert (np.asarray(want) < 128).any()  # something is drawn
    np.testing.assert_array_equal(np.asarray(got), np.asarray(want))


def test_thick_rings_turn_round_corners_at_every_corner():
    # a 2 mm outline of a square, as SVG draws it (stroke-linejoin round): just outside each
    # corner, within 1 mm of it, is ink, and the far corner of the mitre square is white; also
    # at the corner where the ring starts and ends
    ring = Layer("cut", "cut", (polygons_from_shapely([shapely.box(5, 5, 15, 15)],
                                                      Style("#0000ff", 2.0)),))
    with Image.open(io.BytesIO(png.render(Drawing((Sheet(20, 20, (ring,)),)),
                                          dpi=25.4 * 20))) as im:
        img = np.asarray(im.convert("RGB"))
    probe = lambda x, y: tuple(img[int((20 - y) * 20), int(x * 20)].tolist())  # noqa: E731
    for x, y in [(5, 5), (15, 5), (15, 15), (5, 15)]:
        sx, sy = np.sign(x - 10), np.sign(y - 10)  # outwards
        assert close(probe(x + 0.5 * sx, y + 0.5 * sy), BLUE, 30), (x, y)
        assert probe(x + 0.9 * sx, y + 0.9 * sy) == WHITE, (x, y)


def test_an_unstroked_line_draws_nothing():
    # a line with no stroke over a blue square leaves the square as it is, as in SVG
    square = polygons_from_shapely([shapely.box(2, 2, 18, 8)], Style(None, 0.0, "#0000ff"))
    line = polylines_from_lines([[(1, 5), (19, 5)], [(10, 1), (10, 9)]], Style(None, 1.0))
    alone, crossed = (pixels(Drawing((Sheet(20, 10, (Layer("cut", "cut", shapes),)),)))
                      for shapes in [(square,), (line, square)])
    assert (alone == crossed).all()


def test_shapes_after_a_text_or_a_line_are_drawn():
    # a text, a line, then a square in the same layer: the square is drawn
    shapes = (Text(2, 2, "A", 2.0), polylines_from_lines([[(1, 9), (9, 9)]], Style()),
              polygons_from_shapely([shapely.box(10, 2, 18, 8)], Style(None, 0.0, "#0000ff")))
    img = pixels(Drawing((Sheet(20, 10, (Layer("cut", "cut", shapes),)),)))
    assert close(at(img, 14, 5, 10), BLUE)


@pytest.mark.parametrize("width, dpi", [(0.05, 150), (1.0, 10), (0.3, 150), (7.0, 15)])
def test_a_sheet_is_its_size_at_the_resolution_to_within_a_pixel(width, dpi):
    # down to sheets smaller than a pixel, which still make a one-pixel image
    sheet = Sheet(width, width)
    with Image.open(io.BytesIO(png.render(Drawing((sheet,)), dpi=dpi))) as im:
        size = im.size
    want = width / 25.4 * dpi
    assert all(n >= 1 and abs(n - max(want, 1)) < 1 for n in size), (size, want)


def lanczos_halved(img: np.ndarray) -> np.ndarray:
    """``img`` (H, W, 3) uint8, H and W even, halved each way with the Lanczos filter (three
    lobes, widened twice for the reduction) from its definition: sinc(x) sinc(x / 3) for
    |x| < 3, weights normalised per output pixel, rows first then columns, each pass rounded
    to 8 bits as Pillow rounds them (within 1 of Pillow's fixed point)."""
    out = img.astype(float)
    for axis in (1, 0):
        n = out.shape[axis]
        x = (np.arange(n) + 0.5 - (np.arange(n // 2)[:, None] + 0.5) * 2) / 2
        w = np.where(np.abs(x) < 3, np.sinc(x) * np.sinc(x / 3), 0.0)
        w /= w.sum(axis=1, keepdims=True)
        out = np.clip(np.round(np.moveaxis(np.tensordot(w, out, axes=([1], [axis])), 0, axis)),
                      0, 255)
    return out.astype(np.uint8)


def test_a_sheet_is_drawn_at_twice_the_resolution_and_halved_with_lanczos(monkeypatch):
    # the drawing drawn without supersampling at twice the resolution, then halved by the
    # filter's definition: the PNG, to within rounding (other filters differ by 10 or more)
    shapes = (polygons_from_shapely([shapely.Polygon([(2, 2), (17, 3), (9, 9)])],
                                    Style("#000000", 0.5, "#127a7a")),
              polylines_from_lines([[(1, 8), (19, 1)]], Style("#c81e1e", 0.0)),
              Text(11, 6, "Ag", 2.0))
    drawing = Drawing((Sheet(20, 10, (Layer("cut", "cut", shapes),)),))
    img = pixels(drawing)
    monkeypatch.setattr(png, "SUPERSAMPLE", 1)
    with Image.open(io.BytesIO(png.render(drawing, dpi=2 * DPI))) as im:
        twice = np.asarray(im.convert("RGB"))
    assert np.abs(img.astype(int) - lanczos_halved(twice)).max() <= 1


def test_an_unstroked_shapes_stroke_width_plays_no_part():
    # as in SVG, where stroke="none" leaves stroke-width unread: even an infinite one
    square = [shapely.box(2, 2, 18, 8)]
    a, b = (pixels(Drawing((Sheet(20, 10, (Layer("cut", "cut", (polygons_from_shapely(
        square, Style(None, width, "#0000ff")),)),)),))) for width in (0.2, float("inf")))
    assert (a == b).all()
