"""WCAG contrast against values published with the WCAG 2 definition and computed by hand."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from weavecut.layout.contrast import contrast_ratio, relative_luminance, text_colour_on


@pytest.mark.parametrize("colour, luminance", [
    ("#000000", 0.0), ("#ffffff", 1.0),
    ("#ff0000", 0.2126), ("#00ff00", 0.7152), ("#0000ff", 0.0722),
    ("#808080", 0.21586050011389923),   # ((0.502 + 0.055) / 1.055) ** 2.4, by hand
])
def test_relative_luminance(colour, luminance):
    assert relative_luminance(colour) == pytest.approx(luminance, abs=1e-12)


def test_known_ratios():
    assert contrast_ratio("#ffffff", "#000000") == pytest.approx(21.0)
    assert contrast_ratio("#777777", "#ffffff") == pytest.approx(4.478, abs=1e-3)  # the classic "fails AA" grey
    assert contrast_ratio("#767676", "#ffffff") == pytest.approx(4.542, abs=1e-3)  # the lightest grey that passes


colours = st.integers(0, 0xFFFFFF).map(lambda n: f"#{n:06x}")


@given(colours)
def test_text_colour_always_reaches_the_better_contrast(fill):
    ink = text_colour_on(fill)
    other = "#ffffff" if ink == "#000000" else "#000000"
    assert contrast_ratio(ink, fill) >= contrast_ratio(other, fill)
    assert contrast_ratio(ink, fill) >= 4.58  # black or white always reaches at least sqrt(21)


@pytest.mark.parametrize("bad", ["red", "#12345", "123456", "#1234567"])
def test_bad_colour_is_refused(bad):
    with pytest.raises(ValueError):
        relative_luminance(bad)
