"""PDF pages: a drawing goes onto printer pages 1:1, centred when its content fits (turned to
landscape if only that fits), tiled otherwise."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from weavecut.layout.drawing import Drawing, Layer, Sheet, Style, Text, polygons_from_rings
from weavecut.layout.tiling import on_pages

A4 = (210.0, 297.0)


def drawing(width, height, margin=10.0):
    """A sheet with a rectangle filling it inside ``margin`` and a label at its corner."""
    ring = np.array([[margin, margin], [width - margin, margin], [width - margin, height - margin],
                     [margin, height - margin]])
    shapes = (polygons_from_rings([ring], Style("#000000", 0.2)), Text(margin, margin, "x"))
    return Drawing((Sheet(width, height, (Layer("cut", "cut", shapes),)),), "t")


@given(w=st.floats(10, 200), h=st.floats(10, 287))
def test_content_that_fits_is_centred_on_one_upright_page(w, h):
    pages = on_pages(drawing(w + 20, h + 20), A4)
    (sheet,) = pages.sheets
    assert (sheet.width, sheet.height) == A4
    rect, label = sheet.layers[0].shapes
    lo, hi = rect.coords.min(axis=0), rect.coords.max(axis=0)
    assert (lo + hi) / 2 == pytest.approx(np.array(A4) / 2)
    assert hi - lo == pytest.approx([w, h])
    assert (label.x, label.y) == pytest.approx(lo)  # everything moved alike


def test_wide_content_turns_the_page():
    (sheet,) = on_pages(drawing(280, 200), A4).sheets
    assert (sheet.width, sheet.height) == (297.0, 210.0)


def test_larger_content_is_tiled_on_page_sized_sheets():
    pages = on_pages(drawing(420, 420), A4)
    assert len(pages.sheets) == 6  # (420 - 10) / 180 -> 3 columns, (420 - 10) / 267 -> 2 rows
    assert {(s.width, s.height) for s in pages.sheets} == {A4}
