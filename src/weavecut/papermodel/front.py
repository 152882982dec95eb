"""The pages before the strips: the assembly sheet, the weaving page, the pages calling out the
crossings the strips leave unnamed and naming the strands page 1 has no room for, laid out
until page 1's words agree with the pages after it."""

from __future__ import annotations

from ..layout.drawing import Sheet
from ..weave.model import Weave
from .assembly import assembly_sheet, weaving_sheet
from .crossings import crossing_page_count, crossing_pages, id_pages, named_by_callouts
from .modules import ModulePlan
from .pages import PageArea, page_layers
from .wording import PRINTED, Words

ON_COVER = 24  # at most this many unnamed crossings are tried on page 1
SETTLE = 6  # page 1 laid out at most this many times: its words name the pages after it


def front_pages(weave: Weave, plan: ModulePlan, colours, area: PageArea, crossings, book_for,
                tile_size: float, turn: float, title: str, words: Words = PRINTED):
    """(book, sheets): the assembly sheet, the weaving page, the pages of the crossings the
    strips leave unnamed (``crossings``, see :func:`.crossings.left_out_crossings`), which are
    called out on page 1 where they all fit, else on pages of their own, and the strands page 1
    has no room to name: named first in the callout of a crossing where one lies on top
    (:func:`.crossings.named_by_callouts`), the others called out beside the crossings on
    their pages (columns of m plates, IDs or callouts alike: ceil((a + b) / m) pages, never
    more than ceil(a / m) + ceil(b / m) apart), or where the crossings are on page 1 or there
    are none, on pages of their own.
    ``book_for(own, ids, shared)`` gives (the book with ``own`` crossing pages, naming strands
    too where ``shared``, and ``ids`` strand pages after them, its page count, the first
    crossing page's number); ``words`` name what the maker holds. Page 1 is laid out first as
    if the crossing pages named strands too (a pattern too big to call out its crossings on
    page 1 mostly has strands it cannot name): once where it has such strands."""
    area = area.plain  # their subtitles are short
    alone = 0  # the crossing pages without strands (counted until page 1 settles, then drawn)
    on_cover = crossings if len(crossings) <= ON_COVER else ()
    if not on_cover and crossings:
        alone = crossing_page_count(plan, area, crossings, words)
    own, ids = alone, 0  # the crossing pages; pages of strand IDs of their own
    shared = bool(alone)  # the crossing pages name strands too
    for _ in range(SETTLE):  # page 1's words name the other pages: until their count holds
        book, total, first = book_for(own, ids, shared)
        cover, missing, unnamed = assembly_sheet(weave, book, tile_size, turn, title, total,
                                                 on_cover, words)
        if missing:  # the crossings do not all fit on page 1: pages of their own
            on_cover = ()
            own = alone = crossing_page_count(plan, area, crossings, words)
            continue
        called, rest = named_by_callouts(unnamed, crossings)
        was = (own, ids, shared)
        shared = bool(alone and unnamed)  # the crossing pages name strands too
        own = crossing_page_count(plan, area, crossings, words, rest, called) if shared \
            else alone
        ids = crossing_page_count(plan, area, (), unnamed=rest) if rest and not shared else 0
        if (own, ids, shared) == was:
            break
    else:
        raise AssertionError("page 1 and the pages of the strands it does not name never "
                             "agreed on their number")
    own_pages = [] if not alone else crossing_pages(
        weave, plan, colours, area, crossings, turn, words, *((rest, called) if shared else ()))
    named = id_pages(weave, plan, colours, area, rest, turn) if ids else []
    sheets = [cover, weaving_sheet(weave, book, turn, title, total, words)]
    what = ("Crossings the strips and strands page 1 do not name (the strand named first lies "
            "on top)" if shared else
            "Crossings the strips do not name: the strand named first lies on top")
    sheets += [Sheet(area.width, area.height, layers + tuple(page_layers(
        area, title, what, n, total, legend=words.legend, cut=words.cut_line)),
        f"page {n}: crossings{' and strand IDs' if shared else ''}")
        for n, layers in enumerate(own_pages, start=first)]
    sheets += [Sheet(area.width, area.height, layers + tuple(page_layers(
        area, title, "Strand IDs page 1 has no room for: each with a line to one of its tiles",
        n, total, legend=words.legend, cut=words.cut_line)), f"page {n}: strand IDs")
        for n, layers in enumerate(named, start=first + len(own_pages))]
    return book, sheets
