"""Every strand can be found: its ID is printed on the assembly pages and points at that
strand, read from the Drawing alone (the pattern's tiles, the white plates, the leader lines
and the texts of each page's "ids" and "crossings" layers), apart from the placement code."""

from __future__ import annotations

from dataclasses import replace as moved
from functools import lru_cache
from pathlib import Path
from unittest import mock

import numpy as np
import pytest
import shapely

from weavecut.layout.drawing import Layer, Polygons, Polylines, Sheet
from weavecut.layout.labels import text_box
from weavecut.papermodel import cutter_words, front, printcut
from weavecut.papermodel.book import strand_book, tile_size_for
from weavecut.papermodel.checks import sheet_checks
from weavecut.weave.colour import palette

from tests.papermodel.test_strands import pentagon_book, small_book, weaves

pytestmark = pytest.mark.slow  # the pentagon flower's whole book, read back page by page


def pointed_at(sheet, weave) -> dict[str, set[int]]:
    """{ID: the strands it points at} over the texts of ``sheet`` that name strands: an "ids"
    text inside a tile of the pattern names the strand on top there; one on a white plate, the
    strand on top where the plate's leader line ends; a "crossings" callout "C8 over A14" (on
    a plate) names its first strand only, C8, as the strand on top where its leader ends (A14
    is hidden there)."""
    layers = {layer.name: layer for layer in sheet.layers}
    texts = [(t, t.text) for t in layers["ids"].shapes] if "ids" in layers else []
    texts += [(t, t.text.split(" over ")[0]) for t in layers["crossings"].shapes] if (
        "crossings" in layers) else []
    if not texts:
        return {}
    shapes = layers["pattern"].shapes
    tiles = shapes[0].to_shapely()
    tree = shapely.STRtree(tiles)
    plates = [g for s in shapes if isinstance(s, Polygons) and s.style.fill == "#ffffff"
              for g in s.to_shapely().tolist()]
    lines = [line for s in shapes if isinstance(s, Polylines) and s.style.stroke == "#000000"
             for line in s.lines()]
    out: dict[str, set[int]] = {}
    for t, name in texts:
        box = text_box(t)
        plate = [g for g in plates if g.covers(box)]
        if plate:
            ends = [shapely.Point(e[-1]) for e in lines
                    if plate[0].exterior.distance(shapely.Point(e[0])) < 1e-6]
        else:
            ends = [box.centroid]
        hit = {int(k) for e in ends for k in tree.query(e, predicate="within")}
        out.setdefault(name, set()).update(int(weave.tile_over[k]) for k in hit)
    return out


def unfound(book, weave) -> list[str]:
    """The strand IDs that no text on the pages before the strips points at their strand."""
    found: dict[str, set[int]] = {}
    for n in book.extra_pages:
        for text, strands in pointed_at(book.drawing.sheets[n - 1], weave).items():
            found.setdefault(text, set()).update(strands)
    return [label for s, label in enumerate(book.plan.labels) if s not in found.get(label, ())]


def planted(book, n: int, layer: str, text, new=None):
    """``book`` with the text ``text`` of page ``n``'s layer ``layer`` replaced by ``new``, or
    dropped."""
    sheet = book.drawing.sheets[n - 1]
    layers = tuple(Layer(la.name, la.role, tuple(new if t is text else t for t in la.shapes
                                                 if t is not text or new is not None))
                   if la.name == layer else la for la in sheet.layers)
    sheets = list(book.drawing.sheets)
    sheets[n - 1] = Sheet(sheet.width, sheet.height, layers, sheet.name)
    return moved(book, drawing=moved(book.drawing, sheets=tuple(sheets)))


def texts_of(book, pages, layer: str) -> list[tuple[int, object]]:
    """(page, text) of every text of ``layer`` on ``pages``."""
    return [(n, t) for n in pages for la in book.drawing.sheets[n - 1].layers
            if la.name == layer for t in la.shapes]


def test_every_strand_of_the_pentagon_flower_is_named_and_pointed_at():
    """The pentagon flower at 23 cm: page 1 has no room for 22 strands' IDs (it names 158).
    19 of them lie on top at a crossing called out on pages 3-4, whose callout ("C8 over A14")
    names them; the other 3 get a callout of their own there (22 before the callouts counted;
    7 pages in all either way). Every one of the 180 strands is then found, and those pages'
    texts pass the page checks. Planted: an ID callout or the one crossing callout naming a
    strand dropped, that callout told backwards ("A14 over C8"), two IDs swapped: those
    strands are not found."""
    book, weave = pentagon_book(), weaves("pentagon-flower", 3)[-1]
    assert book.id_pages == book.callout_pages == (3, 4)
    assert book.strip_pages[0] == 5 and len(book.drawing.sheets) == 7
    assert not unfound(book, weave)
    for n in (3, 4):
        assert not [r for r in sheet_checks(book, n) if r["broken"]]
    ids = texts_of(book, (3, 4), "ids")
    assert len(ids) == 3 and len({t.text for _, t in ids}) == 3
    on_cover = pointed_at(book.drawing.sheets[0], weave)
    assert sum(s in on_cover.get(label, ()) for s, label in enumerate(book.plan.labels)) == 158
    cover = " ".join(t.text for layer in book.drawing.sheets[0].layers for t in layer.shapes
                     if hasattr(t, "text"))
    assert "and the strands this page has no room to name, are called out on pages 3-4" in cover
    callouts = texts_of(book, (3, 4), "crossings")
    firsts = [t.text.split(" over ")[0] for _, t in callouts]
    n, only = next((n, t) for n, t in callouts if t.text.split(" over ")[0] not in on_cover
                   and firsts.count(t.text.split(" over ")[0]) == 1)  # one callout names it
    top, below = only.text.split(" over ")
    assert sorted(unfound(planted(book, n, "crossings", only), weave)) == [top]
    backwards = moved(only, text=f"{below} over {top}")
    assert sorted(unfound(planted(book, n, "crossings", only, backwards), weave)) == [top]
    (n, a), (m, b) = ids[:2]
    assert unfound(planted(book, n, "ids", a), weave) == [a.text]
    swapped = planted(planted(book, n, "ids", a, moved(a, text=b.text)), m, "ids", b,
                      moved(b, text=a.text))
    assert sorted(unfound(swapped, weave)) == sorted([a.text, b.text])


@lru_cache(maxsize=None)
def default_pentagon_book(cutter: str | None = None):
    """The pentagon flower as ``strands pentagon-flower`` lays it out (20 mm octagons), or at
    23 cm for a cutter as ``--cutter`` does (the Silhouette kit of the recipe
    pentagon-flower-cut-by-machine)."""
    ws = list(weaves("pentagon-flower", 3))
    if cutter is None:
        return strand_book(ws, palette("maritime-12"), tile_size=20.0)
    machine, out = printcut.cutter(cutter), Path("pf.pdf")
    return strand_book(ws, palette("okabe-ito"), (210.0, 297.0), tile_size_for(ws[-1], 230.0),
                       max(10.0, machine.margin), limit=machine.limit(210.0, 297.0),
                       words=cutter_words.cutter_words(machine, out), gap=printcut.WASTE,
                       page_note=cutter_words.cut_file_note(out, machine), bleed=printcut.BLEED)


@pytest.mark.parametrize("cutter, pages, callouts, ids", [(None, 8, (3,), 14),
                                                          ("silhouette", 8, (3, 4), 8)])
def test_the_crossing_callouts_name_strands_so_no_page_of_strand_ids(cutter, pages, callouts,
                                                                     ids):
    """The pentagon flower at its default size (62 crossings called out, page 1 has no room
    for 22 strands: 8 named by their crossings' callouts, 14 beside them) and the Silhouette
    kit at 23 cm (155 crossings, page 1 has no room for 44 strands: 36 named by callouts, 8
    beside them): no page of strand IDs of its own, 8 pages each (9 before the callouts
    counted), every strand found and every page passing the checks."""
    book = default_pentagon_book(cutter)
    weave = weaves("pentagon-flower", 3)[-1]
    assert len(book.drawing.sheets) == pages and book.callout_pages == book.id_pages == callouts
    assert len(texts_of(book, callouts, "ids")) == ids
    assert not unfound(book, weave)
    for n in range(1, len(book.extra_pages) + 1):
        assert not [r for r in sheet_checks(book, n) if r["broken"]], n


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


def test_strands_on_top_of_one_called_out_crossing_only_are_named_by_its_callout():
    """The pentagon flower at 23 cm in the module layout: page 1 has no room for 24 strands'
    IDs. Three of them (C2, C14, D8) lie on top of one tile only, a crossing called out on page
    3, where an ID's ring could only go round the crossing's dot: they had a page 4 of their
    own (5 pages). That callout names them now; 9 of the 24 are named by callouts, 15 by IDs
    beside them: 4 pages, every strand found, every page passing the checks. Planted: a
    callout counted as naming the strand below it too: strands named nowhere."""
    from tests.papermodel.test_strands import pentagon_module_book

    book, weave = pentagon_module_book(), weaves("pentagon-flower", 3)[-1]
    assert book.callout_pages == book.id_pages == (3,) and len(book.drawing.sheets) == 4
    assert len(texts_of(book, (3,), "ids")) == 15
    assert not unfound(book, weave)
    for n in range(1, len(book.drawing.sheets) + 1):
        assert not [r for r in sheet_checks(book, n) if r["broken"]], n
    labels = list(book.plan.labels)
    alone = [labels[s] for s in range(weave.n_strands) if weave.strand(s)[1].sum() == 1]
    firsts = {t.text.split(" over ")[0] for _, t in texts_of(book, (3,), "crossings")}
    assert {"C2", "C14", "D8"} <= set(alone) and {"C2", "C14", "D8"} <= firsts

    def both(unnamed, crossings):  # the strand below named too
        strands = {s for c in crossings for s in c[1:]}
        return ([u for u in unnamed if u[0] in strands],
                [u for u in unnamed if u[0] not in strands])

    with mock.patch.object(front, "named_by_callouts", both):
        bad = pentagon_module_book.__wrapped__()
    assert unfound(bad, weave)


def test_the_counted_crossing_pages_are_the_pages_drawn():
    """Page 1 settles on counts (``crossing_page_count``) and the pages are drawn once after:
    the count is the number drawn, for crossings, strands of their own or both, about where
    a second page starts (found by drawing) and at the pentagon flower's 155 and 22. Planted:
    the count leaving out the strands (or the crossings) fails."""
    from weavecut.papermodel.crossings import (crossing_page_count, crossing_pages,
                                               left_out_crossings)
    from weavecut.papermodel.pages import PageArea

    book, weave = pentagon_book(), weaves("pentagon-flower", 3)[-1]
    found = left_out_crossings(weave, book.plan, [p for _, p in book.pieces], book.layout)
    area = PageArea(210.0, 297.0, 10.0).plain
    strands = [(int(weave.tile_over[t]), t) for t, _, _ in found]

    def drawn(c: int, u: int) -> int:
        return len(crossing_pages(weave, book.plan, book.colours, area, found[:c], 0.0,
                                  unnamed=strands[:u]))

    one = max(c for c in range(4, len(found) + 1, 4) if drawn(c, 0) == 1)  # a page's worth
    assert drawn(one + 8, 0) == 2
    for c, u in ((one, 0), (one, 8), (one - 4, 8), (0, one + 8), (len(found), 22), (3, 0)):
        assert crossing_page_count(book.plan, area, found[:c], unnamed=strands[:u]) == \
            drawn(c, u), (c, u)
