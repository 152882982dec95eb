"""PNG and PDF writers put every colour where the Drawing says: the PNG decoded by Pillow, the
PDF rasterised by poppler's pdftoppm (what a print shop's viewer shows), both at 4 pixels per
mm, and probed pixel by pixel (fills, holes, strokes, hidden layers, sheet placement, text
position, anchor, size and angle) against positions worked out by hand from the model (y up)."""

from __future__ import annotations

import io
import subprocess

import numpy as np
import pytest
import shapely
from PIL import Image

from weavecut.errors import ExportError
from weavecut.export import dxf, pdf, png, svg
from weavecut.layout.drawing import (
    Drawing, Layer, Polygons, Sheet, Style, Text, polygons_from_rings, polygons_from_shapely,
)

from tests.test_readback import pdfinfo, program

PX = 4  # pixels per mm: 101.6 dpi
DPI = 25.4 * PX
TEAL, SAND, RED, INK = (0x12, 0x7A, 0x7A), (0xE0, 0xC0, 0x80), (0xFF, 0, 0), (0x10, 0x20, 0x30)
WHITE = (255, 255, 255)


def hexc(rgb) -> str:
    return "#" + "".join(f"{c:02x}" for c in rgb)


FRAME = shapely.Polygon([(5, 5), (25, 5), (25, 25), (5, 25)],
                        [[(10, 10), (20, 10), (20, 20), (10, 20)]])


def drawing() -> Drawing:
    """Sheet 1 (60 x 40 mm): a teal frame with a hole and a sand triangle (half opaque), a red
    cut square, a line of text turned 30 degrees, text anchored at its end, a hidden black
    block. Sheet 2 (30 x 20 mm): a red square."""
    tiles = Layer("tiles", "paint", (polygons_from_shapely(
        [FRAME, shapely.Polygon([(30, 25), (40, 25), (30, 35)])], Style(None, 0.0, None, 0.5),
        fills=[hexc(TEAL), hexc(SAND)]),))
    cut = Layer("cut", "cut", (polygons_from_shapely([shapely.box(30, 5, 55, 20)],
                                                     Style(hexc(RED), 0.5)),))
    labels = Layer("labels", "label", (
        Text(45, 30, "HHHHHHHH", 2.0, "middle", 30.0, hexc(INK)),
        Text(25, 35, "HIH", 3.0, "end", 0.0, hexc(INK))))
    hidden = Layer("hidden", "guide", (polygons_from_rings(
        [np.array([[32.0, 8], [52, 8], [52, 17], [32, 17]])], Style(None, 0, "#000000")),),
        visible=False)
    back = Layer("back", "paint", (polygons_from_shapely([shapely.box(2, 2, 12, 12)],
                                                         Style(None, 0, hexc(RED))),))
    return Drawing((Sheet(60, 40, (tiles, cut, labels, hidden)), Sheet(30, 20, (back,))),
                   "raster", (("generator", "test"), ("command", "x")))


def at(img: np.ndarray, x: float, y: float, height: float) -> tuple[int, ...]:
    """The pixel at model point (x, y) mm of a sheet ``height`` mm high (y up)."""
    return tuple(img[int((height - y) * PX), int(x * PX)].tolist())


def close(a, b, tol=12) -> bool:
    return max(abs(int(p) - int(q)) for p, q in zip(a, b)) <= tol


def ink(img: np.ndarray, x0, y0, x1, y1, height) -> np.ndarray:
    """(n, 2) model coordinates (mm, y up) of the dark pixels inside a model box."""
    rows, cols = np.nonzero(img[..., :3].max(axis=2) < 128)
    x, y = (cols + 0.5) / PX, height - (rows + 0.5) / PX
    keep = (x > x0) & (x < x1) & (y > y0) & (y < y1)
    return np.column_stack([x[keep], y[keep]])


def check_sheet_one(img: np.ndarray, opacity: float) -> None:
    """The probes of sheet 1, filled colours blended with white by ``opacity``."""
    blend = lambda c: tuple(round(255 - opacity * (255 - v)) for v in c)  # noqa: E731
    assert close(at(img, 7, 15, 40), blend(TEAL))        # the frame
    assert close(at(img, 15, 7, 40), blend(TEAL))
    assert at(img, 15, 15, 40) == WHITE                  # its hole stays open
    assert close(at(img, 32, 27, 40), blend(SAND))       # the triangle
    assert at(img, 38, 33, 40) == WHITE                  # beyond its hypotenuse
    for x, y in [(30, 12), (55, 12), (42, 5), (42, 20)]:  # the cut square's four sides
        assert close(at(img, x, y, 40), RED, 40), (x, y)
    assert at(img, 42, 12, 40) == WHITE                  # not filled; the hidden block unseen
    assert at(img, 2, 2, 40) == WHITE

    # text anchored at its end: the ink ends at x = 25 and stands on y = 35, cap height 3 mm
    hih = ink(img, 0, 33, 30, 40, 40)
    assert hih[:, 0].max() == pytest.approx(25, abs=1.0)  # less the side bearing
    assert hih[:, 1].min() == pytest.approx(35, abs=0.5)
    assert np.ptp(hih[:, 1]) == pytest.approx(3.0, rel=0.2)
    assert np.ptp(hih[:, 0]) > 5                         # three letters, not one
    # turned text: its ink runs at 30 degrees counter-clockwise, its baseline through (45, 30):
    # the middle of its 2 mm high capitals 1 mm above that, turned by 30 degrees with it
    turned = ink(img, 31, 21, 60, 40, 40)
    centre = turned.mean(axis=0)
    up = np.array([-np.sin(np.pi / 6), np.cos(np.pi / 6)])
    assert np.hypot(*(centre - ([45, 30] + 1.0 * up))) < 0.3
    _, vectors = np.linalg.eigh(np.cov((turned - centre).T))
    dx, dy = vectors[:, -1] * np.sign(vectors[0, -1])
    assert np.degrees(np.arctan2(dy, dx)) == pytest.approx(30, abs=4)
    assert np.ptp(turned @ [np.cos(np.pi / 6), np.sin(np.pi / 6)]) > 15  # the whole line


def check_sheet_two(img: np.ndarray) -> None:
    assert close(at(img, 7, 7, 20), RED)
    for x, y in [(1, 7), (13, 7), (7, 1), (7, 13)]:
        assert at(img, x, y, 20) == WHITE, (x, y)


def test_png_pixels_are_where_the_drawing_says():
    data = png.render(drawing(), dpi=DPI)
    with Image.open(io.BytesIO(data)) as im:
        assert im.mode == "RGB"
        assert im.info["dpi"] == pytest.approx((DPI, DPI), abs=0.01)
        assert (im.text["Title"], im.text["generator"], im.text["command"]) == \
            ("raster", "test", "x")
        img = np.asarray(im)
    # sheets stacked top to bottom, 10 px apart, as wide as the widest
    assert img.shape == (40 * PX + 10 + 20 * PX, 60 * PX, 3)
    check_sheet_one(img[:40 * PX], opacity=1.0)  # PNG draws fills opaque
    assert (img[40 * PX:40 * PX + 10] == 255).all()
    check_sheet_two(img[40 * PX + 10:, :30 * PX])
    assert (img[40 * PX + 10:, 30 * PX:] == 255).all()


def test_png_refuses_a_sheet_too_large(monkeypatch):
    assert png.MAX_PIXELS == 12_000 * 12_000
    huge = Drawing((Sheet(3000, 3000),))
    with pytest.raises(ExportError, match=r"a 3000 x 3000 mm sheet at 300 dpi is too large "
                                          r"for PNG \(35433 x 35433 px\)"):
        png.render(huge, dpi=300)
    # the limit to the pixel, on a small limit (rendering 12 000 x 12 000 px takes a minute):
    # 100 x 100 px at 254 dpi is 10 mm; one pixel more in either direction is refused
    monkeypatch.setattr(png, "MAX_PIXELS", 100 * 100)
    with Image.open(io.BytesIO(png.render(Drawing((Sheet(10, 10),)), dpi=254))) as im:
        assert im.size == (100, 100)
    for w, h in [(10.1, 10), (10, 10.1)]:
        with pytest.raises(ExportError, match="too large for PNG"):
            png.render(Drawing((Sheet(w, h),)), dpi=254)


def test_pdf_pixels_are_where_the_drawing_says(tmp_path):
    path = tmp_path / "d.pdf"
    path.write_bytes(pdf.render(drawing()))
    info = pdfinfo(path)
    assert (info["Title"], info["Creator"], info["Producer"], info["Subject"]) == \
        ("raster", "test", "test", "x")
    assert info["Pages"] == "2"
    subprocess.run([program("pdftoppm"), "-r", f"{DPI}", "-png", str(path), str(tmp_path / "p")],
                   check=True)
    pages = [np.asarray(Image.open(tmp_path / f"p-{n}.png").convert("RGB")) for n in (1, 2)]
    assert pages[0].shape == (40 * PX, 60 * PX, 3) and pages[1].shape == (20 * PX, 30 * PX, 3)
    check_sheet_one(pages[0], opacity=0.5)  # PDF keeps the fills' opacity
    check_sheet_two(pages[1])


def test_pdf_strokes_at_their_width(tmp_path):
    """A 0.5 mm cut line is 2 px wide at 4 px/mm; a 2 mm one 8 px."""
    lines = Layer("cut", "cut", (
        polygons_from_shapely([shapely.box(5, 5, 25, 25)], Style(hexc(RED), 0.5)),
        polygons_from_shapely([shapely.box(35, 5, 55, 25)], Style(hexc(RED), 2.0))))
    path = tmp_path / "w.pdf"
    path.write_bytes(pdf.render(Drawing((Sheet(60, 30, (lines,)),))))
    subprocess.run([program("pdftoppm"), "-r", f"{DPI}", "-png", str(path), str(tmp_path / "w")],
                   check=True)
    img = np.asarray(Image.open(tmp_path / "w-1.png").convert("RGB"))
    row = img[int(15 * PX)]  # across both squares at y = 15
    red = (row[:, 0] > 200) & (row[:, 1] < 100)
    thin, thick = red[:30 * PX].sum(), red[30 * PX:].sum()
    assert thin == pytest.approx(2 * 2, abs=1) and thick == pytest.approx(2 * 8, abs=1)


def hole_drawing() -> Drawing:
    """A 30 mm sheet with a teal frame (5-25 mm) whose hole (10-20 mm) runs the same way as
    its outline, as drawings read from files may have."""
    outer = np.array([[5.0, 5], [25, 5], [25, 25], [5, 25]])
    hole = np.array([[10.0, 10], [20, 10], [20, 20], [10, 20]])  # counter-clockwise, as outer
    shape = Polygons(np.concatenate([outer, hole]), np.array([0, 4, 8]), Style(None, 0,
                     hexc(TEAL)), np.array([0, 2]))
    return Drawing((Sheet(30, 30, (Layer("tiles", "paint", (shape,)),)),), "hole")


def test_a_hole_wound_like_its_outline_stays_open_in_every_format(tmp_path):
    """The fill rule is even-odd in every writer: a hole whose ring runs the same way as its
    outline is open in the SVG (rendered by rsvg), the PDF (rendered by poppler) and the PNG,
    not only where shapely oriented the rings (the DXF: the next test)."""
    d = hole_drawing()
    (tmp_path / "h.svg").write_bytes(svg.render(d))
    (tmp_path / "h.pdf").write_bytes(pdf.render(d))
    subprocess.run([program("rsvg-convert"), "-d", f"{DPI}", "-p", f"{DPI}", "-b", "white",
                    "-o", str(tmp_path / "s.png"), str(tmp_path / "h.svg")], check=True)
    subprocess.run([program("pdftoppm"), "-r", f"{DPI}", "-png", str(tmp_path / "h.pdf"),
                    str(tmp_path / "p")], check=True)
    images = {"png": np.asarray(Image.open(io.BytesIO(png.render(d, dpi=DPI))).convert("RGB"))}
    for name, file in [("svg", "s.png"), ("pdf", "p-1.png")]:
        images[name] = np.asarray(Image.open(tmp_path / file).convert("RGB"))
    for name, img in images.items():
        assert close(at(img, 7, 15, 30), TEAL), name       # the frame is filled
        assert at(img, 15, 15, 30) == WHITE, name           # its hole is open


def test_a_hole_wound_like_its_outline_stays_open_in_the_dxf(tmp_path):
    """The same frame as DXF, printed by LibreCAD (its own DXF reader and hatch filler) to a
    PDF fitted to the drawing, rendered by poppler: inside the teal frame's bounds, the middle
    (the hole) is white and a point halfway between the outline and the hole is teal."""
    (tmp_path / "h.dxf").write_bytes(dxf.render(hole_drawing()))
    subprocess.run([program("xvfb-run"), "-a", program("librecad"), "dxf2pdf", "-a", "-t",
                    str(tmp_path), str(tmp_path / "h.dxf")], check=True, capture_output=True)
    subprocess.run([program("pdftoppm"), "-r", "50", "-png", str(tmp_path / "h.pdf"),
                    str(tmp_path / "p")], check=True)
    img = np.asarray(Image.open(tmp_path / "p-1.png").convert("RGB")).astype(int)
    teal = (np.abs(img - TEAL) <= 12).all(axis=-1)
    rows, cols = np.flatnonzero(teal.any(axis=1)), np.flatnonzero(teal.any(axis=0))
    (top, bottom), (left, right) = (rows[[0, -1]], cols[[0, -1]])
    assert bottom - top > 40 and right - left > 40  # the frame, 20 mm across, is drawn
    mid_y, mid_x = (top + bottom) // 2, (left + right) // 2
    assert (img[mid_y, mid_x] == WHITE).all()                  # the hole is open
    assert teal[mid_y, left + (right - left) // 8]             # the frame is filled
    assert teal[top + (bottom - top) // 8, mid_x]
