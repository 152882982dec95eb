"""PDF details read back by poppler (pdfinfo for pages and metadata, pdftoppm pixels probed
where the Drawing puts things, y up): every page at its sheet's size in points, lines in their
colour, width and opacity and never filled, fills without a stray outline, rounded corners,
text anchored and sized, the same bytes every time."""

from __future__ import annotations

import io
import subprocess

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from PIL import Image
from reportlab.pdfgen.pathobject import PDFPathObject

from weavecut.export import pdf, png
from weavecut.layout.drawing import (
    Drawing, Layer, Sheet, Style, Text, polygons_from_shapely, polylines_from_lines,
)

from tests.export.test_raster_readback import PX, at, close
from tests.test_readback import page_sizes, pdfinfo, program

MM = 72 / 25.4  # points per millimetre
BLUE, GREEN, WHITE = (0, 0, 255), (0, 160, 0), (255, 255, 255)


def pages(drawing: Drawing, tmp_path, px: float = PX) -> list[np.ndarray]:
    path = tmp_path / "d.pdf"
    path.write_bytes(pdf.render(drawing))
    subprocess.run([program("pdftoppm"), "-r", f"{25.4 * px}", "-png", str(path),
                    str(tmp_path / "p")], check=True)
    return [np.asarray(Image.open(f).convert("RGB")) for f in sorted(tmp_path.glob("p-*.png"))]


def test_every_page_at_its_sheet_size_in_points(tmp_path):
    sheets = (Sheet(210, 297), Sheet(100, 50), Sheet(50, 100))
    path = tmp_path / "s.pdf"
    path.write_bytes(pdf.render(Drawing(sheets, "sizes")))
    info = pdfinfo(path)
    assert info["Pages"] == "3"
    got = sorted(page_sizes(info))
    want = sorted((s.width * MM, s.height * MM) for s in sheets)
    np.testing.assert_allclose(got, want, atol=0.01)
    sizes = [tuple(map(float, info[f"Page    {n} size"].split()[0:3:2])) for n in (1, 2, 3)]
    np.testing.assert_allclose(sizes, [(s.width * MM, s.height * MM) for s in sheets],
                               atol=0.01)  # in order: page n is sheet n


def test_metadata_defaults_without_generator_or_command(tmp_path):
    path = tmp_path / "m.pdf"
    path.write_bytes(pdf.render(Drawing((Sheet(10, 10),), "plain")))
    info = pdfinfo(path)
    assert (info["Title"], info["Creator"], info["Producer"]) == \
        ("plain", "weave-cut", "weave-cut")
    assert info.get("Subject", "") == ""


def test_same_bytes_every_time():
    drawing = Drawing((Sheet(30, 20, (Layer("l", "label", (Text(5, 5, "x", 3.0),)),)),), "t",
                      (("generator", "g"), ("command", "c")))
    assert pdf.render(drawing) == pdf.render(drawing)


def test_page_streams_are_deflated_binary_and_read_back(tmp_path):
    """Every stream is FlateDecode alone (reportlab's default wraps pages in ASCII85 too, a
    fifth larger) and inflates to the page's operators: planted, useA85 back on fails."""
    import re
    import zlib

    drawing = Drawing((Sheet(30, 20, (Layer("l", "paint", (polygons_from_shapely(
        [shapely.box(2, 2, 12, 8)], Style("#0000ff", 0.5, "#00a000")),)),)),), "t")
    data = pdf.render(drawing)
    filters = re.findall(rb"/Filter\s*(\[[^\]]*\]|/\w+)", data)
    assert filters and all(f.strip(b"[] ") == b"/FlateDecode" for f in filters)
    body = data[data.index(b"stream", data.index(b"/Filter")) + 6:].lstrip(b"\r\n")
    assert b"n 12 2 m 12 8 l 2 8 l 2 2 l h\nB*" in zlib.decompressobj().decompress(body)


def test_lines_in_colour_width_and_opacity_never_filled(tmp_path):
    # a V of a 2 mm blue line whose style also names a fill: the V's inside stays white
    vee = Layer("fold", "score", (polylines_from_lines(
        [[(5, 25), (15, 5), (25, 25)]], Style("#0000ff", 2.0, "#00a000")),))
    faint = Layer("guide", "guide", (polylines_from_lines(
        [[(30, 15), (55, 15)]], Style("#0000ff", 2.0, None, 0.5)),))
    (img,) = pages(Drawing((Sheet(60, 30, (vee, faint)),)), tmp_path)
    assert close(at(img, 10, 15, 30), BLUE, 30)  # on the V's left arm
    assert at(img, 15, 20, 30) == WHITE  # inside the V
    row = img[int((30 - 10) * PX), :15 * PX]  # across the left arm at y = 10
    assert (row[:, 2] - row[:, 0] > 128).sum() == pytest.approx(2 * PX / np.cos(
        np.arctan(0.5)), abs=2)  # 2 mm wide, cut at a slant
    assert close(at(img, 40, 15, 30), (128, 128, 255), 12)  # half opaque: light blue


def test_fills_without_an_outline_and_outlines_around_fills(tmp_path):
    bare = Layer("tiles", "paint", (polygons_from_shapely(
        [shapely.box(5, 5, 15, 15)], Style(None, 2.0, "#00a000")),))
    edged = Layer("cut", "cut", (polygons_from_shapely(
        [shapely.box(25, 5, 35, 15), shapely.box(45, 5, 55, 15)], Style("#0000ff", 1.0),
        fills=["#00a000", None]),))
    (img,) = pages(Drawing((Sheet(60, 20, (bare, edged)),)), tmp_path)
    assert close(at(img, 10, 10, 20), GREEN) and close(at(img, 5.2, 10, 20), GREEN)
    assert at(img, 4.6, 10, 20) == WHITE  # no stroke in a colour the style does not name
    assert close(at(img, 30, 10, 20), GREEN) and close(at(img, 25, 10, 20), BLUE, 30)
    assert at(img, 50, 10, 20) == WHITE and close(at(img, 45, 10, 20), BLUE, 30)


def test_overlapping_polygons_of_a_batch_stack_as_in_the_png(tmp_path):
    """An unfilled square and a filled one after it, overlapping: the fill covers the first
    square's outline where they overlap, in the PDF as in the PNG (which draws polygon by
    polygon), so the printed page shows what the preview shows."""
    batch = Layer("cut", "cut", (polygons_from_shapely(
        [shapely.box(5, 5, 25, 15), shapely.box(15, 5, 35, 15)], Style("#0000ff", 1.0),
        fills=[None, "#00a000"]),))
    drawing = Drawing((Sheet(40, 20, (batch,)),))
    (img,) = pages(drawing, tmp_path)
    with Image.open(io.BytesIO(png.render(drawing, dpi=25.4 * PX))) as im:
        preview = np.asarray(im.convert("RGB"))
    for picture in (img, preview):
        assert close(at(picture, 25, 10, 20), GREEN)  # the first square's edge, under the fill
        assert close(at(picture, 5, 10, 20), BLUE, 30) and close(at(picture, 35, 10, 20), BLUE, 30)


def test_corners_are_rounded(tmp_path):
    # a 2 mm line turning a right angle at (10, 10): a mitred corner fills the square out to
    # (9, 9), a round one leaves its far corner white
    corner = Layer("cut", "cut", (polylines_from_lines(
        [[(10, 18), (10, 10), (18, 10)]], Style("#0000ff", 2.0)),))
    (img,) = pages(Drawing((Sheet(20, 20, (corner,)),)), tmp_path, px=20)
    probe = lambda x, y: tuple(img[int((20 - y) * 20), int(x * 20)].tolist())  # noqa: E731
    assert close(probe(9.5, 9.5), BLUE, 30)  # inside the round join
    assert probe(9.1, 9.1) == WHITE  # beyond it, where a mitre would reach


@pytest.mark.parametrize("anchor", ["start", "middle", "end"])
def test_text_anchored_on_its_baseline_at_cap_height(anchor, tmp_path):
    layer = Layer("l", "label", (Text(20, 10, "HHHH", 5.0, anchor, 0.0, "#700000"),))
    (img,) = pages(Drawing((Sheet(40, 20, (layer,)),)), tmp_path, px=10)
    rows, cols = np.nonzero(img.max(axis=2) < 200)
    x, y = (cols + 0.5) / 10, 20 - (rows + 0.5) / 10  # pixel centres, mm, y up
    x0, x1 = x.min(), x.max()
    assert {"start": x0, "middle": (x0 + x1) / 2, "end": x1}[anchor] == \
        pytest.approx(20, abs=0.8)  # within the side bearing of H (0.08 em)
    assert x1 - x0 > 10  # four capitals
    assert y.min() == pytest.approx(10, abs=0.2)  # standing on the baseline
    assert y.max() == pytest.approx(15, abs=0.2)  # 5 mm capitals: Helvetica's are 0.72 em
    darkest = img.reshape(-1, 3)[img.reshape(-1, 3).sum(axis=1).argmin()]
    assert close(darkest, (0x70, 0, 0), 20)  # in its own colour


@settings(max_examples=100, deadline=None)
@given(st.lists(st.lists(st.tuples(*[st.one_of(st.floats(-1e4, 1e4), st.sampled_from(
    [0.0, -0.0, 1e-8, 0.5, -1.0, 123456.789]))] * 2), min_size=1, max_size=6), max_size=5),
    st.booleans())
def test_paths_are_what_reportlabs_path_operators_write(rings, close):
    # the writer formats every number of a shape at once; reportlab's moveTo, lineTo and close
    # on the same points are the oracle
    coords = np.array([p for r in rings for p in r], dtype=float).reshape(-1, 2)
    offsets = np.r_[0, np.cumsum([len(r) for r in rings])].tolist()
    want = PDFPathObject()
    for ring in rings:
        want.moveTo(*np.array(ring[0], dtype=float))
        for x, y in np.array(ring[1:], dtype=float).reshape(-1, 2).tolist():
            want.lineTo(x, y)
        if close:
            want.close()
    got = pdf._path(pdf._points(coords), zip(offsets[:-1], offsets[1:]), close)
    assert got.getCode() == want.getCode()
