"""The words of a page's header: the title shortened to its line, the subtitle wrapped onto
the header's lines, and a strip page's list of strips fitted to the room the subtitle leaves.

>>> labels = ["A1", "A2", "A3", "B5", "B7 1/2", "C1", "C4", "C6", "C8", "D2", "D4"]
>>> wrapped(strips_subtitle("", labels, 200.0, 1), 200.0, 1)
['Strips: A1-A3, B5, B7 1/2, C1, C4, C6, C8, D2, D4']
>>> wrapped(strips_subtitle("", labels, 80.0, 1), 80.0, 1)
['Strips: A1-A3 and 8 more (page 1 lists them)']
"""

from __future__ import annotations

from ..layout.labels import MIN_CAP, text_width, wrap
from ..text import counted
from .wording import runs

SMALL = MIN_CAP  # cap height of the subtitle and the rest of the page furniture (mm)
MORE = "and {} more (page 1 lists them)"


def shortened(text: str, width: float, size: float) -> str:
    """``text``, or where it is wider than ``width`` mm at cap height ``size`` (a title naming
    a deep input path), its start and end joined by "..." in place of as little of its middle
    as must go."""
    if text_width(text, size) <= width:
        return text
    for keep in range(len(text) - 1, 0, -1):  # characters kept, not mesh elements
        short = text[:(keep + 1) // 2] + "..." + text[len(text) - keep // 2:]
        if text_width(short, size) <= width:
            return short
    return "..."


def wrapped(text: str, width: float, lines: int) -> list[str]:
    """``text`` broken at spaces into at most ``lines`` lines no wider than ``width`` mm (the
    last line is shortened with an ellipsis if it must be)."""
    out = wrap(text, width, SMALL)
    if len(out) > lines:
        last = " ".join(out[lines - 1:])
        while text_width(last + " ...", SMALL) > width and " " in last:
            last = last.rsplit(" ", 1)[0]
        out = out[:lines - 1] + [last + " ..."]
    return out


def header_lines(head: str, width: float) -> int:
    """The subtitle lines (of ``width`` mm) a strip page needs for ``head`` (say, its cut
    file's name) and the shortest list of its strips, one strip and how many more."""
    return len(wrap(f"{head}Strips: A1 {MORE.format(999)}", width, SMALL))


def strips_subtitle(head: str, labels, width: float, lines: int) -> str:
    """``head`` and "Strips: A1-A4, B7 1/2" naming ``labels`` where that fits ``lines`` lines
    of ``width`` mm; else the list's first items that fit and "and 12 more (page 1 lists
    them)": the page's strips are named on them, and the whole list is on page 1."""
    items = runs(labels)
    for k in range(len(items), 0, -1):
        left = sum(n for _, n in items[k:])
        text = (f"{head}Strips: {', '.join(t for t, _ in items[:k])}"
                + (f" {MORE.format(left)}" if left else ""))
        if len(wrap(text, width, SMALL)) <= lines:
            return text
    return f"{head}{counted(len(labels), 'strip')} (page 1 lists them)"
