"""A picture (Raster) in every writer, read back by a reader that is not weave-cut's: the SVG's
``<image>`` parsed and its PNG decoded by Pillow, and drawn by rsvg; the PDF's image listed and
extracted by poppler's pdfimages and the page drawn by pdftoppm; the PNG's pixels; the DXF's
lines read by ezdxf. The picture lies over a red block, opaque: red must show right up to its
box and not inside it, so a picture a pixel off in place or size fails."""

from __future__ import annotations

import base64
import io
import subprocess
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
from PIL import Image

from weavecut.export import dxf, pdf, png, svg
from weavecut.layout.drawing import (Drawing, Layer, Raster, Sheet, Style, polygons_from_rings,
                                     polylines_from_lines)
from weavecut.layout.tiling import on_pages

from tests.svg_readback import assert_svg_shows
from tests.test_readback import program

PX = 4  # pixels per mm the pages are drawn at
DPI = 25.4 * PX
BOX = (12.5, 7.25, 20.0, 10.0)  # x, y (bottom left), width, height in mm
SHEET = (60.0, 40.0)


def pixels() -> np.ndarray:
    """(50, 100): a black block in the top-left quarter, a grey band along the bottom rows,
    white elsewhere (0.2 mm pixels)."""
    p = np.full((50, 100), 255, dtype=np.uint8)
    p[:25, :50] = 0
    p[40:, :] = 128
    return p


def drawing() -> Drawing:
    red = Layer("under", "paint", (polygons_from_rings(
        [np.array([[5.0, 2], [55, 2], [55, 38], [5, 38]])], Style(None, 0, "#ff0000")),))
    line = polylines_from_lines([[(13.0, 8.0), (32.0, 16.0)]], Style("#000000", 0.01))
    picture = Raster(*BOX, pixels(), vector=(line,))
    return Drawing((Sheet(*SHEET, (red, Layer("edges", "cut", (picture,)))),), "picture")


def probes(img: np.ndarray, height: float = SHEET[1]) -> None:
    """The page ``img`` (drawn at PX a mm, RGB) shows the picture in its box over red."""
    x, y, w, h = BOX

    def at(px, py):
        return img[int((height - py) * PX), int(px * PX)].astype(int)

    def is_red(c):
        return c[0] > 200 and c[1] < 60 and c[2] < 60

    inside = 0.6  # mm from an edge of the box: 2.4 pixels, clear of smoothing
    assert (at(x + w / 4, y + 3 * h / 4) < 40).all()  # the black block
    assert (at(x + 3 * w / 4, y + h / 2) > 225).all()  # white: the red does not show
    grey = at(x + w / 2, y + 0.5)
    assert (abs(grey - 128) < 20).all(), grey  # the grey band along the bottom
    for px, py in [(x - inside, y + h / 2), (x + w + inside, y + h / 2),
                   (x + w / 2, y - inside), (x + w / 2, y + h + inside)]:
        assert is_red(at(px, py)), (px, py)  # just outside every edge
    for px, py in [(x + inside, y + h / 2), (x + w - inside, y + h / 2),
                   (x + 3 * w / 4, y + h - inside)]:
        assert not is_red(at(px, py)), (px, py)  # just inside


def test_svg_has_the_picture_as_an_image_in_mm():
    root = ET.fromstring(svg.render(drawing()))
    images = root.findall(".//{http://www.w3.org/2000/svg}image")
    assert len(images) == 1
    image = images[0]
    x, y, w, h = BOX
    assert [float(image.get(k)) for k in ("x", "y", "width", "height")] == \
        [x, SHEET[1] - y - h, w, h]  # y down from the top
    assert image.get("preserveAspectRatio") == "none"
    head, _, data = image.get("{http://www.w3.org/1999/xlink}href").partition(",")
    assert head == "data:image/png;base64"
    with Image.open(io.BytesIO(base64.b64decode(data))) as im:
        assert im.mode == "L"
        assert im.info["dpi"] == pytest.approx((127, 127), abs=0.01)  # 0.2 mm pixels
        assert (np.asarray(im) == pixels()).all()


def test_svg_shows_every_layer_shape_and_picture():
    assert_svg_shows(drawing(), svg.render(drawing()))


def test_svg_picture_drawn_by_rsvg_is_in_its_box(tmp_path):
    (tmp_path / "p.svg").write_bytes(svg.render(drawing()))
    subprocess.run([program("rsvg-convert"), "-d", f"{DPI}", "-p", f"{DPI}", "-b", "white",
                    "-o", str(tmp_path / "p.png"), str(tmp_path / "p.svg")], check=True)
    probes(np.asarray(Image.open(tmp_path / "p.png").convert("RGB")))


def test_pdf_has_the_picture_as_a_grey_image_at_its_size(tmp_path):
    (tmp_path / "p.pdf").write_bytes(pdf.render(drawing()))
    listed = subprocess.run([program("pdfimages"), "-list", str(tmp_path / "p.pdf")],
                            capture_output=True, text=True, check=True).stdout.splitlines()[2:]
    assert len(listed) == 1
    cells = listed[0].split()
    # page num type width height color comp bpc enc interp object ID x-ppi y-ppi
    assert cells[2:8] == ["image", "100", "50", "gray", "1", "8"]
    assert (cells[12], cells[13]) == ("127", "127")  # 0.2 mm pixels: the box's exact size
    subprocess.run([program("pdfimages"), "-png", str(tmp_path / "p.pdf"),
                    str(tmp_path / "img")], check=True)
    with Image.open(tmp_path / "img-000.png") as im:
        assert (np.asarray(im.convert("L")) == pixels()).all()


def test_pdf_page_drawn_by_poppler_shows_the_picture_in_its_box(tmp_path):
    (tmp_path / "p.pdf").write_bytes(pdf.render(drawing()))
    subprocess.run([program("pdftoppm"), "-r", f"{DPI}", "-png", "-singlefile",
                    str(tmp_path / "p.pdf"), str(tmp_path / "page")], check=True)
    probes(np.asarray(Image.open(tmp_path / "page.png").convert("RGB")))


def test_png_pastes_the_picture_over_its_box():
    probes(np.asarray(Image.open(io.BytesIO(png.render(drawing(), dpi=DPI))).convert("RGB")))


def test_dxf_draws_the_lines_the_picture_is_of():
    doc = ezdxf.read(io.StringIO(dxf.render(drawing()).decode("cp1252")))
    lines = [e for e in doc.modelspace() if e.dxf.layer == "edges"]
    assert [e.dxftype() for e in lines] == ["LWPOLYLINE"]
    assert [tuple(p) for p in lines[0].get_points("xy")] == [(13.0, 8.0), (32.0, 16.0)]
    assert not doc.modelspace().query("IMAGE")


def test_a_tiled_print_crops_the_picture_page_by_page():
    big = Drawing((Sheet(400, 300, (Layer("edges", "cut", (
        Raster(10.0, 10.0, 380.0, 280.0, np.zeros((280, 380), dtype=np.uint8)),)),)),))
    pages = on_pages(big, (210.0, 297.0))
    assert len(pages.sheets) > 1
    covered = 0.0
    for page in pages.sheets:
        parts = [s for layer in page.layers for s in layer.shapes if isinstance(s, Raster)]
        assert len(parts) == 1
        part = parts[0]
        h, w = part.pixels.shape
        assert (part.width, part.height) == pytest.approx((w, h))  # 1 mm pixels, whole
        # on the page: it may reach into the margin by less than a pixel, not beyond
        assert part.x > -1 and part.y > -1
        assert part.x + part.width < page.width + 1 and part.y + part.height < page.height + 1
        covered += part.width * part.height
    assert covered >= 380 * 280  # every pixel is on some page (overlaps twice)
