"""The kit's figures on the web page (``weavecut.web.summary``): each row states the
``--json`` summary's value in the unit it prints, converted from the unit the JSON key
states (``_mm``, ``_m``, a fraction as per cent); worked out by hand here."""

from __future__ import annotations

from weavecut.web import summary

STRANDS = {"pages": {"total": 3, "strip": 1, "extra": 2}, "strands": 24, "module_strips": 6,
           "copies": 4, "strip_width_mm": 13.7, "tile_size_mm": 20.0, "ink_fraction": 0.293,
           "cutter": {"name": "silhouette", "cut_length_mm": 2819.4, "outlines": 24}}
PUZZLE = {"pieces": 20, "piece_across_mm": [33.6, 38.6], "frame_mm": [200.0, 190.2],
          "kerf_mm": 0.15, "material": "3 mm poplar plywood",
          "modes": {"shared": {"cut_length_m": 1.885, "sheets": 1, "time_min": 1.6},
                    "separate": {"cut_length_m": 3.164, "sheets": 2, "time_min": 2.7}}}
CARD = {"sheets": 3, "card_colours": 4, "strips": 30, "cut_minutes": 12.4, "length_m": 5.26,
        "smallest_label_mm": 2.46}


def test_a_strand_books_figures_in_their_units():
    assert summary.figures(STRANDS) == [
        ("Pages", "3 (1 of strips)"), ("Strands", "24"), ("Module", "4 copies of 6 strips"),
        ("Strip width", "13.7 mm"), ("Octagons across", "20 mm"), ("Ink", "29 %"),
        ("Cuts (silhouette)", "2.8 m")]


def test_a_puzzles_figures_in_their_units():
    assert summary.figures(PUZZLE) == [
        ("Pieces", "20"), ("Pieces across", "33.6–38.6 mm"), ("Frame", "200 × 190 mm"),
        ("Material", "3 mm poplar plywood"), ("Kerf", "0.15 mm"),
        ("Shared-edge cut", "1.9 m of cuts on 1 sheet, about 2 min"),
        ("Separate pieces", "3.2 m of cuts on 2 sheets, about 3 min")]


def test_a_laser_card_kits_figures_in_their_units():
    assert summary.figures(CARD) == [
        ("Sheets", "3"), ("Card colours", "4"), ("Strip pieces", "30"),
        ("Cutting time", "about 12 min"), ("Cutting length", "5.3 m"),
        ("Smallest label", "2.5 mm")]


def test_a_drawings_puzzle_names_the_cell_and_level_chosen():
    """The CLI chooses a drawing's cell and level (its summary's "chosen"); the page says them
    (issue 29: a heart upload showed a level field of 4 and a kit of level 2)."""
    chosen = {"cell_mm": 39.0, "levels": 2, "text": "chose --cell 39mm --levels 2 (...)"}
    rows = summary.figures({**PUZZLE, "chosen": chosen})
    assert rows[0] == ("Chosen for the drawing", "39 mm cells, level 2")
    assert rows[1:] == summary.figures(PUZZLE)
