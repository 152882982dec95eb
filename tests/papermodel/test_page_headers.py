"""A strip page's header, read back from the Drawing: the title, the subtitle on as many lines as
its head needs (a print-and-cut page's file names in full, however long the output's name) and
the list of the page's strips, whole or its first items and how many more; every text of the
page furniture inside the page's margins and off the area the strips may use."""

from __future__ import annotations

import re
from functools import lru_cache
from pathlib import Path

import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut import inputs
from weavecut.layout.drawing import Text
from weavecut.layout.labels import text_box
from weavecut.papermodel import cutter_words, printcut
from weavecut.papermodel.book import strand_book
from weavecut.papermodel.header import strips_subtitle, wrapped
from weavecut.papermodel.pages import FURNITURE_GAP
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

from tests.papermodel.test_cutter import strip_names

LETTER = (215.9, 279.4)
LONG = Path("a very long output name for my kitchen table weave.pdf")
LISTED = re.compile(r"Strips: (?P<names>.*?)(?: and (?P<more>\d+) more \(page 1 lists them\))?$")


@lru_cache(maxsize=None)
def weaves():
    return tuple(snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2)))


@lru_cache(maxsize=None)
def cricut_book(output: Path = LONG):
    """``strands --cutter cricut --page letter -o OUTPUT``'s book, as the command lays it."""
    machine = printcut.cutter("cricut")
    return strand_book(list(weaves()), palette("maritime-4"), LETTER, 20.0, machine.margin,
                       limit=machine.limit(*LETTER), gap=printcut.WASTE, bleed=printcut.BLEED,
                       words=cutter_words.cutter_words(machine, output),
                       page_note=cutter_words.cut_file_note(output, machine))


def narrow_book(layout: str, page: tuple[float, float]):
    """A 3 x 3 square grid's book on a narrow page, where a page's subtitle is long."""
    ws = snub_weaves(subdivide(inputs.get("square-grid:3x3"), 2))
    return strand_book(list(ws), palette("maritime-12"), page, 20.0, layout=layout)


def header(book, n: int) -> tuple[list[Text], str]:
    """(the page furniture's texts, page ``n``'s subtitle: its lines under the title, read top
    down and joined); no line starts inside a strip part's name ("8" | "2/2")."""
    sheet = book.drawing.sheets[n - 1]
    texts = [s for layer in sheet.layers if layer.name == "page" for s in layer.shapes
             if isinstance(s, Text)]
    top = book.area.box[3]
    lines = sorted((t for t in texts if t.y > top and t.anchor == "start"), key=lambda t: -t.y)
    assert not any(re.match(r"\d+/\d+", t.text) for t in lines)
    return texts, " ".join(t.text for t in lines[1:])  # lines[0]: the title


def assert_furniture_in_place(book, n: int) -> None:
    """Every text of page ``n``'s furniture inside the margins, none on the strips' area, and
    each at least ``FURNITURE_GAP`` from the next."""
    texts, _ = header(book, n)
    area = book.area
    m = area.margin
    inner = shapely.box(m, m, area.width - m, area.height - m)
    strips = shapely.box(*area.box)
    boxes = [text_box(t) for t in texts]
    for t, b in zip(texts, boxes):
        assert inner.covers(b), f"page {n}: {t.text!r} leaves the page"
        assert not strips.intersection(b).area, f"page {n}: {t.text!r} lies on the strips"
    for i, b in enumerate(boxes):
        for c in boxes[i + 1:]:
            assert b.distance(c) >= FURNITURE_GAP - 1e-9


def assert_lists_its_strips(book, n: int, subtitle: str) -> None:
    """The subtitle names only the page's strips, and says how many more there are."""
    on_page = {p.label for k, p in book.pieces if k == n}
    listed = LISTED.search(subtitle)
    assert listed, subtitle
    named = strip_names(listed["names"])
    assert named and set(named) <= on_page and len(set(named)) == len(named), (named, on_page)
    assert len(named) + int(listed["more"] or 0) == len(on_page)


def test_a_long_output_name_is_printed_whole_on_two_lines():
    """The Cricut page names its print image and cut file in full (a maker's kitchen-table
    name cut off at "a very long output ..." before); the header holds them, so no text runs
    over the strips. Planted: the subtitle held to one line, as before, fails."""
    book = cricut_book()
    assert book.area.header_lines == 2
    stem = LONG.stem
    for n in book.strip_pages:
        _, subtitle = header(book, n)
        assert f"Print image: {stem}-p{n:02d}-print.svg; cut file: {stem}-p{n:02d}-cut.svg" \
            in subtitle
        assert_lists_its_strips(book, n, subtitle)
        assert_furniture_in_place(book, n)
    short = cricut_book(Path("sq.pdf"))
    assert short.area.header_lines == 1 and short.strip_pages[0] == book.strip_pages[0]


def test_a_long_list_of_strips_is_cut_after_a_whole_item_and_counted():
    """On a narrow page the module layout's words and list of parts ("8 2/2") take the lines
    they need, and a long list of strips ends after a whole item and says how many more the
    page holds (page 1 lists them all). Planted: the list cut off mid-way with "..." or held
    to one line (as before) fails."""
    module = narrow_book("module", (100.0, 200.0))
    assert module.area.header_lines == 3
    mixed = narrow_book("mixed", (120.0, 240.0))
    for book in (module, mixed):
        for n in book.strip_pages:
            _, subtitle = header(book, n)
            assert_lists_its_strips(book, n, subtitle)
            assert_furniture_in_place(book, n)
    _, subtitle = header(mixed, mixed.strip_pages[0])
    assert subtitle.endswith(" more (page 1 lists them)")  # the case the test is for


@settings(max_examples=200, deadline=None)
@given(st.sets(st.tuples(st.sampled_from("ABCD"), st.integers(1, 40), st.integers(0, 2)),
               min_size=1, max_size=60),
       st.floats(60.0, 300.0), st.integers(1, 3))
def test_a_fitted_list_fits_and_accounts_for_every_strip(strips, width, lines):
    """However many strips and however narrow the header, the fitted subtitle takes at most
    ``lines`` lines, breaks no strip part's name and names every strip or says how many it
    leaves out. Planted: a part's name broken at its space fails."""
    labels = {f"{c}{k}" + (f" {part}/2" if part else "") for c, k, part in strips}
    labels = {lab for lab in labels if lab.split(" ")[0] not in labels}  # whole or in parts
    out = wrapped(strips_subtitle("", labels, width, lines), width, lines)
    assert len(out) <= lines and not out[-1].endswith("...")
    assert not any(re.match(r"\d+/\d+", line) for line in out)  # "A7" | "1/2"
    text = " ".join(out)
    if text.endswith(" strips (page 1 lists them)") or text.endswith(" strip (page 1 lists them)"):
        assert text.startswith(f"{len(labels)} strip")
        return
    listed = LISTED.search(text)
    named = strip_names(listed["names"])
    assert set(named) <= labels and len(set(named)) == len(named)
    assert len(named) + int(listed["more"] or 0) == len(labels)
