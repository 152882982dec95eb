"""Text every output format can hold: SVG and DXF (XML/ASCII-safe), PDF, PNG chunks and JSON.

File names and command lines may hold control characters and bytes that are not UTF-8 (Python
keeps them as lone surrogates); neither is allowed in XML 1.0 nor encodable as UTF-8.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import replace

_UNSAFE = re.compile("[\x00-\x1f\x7f-\x9f\ud800-\udfff\ufffe\uffff]")


def clean(text: str) -> str:
    """``text`` with every control character and undecodable byte replaced by U+FFFD.

    Examples
    --------
    >>> clean("m\\x01.obj"), clean("caf\\udce9.obj"), clean("plain")
    ('m\\ufffd.obj', 'caf\\ufffd.obj', 'plain')
    """
    return _UNSAFE.sub("\ufffd", text)


def counted(n: int, noun: str, plural: str | None = None) -> str:
    """``n`` and ``noun``, in the plural unless ``n`` is 1 (``plural``: an irregular one;
    by default an -s, or -ies after a consonant and y).

    Examples
    --------
    >>> counted(1, "copy"), counted(3, "copy"), counted(0, "page"), counted(1, "sheet")
    ('1 copy', '3 copies', '0 pages', '1 sheet')
    """
    if n == 1:
        return f"{n} {noun}"
    if plural is None:
        plural = (noun[:-1] + "ies" if noun.endswith("y") and noun[-2:-1] not in "aeiou"
                  else noun + "s")
    return f"{n} {plural}"


def nearest(word: str, choices) -> str:
    """' (did you mean X?)' for the closest of ``choices`` to a name a person typed, or ''.

    Examples
    --------
    >>> nearest("squre-grid", ["pentagon", "square-grid"]), nearest("xyz", ["pentagon"])
    (" (did you mean 'square-grid'?)", '')
    """
    match = difflib.get_close_matches(word, sorted(choices), n=1, cutoff=0.6)
    return f" (did you mean {match[0]!r}?)" if match else ""


def clean_drawing(drawing):
    """``drawing`` (a ``layout.drawing.Drawing``) with its title, metadata, sheet and layer
    names and the strings of its Text shapes ``clean``."""

    def shape(s):
        return replace(s, text=clean(s.text)) if isinstance(getattr(s, "text", None), str) else s

    sheets = tuple(replace(sheet, name=clean(sheet.name), layers=tuple(
        replace(layer, name=clean(layer.name), shapes=tuple(map(shape, layer.shapes)))
        for layer in sheet.layers)) for sheet in drawing.sheets)
    return replace(drawing, title=clean(drawing.title), sheets=sheets,
                   metadata=tuple((clean(k), clean(v)) for k, v in drawing.metadata))
