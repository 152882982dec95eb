"""The label checks catch each rule on its own: one planted text per broken rule, on a sheet
built here (a filled square, a strip outline, a printable box), and a readable text breaks
nothing. The report's figures are recounted from the records."""

from __future__ import annotations

import numpy as np
import pytest

from weavecut.layout.contrast import contrast_ratio
from weavecut.layout.drawing import Drawing, Layer, Sheet, Style, Text, polygons_from_rings
from weavecut.layout.labels import centred_text, text_box
from weavecut.papermodel.checks import report, text_checks

DARK = "#203060"
BOX = (10.0, 10.0, 190.0, 190.0)  # the printable box of a strip page


def _square(x0, y0, x1, y1):
    return np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], dtype=float)


def _sheet(*texts, extra=(), hidden=False):
    """A dark 100 mm square (the strip's cut outline too), texts on a "labels" layer and
    ``extra`` layers drawn after it."""
    paint = polygons_from_rings([_square(50, 50, 150, 150)], Style(None, 0.0), [DARK])
    cut = polygons_from_rings([_square(50, 50, 150, 150)], Style("#ff0000", 0.2))
    layers = (Layer("paint", "paint", (paint,), visible=not hidden),
              Layer("cut", "cut", (cut,)), Layer("labels", "label", tuple(texts)), *extra)
    return Sheet(200.0, 200.0, layers)


def _broken(sheet, box=BOX):
    return [r["broken"] for r in text_checks(sheet, box)]


def test_a_readable_label_breaks_nothing_and_reports_its_size_and_contrast():
    good = centred_text((100.0, 100.0), "A7", 5.0, 0.0, "#ffffff")
    (record,) = text_checks(_sheet(good), BOX)
    assert record == {"text": "A7", "size": 5.0, "contrast": contrast_ratio("#ffffff", DARK),
                      "broken": []}
    assert text_checks(_sheet(centred_text((100.0, 100.0), "A7", 2.5, 90.0, "#ffffff")),
                       BOX)[0]["broken"] == []  # at the limits: 2.5 mm, a quarter turn
    within = centred_text((100.0, 100.0), "A7", 2.5 - 1e-9, 0.0, "#ffffff")  # (rounding)
    assert text_checks(_sheet(within), BOX)[0]["broken"] == []


@pytest.mark.parametrize("text, rule", [
    (centred_text((100.0, 100.0), "A7", 2.4, 0.0, "#ffffff"), "small"),
    (centred_text((100.0, 100.0), "A7", 4.0, 180.0, "#ffffff"), "upside down"),
    (centred_text((100.0, 100.0), "A7", 4.0, -90.0, "#ffffff"), "upside down"),
    (centred_text((100.0, 100.0), "A7", 4.0, 90.5, "#ffffff"), "upside down"),
    (centred_text((100.0, 100.0), "A7", 4.0, 0.0, "#304070"), "low contrast"),
])
def test_each_rule_is_caught_alone(text, rule):
    assert _broken(_sheet(text)) == [[rule]]


def test_a_label_across_its_fills_edge():
    """Centred just inside the square, reaching over its edge (and so off its strip)."""
    text = centred_text((149.0, 100.0), "A7", 4.0, 0.0, "#ffffff")
    assert _broken(_sheet(text)) == [["crosses its fill's edge", "outside its strip"]]
    inside = centred_text((140.0, 100.0), "A7", 4.0, 0.0, "#ffffff")
    assert _broken(_sheet(inside)) == [[]]


def test_a_label_off_its_strip_and_furniture_on_the_strips():
    off = centred_text((30.0, 100.0), "A7", 4.0, 0.0, "#000000")  # on paper, inside the box
    assert _broken(_sheet(off)) == [["outside its strip"]]
    # paint is no cut line: a label on a painted square that no strip outlines is off strips
    patch = Layer("patch", "paint", (polygons_from_rings([_square(15, 15, 45, 45)],
                                                         Style(None, 0.0), [DARK]),))
    on_patch = centred_text((30.0, 30.0), "A7", 4.0, 0.0, "#ffffff")
    assert _broken(_sheet(on_patch, extra=(patch,))) == [["outside its strip"]]
    furniture = Layer("page", "label", (Text(100.0, 20.0, "page 3", 4.0),
                                        Text(100.0, 195.0, "title", 4.0)))
    records = text_checks(_sheet(extra=(furniture,)), BOX)
    assert [r["broken"] for r in records] == [["furniture on the strips"], []]
    # without a box (not a strip page) neither rule applies
    assert _broken(_sheet(off, extra=(furniture,)), None) == [[], [], []]


def test_a_label_under_a_later_shape_or_over_another_label():
    label = centred_text((100.0, 100.0), "A7", 4.0, 0.0, "#ffffff")
    cover = polygons_from_rings([_square(95, 95, 140, 140)], Style(None, 0.0), [DARK])
    over = Layer("arrows", "paint", (cover,))
    # the later shape now is the fill under the centre: the label is on it, and crosses it
    assert "under another shape" not in _broken(_sheet(label, extra=(over,)))[0]
    corner = polygons_from_rings([_square(101, 101, 140, 140)], Style(None, 0.0), [DARK])
    broken = _broken(_sheet(label, extra=(Layer("arrows", "paint", (corner,)),)))[0]
    assert broken == ["under another shape"]
    twin = centred_text((101.0, 100.0), "B2", 4.0, 0.0, "#ffffff")
    assert _broken(_sheet(label, twin)) == [["overlaps a text"], ["overlaps a text"]]
    apart = centred_text((100.0, 130.0), "B2", 4.0, 0.0, "#ffffff")
    assert _broken(_sheet(label, apart)) == [[], []]


def test_hidden_layers_and_unfilled_shapes_are_not_a_fill():
    """A text on a hidden or unfilled square lies on white paper: white ink is then too pale."""
    white = centred_text((100.0, 100.0), "A7", 4.0, 0.0, "#ffffff")
    assert "low contrast" in _broken(_sheet(white, hidden=True))[0]
    # a hidden layer hides itself only: a fill drawn after it still counts
    later = Layer("later", "paint", (polygons_from_rings([_square(60, 60, 140, 140)],
                                                         Style(None, 0.0), [DARK]),))
    assert _broken(_sheet(white, extra=(later,), hidden=True)) == [[]]
    outline = polygons_from_rings([_square(50, 50, 150, 150)], Style("#000000", 0.2))
    sheet = Sheet(200.0, 200.0, (Layer("paint", "paint", (outline,)),
                                 Layer("labels", "label", (white,))))
    (record,) = text_checks(sheet, None)
    assert record["contrast"] == pytest.approx(1.0) and record["broken"] == ["low contrast"]
    # a style fill paints every polygon of the shape
    styled = polygons_from_rings([_square(50, 50, 150, 150)], Style(None, 0.0, DARK))
    sheet = Sheet(200.0, 200.0, (Layer("paint", "paint", (styled,)),
                                 Layer("labels", "label", (white,))))
    assert text_checks(sheet, None)[0]["contrast"] == contrast_ratio("#ffffff", DARK)


class _Area:
    box = BOX
    width, height, margin = 200.0, 200.0, BOX[0]


class _Plan:
    labels = ()  # no strand IDs on the assembly sheet here


class _Book:
    """What report() reads of a strand book."""

    def __init__(self, sheets, strip_pages, ink=0.41234):
        self.drawing = Drawing(tuple(sheets))
        self.strip_pages = strip_pages
        self.extra_pages = (1,)
        self.area = _Area()
        self.plan, self.colours, self.pieces = _Plan(), (), ()
        self.ink = ink
        self.tile_size = 21.456
        self.strip_width = 9.87
        self.warnings = ("thin",)


def test_report_recounts_pages_sizes_contrast_and_violations():
    good = centred_text((100.0, 100.0), "A7", 5.0, 0.0, "#ffffff")
    small = centred_text((80.0, 80.0), "B1", 2.456, 0.0, "#ffffff")
    off = centred_text((30.0, 100.0), "C3", 3.0, 0.0, "#000000")  # a fine label off a strip
    book = _Book([_sheet(off), _sheet(good, small)], (2,))
    rep = report(book)
    assert rep == {"pages": {"strip": 1, "extra": 1, "total": 2}, "ink_fraction": 0.412,
                   "smallest_text_mm": 2.46,
                   "smallest_contrast": round(contrast_ratio("#ffffff", DARK), 2),
                   "min_label_contrast": round(contrast_ratio("#ffffff", DARK), 2),
                   "min_label_gap_mm": round(text_box(good).distance(text_box(small)), 2),
                   "label_violations": 1, "tile_size_mm": 21.46, "strip_width_mm": 9.9,
                   "warnings": ["thin"], "label_tabs": 0, "names_left_out": 0,
                   "slimmest_piece_mm": None}  # this book has no pieces
    # page 1 is no strip page: its label off the strip is fine; as a strip page it is not
    assert report(_Book([_sheet(off), _sheet(good, small)], (1, 2)))["label_violations"] == 2
    empty = report(_Book([Sheet(200.0, 200.0)], ()))
    assert (empty["smallest_text_mm"], empty["smallest_contrast"]) == (0.0, 21.0)
    assert text_box(good).area > 0


def test_furniture_keeps_its_gap_from_furniture_only():
    """A strip label 0.7 mm from a page number beyond the printable box: the gap rule is for
    the page furniture among itself (labels sit on strips, where the overlap rule holds)."""
    label = centred_text((100.0, 147.5), "A7", 4.0, 0.0, "#ffffff")
    number = centred_text((100.0, 147.5), "page 3", 4.0, 0.0, "#000000")
    lift = text_box(label).bounds[3] + 0.7 - text_box(number).bounds[1]
    number = centred_text((100.0, 147.5 + lift), "page 3", 4.0, 0.0, "#000000")
    furniture = Layer("page", "label", (number,))
    box = (50.0, 50.0, 150.0, 150.0)
    assert _broken(_sheet(label, extra=(furniture,)), box) == [[], []]
