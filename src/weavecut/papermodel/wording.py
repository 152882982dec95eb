"""The words on a strand book's pages: wrapped paragraphs of running text, which page holds
which strip ("p. 3: A1-A4, B2"), and the sentences that depend on what the maker holds: strips
printed on paper (``PRINTED``) or laser-cut from coloured card (``CARD``)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..layout.drawing import Text
from ..layout.labels import MIN_CAP, text_width, wrap
from ..text import counted

TEXT = 2.6  # cap height of running text on these pages (mm)
LINE = 4.4  # line pitch (mm)


def paragraphs(items: list[str], x: float, top: float, width: float,
                numbered: bool = False) -> tuple[list[Text], float]:
    """Wrapped lines from ``top`` down; returns the texts and the y below the last line."""
    texts, y = [], top
    for n, item in enumerate(items, start=1):
        head = f"{n}. " if numbered else ""
        indent = text_width(head, TEXT) if numbered else 0.0
        for i, line in enumerate(wrap(item, width - indent, TEXT)):
            y -= LINE
            if i == 0 and head:
                texts.append(Text(x, y, head.strip(), TEXT))
            texts.append(Text(x + indent, y, line, TEXT))
        y -= 0.8
    return texts, y


def _label_key(label: str):
    head = label.rstrip("0123456789")
    return (head, int(label[len(head):] or -1))  # -1: a letter alone (a ball's strand "A")


def _key_text(key) -> str:
    return key[0] + (str(key[1]) if key[1] >= 0 else "")


def strip_runs(labels) -> str:
    """"A1-A4, A6, A7 1/2, X1" from strip labels in any order: whole strips in runs, a part of
    a split strip ("A7 1/2") by itself, where its strip would stand."""
    return ", ".join(text for text, _ in runs(labels))


def runs(labels) -> list[tuple[str, int]]:
    """The items of :func:`strip_runs` ("A1-A4", "A7 1/2"), each with the number of labels
    it stands for (4, 1)."""
    out, start, prev = [], None, None
    whole = [lab for lab in labels if " " not in lab]
    parts = {}
    for lab in labels:
        if " " in lab:
            parts.setdefault(lab.partition(" ")[0], []).append(lab)
    for lab in sorted([*whole, *parts], key=_label_key) + [None]:
        key = None if lab is None else _label_key(lab)
        if (prev is not None and key is not None and key[0] == prev[0]
                and key[1] == prev[1] + 1 and lab not in parts):
            prev = key
            continue
        if start is not None:
            out.append((_key_text(start), 1) if start == prev
                       else (f"{_key_text(start)}-{_key_text(prev)}", prev[1] - start[1] + 1))
        start = prev = key
        if lab in parts:  # a split strip's parts on this page, each by itself
            out += [(part, 1) for part in sorted(parts[lab])]
            start = prev = None
    return out


def colours_said(colours) -> str:
    """The colours a maker prints or buys, in words: "6 strand colours, each with a light
    tint" (where a strip lies under another it is printed in its colour's light tint)."""
    return f"{counted(len(set(colours)), 'strand colour')}, each with a light tint"


def left_out_note(n: int, strips: str | None, where: str) -> str:
    """The warning that ``n`` under-crossing names are left off ``strips`` (None: their own
    strips) and called out ``where``, in the singular for one."""
    one = n == 1
    strips = strips or ("its strip" if one else "their strips")
    return (f"{counted(n, 'under-crossing name')} {'is' if one else 'are'} left off {strips}: "
            f"the tile under {'it' if one else 'them'}, even with a plate over its neighbours, "
            f"is too small for {MIN_CAP:g} mm text; {'it is' if one else 'they are'} called out "
            f"on {where}")


def page_index(book) -> str:
    """"p. 3: A1-A4, B2; p. 4: ..." which page holds which strip of a
    ``StrandBook``."""
    parts = []
    for n in book.strip_pages:
        labels = {p.label for k, p in book.pieces if k == n}
        parts.append(f"p. {n}: {strip_runs(labels)}")
    return "; ".join(parts)


@dataclass(frozen=True)
class Words:
    """The sentences of a flat model's assembly and weaving pages that name what the maker
    holds (the rest is the same for every product).

    Parameters
    ----------
    scale : after the model's size on page 1 (how to print)
    sources : page 1's sentence on where the strips come from and where each one is, or a
        function of the book that gives it; None: the printed book's ("Print the strip pages
        once (p. 3-8). Where each strip is: ...")
    ids : page 1's sentence on the pattern's IDs and arrows
    unnamed_mark : how a crossing too small to name looks on its strip ("... (X there)")
    unnamed_there : the same for the crossing pages ("there the strip X")
    drawn : what page 1's pattern is drawn at a fraction of
    need, cut, tab, unnamed, glue : weaving steps: what to have, how to cut and sort, label
        tabs, unnamed crossings (``{where}``, ``{meaning}``), strips in parts (``{name}``,
        ``{n}``)
    face_up : which side of a strip lies up
    weft_under, strip_under : where a strip goes under (a weft strip; any strip)
    legend : the pages carry the printed strips' scale bar and legend
    cut_line : the strips are printed with their cut lines (and the legend has "cut"); not
        for print and cut, whose strips bleed past theirs
    """

    scale: str
    sources: str | Callable[..., str] | None
    ids: str
    unnamed_mark: str
    unnamed_there: str
    drawn: str
    need: str
    cut: str
    tab: str
    unnamed: str
    glue: str
    face_up: str
    weft_under: str
    strip_under: str
    legend: bool = True
    cut_line: bool = True


PRINTED = Words(
    scale=" Print at 100 % (no fit to page).",
    sources=None,
    ids="Each strand's ID is printed at both ends and along it; arrows show the way its strip "
        "reads. Weaving steps: page 2.",
    unnamed_mark="printed light with no name there",
    unnamed_there="is printed light with no name",
    drawn="its printed size",
    need="You need: the printed pages, scissors or a craft knife, tape or paper clips, a glue "
         "stick and a piece of cardboard a little larger than the model.",
    cut="Cut out every strip along its red line. Sort the strips by ID: the ID printed in the "
        "strip's own colour is its name on page 1; a small ID in a light part names the strand "
        "that lies on top there.",
    tab="Strips too small for their ID carry it on a small tab at one end: cut the tab out with "
        "the strip and cut it off along its dashed line once the strip is woven in.",
    unnamed="A light part with no name is a crossing too small to name on the strip: it is "
            "called out on {where} ({meaning}).",
    glue="Some strips are printed in parts, numbered beside their ID (strip {name}: \"1/{n}\" to "
         "\"{n}/{n}\"; page 1 says which page holds each part): spread glue on the grey band "
         "\"glue 1\" at the end of part 1 and stick it under the tile marked \"{one}\" at the "
         "start of part 2 (\"glue 2\" under \"{two}\", and so on) before weaving, so the tiles "
         "line up.",
    face_up="coloured side up",
    weft_under="where a weft strip is printed light it goes under the strand named there, where "
               "it shows its own colour it lies on top",
    strip_under="Where a strip is printed light it goes under the strand named there; where it "
                "shows its own colour it lies on top.",
)

CARD = Words(
    scale="",
    sources=None,  # the card kit names its sheets (cardkit.card_words)
    ids="The pattern below shows each strand's ID at both ends and along it, and arrows the way "
        "its strip reads (the arrows engraved on the strip). Weaving steps: page 2.",
    unnamed_mark="an engraved dot and no name there",
    unnamed_there="has an engraved dot and no name",
    drawn="the model's size",
    need="You need: the card strips, tape or paper clips, a glue stick and a piece of cardboard "
         "a little larger than the model.",
    cut="Take the strips out of the card sheets and sort them by ID: the large engraved ID is the "
        "strip's name on page 1. Score lines across a strip mark where one tile ends and the "
        "next begins: its tiles lie on top and under in turn, and a small engraved ID in a tile "
        "names the strand that lies on top there.",
    tab="Strips too small for their ID carry it on a small tab at one end, cut with the strip: "
        "cut the tab off along its engraved line once the strip is woven in.",
    unnamed="A tile with an engraved dot and no name is a crossing too small to name on the "
            "strip: the strip goes under there too, and the crossing is called out on {where} "
            "({meaning}).",
    glue="Some strips are cut in parts, numbered beside their ID (strip {name}: \"1/{n}\" to "
         "\"{n}/{n}\"): spread glue on the end of a part beyond its engraved line "
         "(\"glue 1\") and stick it under the tile marked \"{one}\" at the start of the next part "
         "before weaving, so the tiles line up.",
    face_up="engraved side up",
    weft_under="where a weft strip carries a small engraved ID it goes under the strand of that "
               "ID, elsewhere it lies on top",
    strip_under="Where a strip carries a small engraved ID it goes under the strand of that ID; "
                "elsewhere it lies on top.",
    legend=False,
)
