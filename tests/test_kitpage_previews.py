"""The kit page's pictures say what the files hold (#34: mutants of kitpage/previews.py no test
killed): a PDF's thumbnails come in page order however many pages it has, and a cut drawn
over a printed page or on card is its outline only, whatever fill its shapes carry."""

from __future__ import annotations

import io

import numpy as np
from PIL import Image

from weavecut import export
from weavecut.kitpage import previews
from weavecut.kitpage.document import _layer_settings
from weavecut.layout.drawing import Drawing, Layer, Polygons, Sheet, Style, polylines_from_lines

from .test_readback import program


def box(x0: float, y0: float, x1: float, y1: float, style: Style,
        fills: tuple[str, ...] | None = None) -> Polygons:
    return Polygons(np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float),
                    np.array([0, 4]), style, fills=fills)


def pixels(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)


def test_a_pdfs_thumbnails_are_in_page_order_past_nine_pages(tmp_path):
    """Page k (1..12) carries a black bar k x 15 mm wide: the thumbnails' bars widen one by
    one (pdftoppm names the pages page-01 .. page-12)."""
    program("pdftoppm")
    sheets = tuple(Sheet(210.0, 297.0, (Layer("bar", "paint", (box(
        10, 100, 10 + 15 * k, 150, Style(None, 0.0, "#000000")),)),), f"page {k}")
        for k in range(1, 13))
    drawing = Drawing(sheets, "twelve pages")
    pdf = tmp_path / "twelve.pdf"
    export.write(drawing, pdf)
    thumbs, how = previews.pdf_thumbnails(pdf, drawing)
    assert how == "pdftoppm" and len(thumbs) == 12
    widths = [int(((pixels(t) < 100).all(axis=2)).any(axis=0).sum()) for t in thumbs]
    assert all(a < b for a, b in zip(widths, widths[1:])), widths


def test_a_cut_drawn_over_its_page_or_card_is_an_outline_whatever_its_fill():
    """A cut square whose shapes carry a fill of their own (green): the overlay and the card
    picture draw its outline, and inside it the page (white) or the card shows, never green."""
    cut = box(40, 40, 160, 160, Style("#ff0000", 0.01), fills=("#00ff00",))
    page = Sheet(200.0, 200.0, (), "page")
    sheet = Sheet(200.0, 200.0, (Layer("cut", "cut", (cut,)),), "cut")
    for png, inside in ((previews.overlay_png(page, sheet), (255, 255, 255)),
                        (previews.card_png(sheet, "#1b4f72"), (0x1B, 0x4F, 0x72))):
        image = pixels(png)
        h, w, _ = image.shape
        centre = image[h // 2 - 20:h // 2 + 20, w // 2 - 20:w // 2 + 20]
        assert (np.abs(centre - inside) <= 2).all(), centre[0, 0]
        green = (image[..., 1] > 200) & (image[..., 0] < 80) & (image[..., 2] < 80)
        assert not green.any()
        edge = image[h // 2, :w // 2]  # the outline crosses the left half of the middle row
        assert (np.abs(edge - inside).sum(axis=1) > 60).any()


def test_a_laser_files_settings_name_its_passes_only_where_there_are_several():
    """A laser file's card lists each operation in the order it runs: its colour, speed and
    power, and its passes where an operation takes more than one (none said: one)."""
    line = [np.array([[0.0, 0.0], [10.0, 0.0]])]
    layers = tuple(Layer(role, role, (polylines_from_lines(line, Style(colour, 0.1)),))
                   for role, colour in (("cut", "#ff0000"), ("engrave", "#000000"),
                                        ("score", "#0000ff")))
    drawing = Drawing((Sheet(100.0, 100.0, layers),), "t")
    operations = {"engrave": {"speed_mm_s": 150, "power_pct": 15},
                  "score": {"speed_mm_s": 80, "power_pct": 25, "passes": 1},
                  "cut": {"speed_mm_s": 20, "power_pct": 100, "passes": 2}}
    assert _layer_settings(drawing, operations, 20.0) == (
        "engrave black at 150 mm/s, 15 %; score blue at 80 mm/s, 25 %; "
        "cut red at 20 mm/s, 100 %, 2 passes")
