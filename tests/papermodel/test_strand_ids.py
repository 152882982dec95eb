"""Every strand can be found: its ID is printed on the assembly pages and points at that
strand, read from the Drawing alone (the pattern's tiles, the white plates, the leader lines
and the texts of each page's "ids" layer), apart from the placement code."""

from __future__ import annotations

from dataclasses import replace as moved

import numpy as np
import pytest
import shapely

from weavecut.layout.drawing import Layer, Polygons, Polylines, Sheet
from weavecut.layout.labels import text_box
from weavecut.papermodel.checks import sheet_checks

from tests.papermodel.test_strands import pentagon_book, small_book, weaves

pytestmark = pytest.mark.slow  # the pentagon flower's whole book, read back page by page


def pointed_at(sheet, weave, ids) -> dict[str, set[int]]:
    """{ID: the strands it points at} over the "ids" texts of ``sheet``: a text inside a tile of
    the pattern names the strand on top there; a text on a white plate, the strand on top where
    the plate's leader line ends."""
    layers = {layer.name: layer for layer in sheet.layers}
    if "ids" not in layers:
        return {}
    shapes = layers["pattern"].shapes
    tiles = shapes[0].to_shapely()
    tree = shapely.STRtree(tiles)
    plates = [g for s in shapes if isinstance(s, Polygons) and s.style.fill == "#ffffff"
              for g in s.to_shapely().tolist()]
    lines = [line for s in shapes if isinstance(s, Polylines) and s.style.stroke == "#000000"
             for line in s.lines()]
    out: dict[str, set[int]] = {}
    for t in layers["ids"].shapes:
        box = text_box(t)
        plate = [g for g in plates if g.covers(box)]
        if plate:
            ends = [shapely.Point(e[-1]) for e in lines
                    if plate[0].exterior.distance(shapely.Point(e[0])) < 1e-6]
        else:
            ends = [box.centroid]
        hit = {int(k) for e in ends for k in tree.query(e, predicate="within")}
        out.setdefault(t.text, set()).update(int(weave.tile_over[k]) for k in hit)
    return out


def unfound(book, weave) -> list[str]:
    """The strand IDs that no text on the pages before the strips points at their strand."""
    found: dict[str, set[int]] = {}
    for n in book.extra_pages:
        for text, strands in pointed_at(book.drawing.sheets[n - 1], weave,
                                        book.plan.labels).items():
            found.setdefault(text, set()).update(strands)
    return [label for s, label in enumerate(book.plan.labels) if s not in found.get(label, ())]


def _without(sheet, keep) -> Sheet:
    layers = tuple(Layer("ids", "label", tuple(t for t in layer.shapes if keep(t)))
                   if layer.name == "ids" else layer for layer in sheet.layers)
    return Sheet(sheet.width, sheet.height, layers, sheet.name)


def test_every_strand_of_the_pentagon_flower_is_named_and_pointed_at():
    """The pentagon flower at 23 cm: page 1 had no room for 41 strands' IDs; with the shortest
    unnamed strands given their plates first and a finer, wider search for the rest it has
    none for 22 (page 1 names 158 strands); those are named on the two pages of crossing
    callouts (pages 3-4, 7 pages in all, as before they had a page of their own), each with a
    leader into one of its tiles. Every one of the 180 strands is then found, and those pages'
    texts pass the page checks. Planted: one callout dropped from a page, or two swapped: those
    strands are not found."""
    book, weave = pentagon_book(), weaves("pentagon-flower", 3)[-1]
    assert book.id_pages == book.callout_pages == (3, 4)
    assert book.strip_pages[0] == 5 and len(book.drawing.sheets) == 7
    assert not unfound(book, weave)
    for n in (3, 4):
        assert not [r for r in sheet_checks(book, n) if r["broken"]]
    ids = [t for n in (3, 4) for layer in book.drawing.sheets[n - 1].layers
           if layer.name == "ids" for t in layer.shapes]
    assert len(ids) == 22 and len({t.text for t in ids}) == 22
    assert sum(len(pointed_at(book.drawing.sheets[0], weave, ()).get(label, ()))
               for label in book.plan.labels) == 180 - 22
    cover = " ".join(t.text for layer in book.drawing.sheets[0].layers for t in layer.shapes
                     if hasattr(t, "text"))
    assert "and the strands this page has no room to name, are called out on pages 3-4" in cover
    sheet = book.drawing.sheets[2]
    ids = next(layer for layer in sheet.layers if layer.name == "ids").shapes
    for planted in ("dropped", "swapped"):
        a, b = ids[0], ids[1]
        if planted == "dropped":
            bad = _without(sheet, lambda t: t is not a)
        else:
            swap = {id(a): moved(a, text=b.text), id(b): moved(b, text=a.text)}
            bad = Sheet(sheet.width, sheet.height, tuple(
                Layer("ids", "label", tuple(swap.get(id(t), t) for t in layer.shapes))
                if layer.name == "ids" else layer for layer in sheet.layers), sheet.name)
        sheets = list(book.drawing.sheets)
        sheets[2] = bad
        bad_book = moved(book, drawing=moved(book.drawing, sheets=tuple(sheets)))
        want = [a.text] if planted == "dropped" else sorted([a.text, b.text])
        assert sorted(unfound(bad_book, weave)) == want, planted


def test_a_pattern_whose_page_1_names_every_strand_has_no_strand_page():
    """The small square grid's page 1 names every strand: no page of strand IDs."""
    book = small_book()
    w = weaves("square-grid:2x2", 2)[-1]
    assert not unfound(book, w) and book.id_pages == ()
    assert not any(s.name.endswith("strand IDs") for s in book.drawing.sheets)
    assert np.all([n in book.extra_pages for n in (1, 2)])


@pytest.mark.parametrize("n", [1, 3, 4])
def test_the_leader_ends_of_page_1_and_the_strand_pages_meet_no_other_leader(n):
    """No two leader lines meet on page 1 or on the pages naming strands beside crossings."""
    book = pentagon_book()
    sheet = book.drawing.sheets[n - 1]
    shapes = next(layer for layer in sheet.layers if layer.name == "pattern").shapes
    lines = shapely.linestrings([line for s in shapes if isinstance(s, Polylines)
                                 and s.style.stroke == "#000000" for line in s.lines()])
    i, j = shapely.STRtree(lines).query(lines, predicate="intersects")
    assert not [(a, b) for a, b in zip(i.tolist(), j.tolist()) if a < b]


def test_strands_whose_one_tile_is_a_called_out_crossing_keep_a_page_of_their_own():
    """The pentagon flower at 23 cm in the module layout: its 70 crossings and 24 unnamed
    strands would fit page 3 together, but three of those strands (C2, C14, D8) lie on top of
    one tile only, itself a crossing called out on that page: a ring round its dot would show
    the dot, not the strand's colour. The strands keep page 4 and every page passes the
    checks. Planted: shared all the same: page 3 has IDs outside their strands."""
    from tests.papermodel.test_strands import pentagon_module_book

    book = pentagon_module_book()
    assert book.callout_pages == (3,) and book.id_pages == (4,)
    assert not unfound(book, weaves("pentagon-flower", 3)[-1])
    for n in range(1, len(book.drawing.sheets) + 1):
        assert not [r for r in sheet_checks(book, n) if r["broken"]], n
