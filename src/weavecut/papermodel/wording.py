"""The words on a strand book's pages: wrapped paragraphs of running text, and which page holds
which strip ("p. 3: A1-A4, B2")."""

from __future__ import annotations

from ..layout.drawing import Text
from ..layout.labels import text_width, wrap

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
    """"A1-A4, A6, X1" from strip labels in any order."""
    out, start, prev = [], None, None
    for lab in sorted(labels, key=_label_key) + [None]:
        key = None if lab is None else _label_key(lab)
        if prev is not None and key is not None and key[0] == prev[0] and key[1] == prev[1] + 1:
            prev = key
            continue
        if start is not None:
            out.append(_key_text(start) if start == prev
                       else f"{_key_text(start)}-{_key_text(prev)}")
        start = prev = key
    return ", ".join(out)


def page_index(book) -> str:
    """"p. 3: A1-A4, B2; p. 4: ..." which page holds which strip of a
    ``StrandBook``."""
    parts = []
    for n in book.strip_pages:
        labels = {p.label.split(" ")[0] for k, p in book.pieces if k == n}
        parts.append(f"p. {n}: {strip_runs(labels)}")
    return "; ".join(parts)
