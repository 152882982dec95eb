"""Every length unit weave-cut accepts, against its published definition, through each way a
length comes in (``units.to_mm``, ``units.length``, a page size, a preset's schema, an option).

A unit read as another of similar size (pt as px, in as 2.5 cm) changes every cut by a few
per cent and nothing else notices; the definitions here are written from their sources, not
from ``units.UNITS``:

- mm, cm, m: the SI (BIPM, The International System of Units, 9th ed., 2019);
- in = 25.4 mm exactly: the international yard and pound agreement of 1959 (NBS, Federal
  Register 24 (1959) 5348);
- pt = 1/72 in: the PostScript (desktop publishing) point, PostScript Language Reference,
  3rd ed., sec. 4.3.1, and CSS Values and Units Level 3, sec. 6.2 ("1pt = 1/72th of 1in");
- px = 1/96 in: CSS Values and Units Level 3, sec. 6.2 ("1px = 1/96th of 1in"), the SVG user
  unit of an Inkscape drawing.
"""

from __future__ import annotations

from fractions import Fraction

import pytest
from click.testing import CliRunner

from weavecut import presets, schema, units
from weavecut.cli import cli

INCH = Fraction(254, 10)  # mm
DEFINITIONS = {"mm": Fraction(1), "cm": Fraction(10), "m": Fraction(1000), "in": INCH,
               "pt": INCH / 72, "px": INCH / 96}
# amounts that make a round number of millimetres in each unit
ROUND = {"mm": ("12.5", 12.5), "cm": ("2.54", 25.4), "m": ("0.2159", 215.9),
         "in": ("8.5", 215.9), "pt": ("612", 215.9), "px": ("816", 215.9)}


def test_every_accepted_unit_has_a_published_definition_here():
    assert set(units.UNITS) == set(DEFINITIONS)


@pytest.mark.parametrize("unit", sorted(DEFINITIONS))
def test_one_unit_is_its_definition(unit):
    assert units.to_mm(f"1{unit}") == pytest.approx(float(DEFINITIONS[unit]), rel=1e-15)
    assert units.length(f"3 {unit.upper()}") == pytest.approx(float(3 * DEFINITIONS[unit]),
                                                             rel=1e-15)


@pytest.mark.parametrize("unit", sorted(ROUND))
def test_round_amounts(unit):
    amount, mm = ROUND[unit]
    assert float(Fraction(amount) * DEFINITIONS[unit]) == pytest.approx(mm, rel=1e-15)
    assert units.length(amount + unit) == pytest.approx(mm, rel=1e-12)


def test_units_of_similar_size_are_told_apart():
    """The pairs a slip would confuse differ by more than the tolerance every test above uses."""
    for a, b in (("pt", "px"), ("in", "cm"), ("mm", "px"), ("mm", "pt")):
        assert abs(units.to_mm(f"1{a}") / units.to_mm(f"1{b}") - 1) > 0.05


LETTER = {"mm": "215.9x279.4mm", "cm": "21.59x27.94cm", "m": "0.2159x0.2794m",
          "in": "8.5x11in", "pt": "612x792pt", "px": "816x1056px"}


@pytest.mark.parametrize("unit", sorted(LETTER))
def test_a_letter_page_in_every_unit(unit):
    """US Letter is 8.5 x 11 in (ANSI/ASME Y14.1): 215.9 x 279.4 mm, in any unit."""
    w, h = units.page_size(LETTER[unit])
    assert (w, h) == (pytest.approx(215.9, rel=1e-12), pytest.approx(279.4, rel=1e-12))
    assert units.PAPER_SIZES["letter"] == (215.9, 279.4)
    assert units.PAPER_SIZES["a4"] == (210.0, 297.0)  # ISO 216
    assert units.PAPER_SIZES["a3"] == (297.0, 420.0)


@pytest.mark.parametrize("unit", sorted(ROUND))
def test_a_preset_length_in_every_unit(unit):
    amount, mm = ROUND[unit]
    pages = presets.schemas()["pages"]
    assert pages.fields["width"].problem(amount + unit) is None
    assert schema.Length(0, mm * (1 + 1e-9)).problem(amount + unit) is None
    assert "must be" in (schema.Length(0, mm * (1 - 1e-6)).problem(amount + unit) or "must be")
    assert schema.Length(0, mm * (1 - 1e-6)).problem(amount + unit) is not None


@pytest.mark.parametrize("unit", sorted(ROUND))
def test_an_option_length_in_every_unit(unit, tmp_path):
    """``--size`` is the drawing's longer side: the SVG's user units are mm, so the drawn
    pentagon's width read from its path is the length given, in mm."""
    import re
    from xml.etree import ElementTree

    amount, mm = ROUND[unit]
    if mm < 20:
        amount, mm = str(Fraction(amount) * 4), mm * 4
    out = tmp_path / "p.svg"
    result = CliRunner().invoke(cli, ["subdivide", "pentagon", "--levels", "0", "--size",
                                      amount + unit, "-o", str(out)])
    assert result.exit_code == 0, result.output
    root = ElementTree.parse(out).getroot()
    xy = [float(v) for p in root.iter("{http://www.w3.org/2000/svg}path") if p.get("d")
          for v in re.findall(r"-?\d+(?:\.\d+)?", p.get("d"))]
    xs, ys = xy[0::2], xy[1::2]
    assert max(max(xs) - min(xs), max(ys) - min(ys)) == pytest.approx(mm, abs=2e-3)
