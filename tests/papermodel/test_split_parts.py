"""A strip printed in parts can be put together from the pages alone (issue 29: page 1 listed
A10 on p. 3 and p. 7 without saying which part is where, the "2/2" stood 4-5 tiles from the
ID, and nothing marked where the glue band goes): page 1 names each part and its page, a part's
number sits in the own tile nearest its ID, and the band "glue j" at the end of a part goes
under the tile marked "j" at the start of the next, as on the ball."""

from __future__ import annotations

import re
from functools import lru_cache

import numpy as np
import pytest
import shapely

from weavecut import inputs
from weavecut.layout.drawing import Text
from weavecut.papermodel.book import strand_book
from weavecut.papermodel.modules import copy_colours, plan_modules
from weavecut.papermodel.pages import split_strip
from weavecut.papermodel.strip_labels import label_strips
from weavecut.papermodel.strips import build_strips, octagon_size
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

TILE = 30.0  # mm across an octagon


@lru_cache(maxsize=None)
def _parts():
    """The 4x4 square grid's longest strip at ``TILE`` mm octagons cut in two or more parts,
    labelled."""
    w = snub_weaves(subdivide(inputs.get("square-grid:4x4"), 2))[-1]
    plan = plan_modules(w)
    strips = build_strips(w, plan, copy_colours(plan, palette("maritime-12")),
                          TILE / octagon_size(w), range(w.n_strands))
    strip = max(strips, key=lambda s: s.length)
    return strip, label_strips(split_strip(strip, strip.length / 1.5, 1000.0), TILE)


def _tile_of(piece, text: Text) -> int:
    """The tile of ``piece`` under the centre of ``text``."""
    hits = np.flatnonzero(shapely.contains_xy(piece.tiles, text.x, text.y))
    assert len(hits), text
    return int(hits[0])


def test_each_glue_band_names_the_tile_it_goes_under():
    strip, pieces = _parts()
    assert len(pieces) >= 2
    for i, (piece, nxt) in enumerate(zip(pieces, pieces[1:])):
        assert piece.tab == f"glue {i + 1}" and nxt.mark == str(i + 1)
        band = [t for t in piece.texts if t.text == piece.tab]
        assert band and _tile_of(piece, band[0]) == len(piece.tiles) - 1, piece.label
        marks = [t for t in nxt.texts if t.text == nxt.mark]
        assert marks and _tile_of(nxt, marks[0]) == 0, nxt.label
        # the band and the marked tile are the same tile of the strand
        assert piece.tiles[-1].area == shapely.area(nxt.tiles[0]) or np.isclose(
            piece.tiles[-1].area, nxt.tiles[0].area, rtol=1e-9)
    assert pieces[0].mark == "" and pieces[-1].glue is None


def test_a_parts_number_sits_by_its_id():
    """The number ("2/3") is in an own tile next but one to the ID's (the tile between is an
    under tile), not in the largest own tile elsewhere on the part; or, with one own tile,
    with the ID."""
    strip, pieces = _parts()
    name = strip.label
    for piece in pieces:
        part = piece.label.partition(" ")[2]
        if any(t.text == piece.label for t in piece.texts):
            continue  # one own tile: it says both ("C6 1/5")
        ids = [_tile_of(piece, t) for t in piece.texts if t.text == name]
        number = [_tile_of(piece, t) for t in piece.texts if t.text == part]
        assert ids and number, piece.label
        assert min(abs(n - i) for n in number for i in ids) <= 2, piece.label


@lru_cache(maxsize=None)
def _book(layout: str):
    """The 3x3 grid on A5, its strips split: ``layout`` "mixed" or "module" (the module's
    strips once, named by number alone: "10 1/2")."""
    ws = list(snub_weaves(subdivide(inputs.get("square-grid:3x3"), 2)))
    return strand_book(ws, palette("maritime-12"), (148.0, 210.0), tile_size=30.0, margin=6.0,
                       layout=layout)


def _words(book, n: int) -> str:
    return " ".join(t.text for lay in book.drawing.sheets[n - 1].layers for t in lay.shapes
                    if isinstance(t, Text))


@pytest.mark.parametrize("layout", ["mixed", "module"])
def test_page_one_says_which_page_holds_each_part(layout):
    """On A5 the 3x3 grid's strips are split: page 1's index names every part with the
    page that holds it, as page 2's step says it does, and the page's subtitle names it too
    (walk of issue #29: the module layout's page 1 had no index)."""
    book = _book(layout)
    page_one = _words(book, 1)
    index = dict(re.findall(r"p\. (\d+): ((?:[A-Z]*\d+(?: \d+/\d+)?(?:-[A-Z]*\d+)?,? ?)+)",
                            page_one))
    parts = [(n, p.label) for n, p in book.pieces if " " in p.label]
    assert parts and "page 1 says which page holds each part" in _words(book, 2)
    for n, label in parts:
        assert re.search(rf"(?<![\w/]){re.escape(label)}(?![\w/])",
                         index.get(str(n), "")), (n, label, index.get(str(n)))
        assert label in _words(book, n)


@pytest.mark.parametrize("layout", ["mixed", "module"])
def test_a_glue_mark_is_no_strands_id_and_page_two_names_it(layout):
    """The mark on the tile a glue band goes under reads as no ID printed in the book (the
    module layout's IDs are bare numbers: its "1" was strand 1's), and page 2 names that mark."""
    book = _book(layout)
    marks = {p.mark for _, p in book.pieces if p.mark}
    ids = {p.label.partition(" ")[0] for _, p in book.pieces} | set(book.plan.labels)
    assert marks and not marks & ids, sorted(marks & ids)
    for mark in marks:
        on = [t for _, p in book.pieces if p.mark == mark for t in p.texts if t.text == mark]
        assert on, mark  # printed on its part
    first = min(marks, key=len)
    assert f'under the tile marked "{first}"' in " ".join(_words(book, 2).split())
