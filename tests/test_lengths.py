"""Lengths with units and paper sizes (weavecut.units): the module's own examples, run as
tests here too so that ``make mutation`` (which runs the tests/ files, not the doctests in
src/) reaches them, and what its mutants showed untested."""

from __future__ import annotations

import doctest
import tomllib

import pytest

from weavecut import presets, units


def test_the_examples_in_the_docstrings_hold():
    failed, tried = doctest.testmod(units, optionflags=doctest.ELLIPSIS)
    assert tried >= 4 and failed == 0


@pytest.mark.parametrize("value, mm", [
    ("100mmx5cm", (100.0, 50.0)),   # a unit on each side: each its own
    ("100x5e1mm", (100.0, 50.0)),   # an exponent is part of the number, not of the unit
    ("2inx3in", (50.8, 76.2)),
    ("0.5x50mm", (0.5, 50.0)),      # small but positive
    ("50x0.5mm", (50.0, 0.5)),
    ("10000x5mm", (10000.0, 5.0)),  # as large as a page may be
    (" A4 ", (210.0, 297.0)),
    ("100mm x 5cm", (100.0, 50.0)),  # spaces around the x (refused as '100mm  5cm' before)
    ("100 x 50 mm", (100.0, 50.0)),
    ("816pxx1056px", (215.9, 279.4)),  # px on each side: the x between, not px's
])
def test_a_page_size_is_read_side_by_side(value, mm):
    assert units.page_size(value) == pytest.approx(mm, rel=1e-12)


@pytest.mark.parametrize("value, message", [
    ("a44", "'a44' is not a page size: use a4, a3, letter, a preset or WxH like 200x300mm "
            "(did you mean 'a4'?)"),
    ("100x1", "'100x1' has no unit: write it like '100x1mm'"),
    ("50x0mm", "page size '50x0mm' must be positive"),
    ("0x50mm", "page size '0x50mm' must be positive"),
    ("10001x5mm", "page size '10001x5mm' is larger than 10 m"),
])
def test_a_page_size_that_cannot_be_is_refused_with_its_reason(value, message):
    with pytest.raises(ValueError) as refused:
        units.page_size(value)
    assert str(refused.value) == message


# ISO 216 and ANSI/ASME Y14.1 sizes in mm (legal 8.5 x 14 in, tabloid 11 x 17 in), portrait
PUBLISHED = {"a2": (420.0, 594.0), "a5": (148.0, 210.0), "legal": (215.9, 355.6),
             "tabloid": (279.4, 431.8)}


@pytest.mark.parametrize("name", presets.names("pages"))
def test_a_page_preset_is_read_as_its_file_says(name):
    """Width first, height second, as the preset's TOML (read by tomllib) names them; the
    paper sizes also as published."""
    doc = tomllib.loads(presets.find("pages", name).read_text(encoding="utf-8"))
    wanted = (units.to_mm(doc["width"]), units.to_mm(doc["height"]))
    assert presets.page_size(name) == wanted
    if name in PUBLISHED:
        assert wanted == pytest.approx(PUBLISHED[name], abs=1e-9)


@pytest.mark.parametrize("read, value, message", [
    (units.to_mm, "3yd", "'3yd' is not a length: unknown unit 'yd'; use mm, cm, m, in, pt, px"),
    (units.length, True, "True is not a length"),
    (units.to_mm, "3 mm mm", "'3 mm mm' is not a length like '3mm', '2.5cm' or '1in'"),
    (presets.page_size, "a9", "'a9' is not a page size: use a4, a3, letter, a preset (a2, a5, "
                              "glowforge-bed, legal, tabloid) or WxH like 200x300mm"),
])
def test_what_is_not_a_length_or_a_page_is_said_word_for_word(read, value, message):
    with pytest.raises(ValueError) as refused:
        read(value)
    assert str(refused.value) == message
