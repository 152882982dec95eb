"""The form's words: a field's label, its bounds, and click's help as a maker in a browser
reads it, with fields, not flags.

The CLI's ``--help`` keeps its words; the web form shows each option's help through
:func:`form_words`, one transform instead of a second copy of every help string: no preset
folder (the form lists the presets), no file (the web app reads no file a request names), no
comma list (the form has checkboxes), ``-o`` is the kit, and an option named in a help is the
field's label.
"""

from __future__ import annotations

import re

WEB_WORDS = (  # (the CLI's words, the form's words), in this order
    (r" \(templates/[a-z]+\)|(?<=\()templates/[a-z]+: ", ""),  # a preset folder
    (r",? or a \.toml file", ""),
    (r", comma-separated", ""),
    (r"\bbeside -o\b", "in the kit"),
    (r"(?<![\w-])-o\b", "the kit"),  # the job's output, which the form does not show
)
TICKED = {  # command -> flag -> why the form ticks it at first (the command's default is off)
    "puzzle": {"numbers": "Ticked at first here: a maker finds each piece's place by its "
                          "number (the guides show the same numbers); untick it for pieces "
                          "without numbers."}}
FORMAT_LABELS = {"pdf": "PDF: print it", "svg": "SVG: view it, or edit it in Inkscape",
                 "dxf": "DXF: CAD or laser software", "png": "PNG: a picture",
                 "obj": "OBJ: the 3-D model (a surface's)",
                 "glb": "GLB: the 3-D model, coloured", "json": "JSON: weave-cut's mesh",
                 "lbrn2": "LightBurn project (.lbrn2): layers set for your laser"}
NAMED = re.compile(r"(?<![\w-])--([a-z][a-z0-9-]*)")  # an option named in a help
HINT = re.compile(r"'(?:-\w' / ')?--([a-z][a-z0-9-]*)(?:' / '-\w)?'|'(INPUT|NAME)'")  # click's


def form_words(text: str, labels: dict[str, str]) -> str:
    """``text`` in the form's words; ``labels``: option key (``laser-card``) -> how the form
    names its field. An option without a field is left as it is (the web tests find it).

    >>> form_words("With --laser-card: colour conventions (templates/laser).",
    ...            {"laser-card": "“Laser-cut card” ticked"})
    'With “Laser-cut card” ticked: colour conventions.'
    >>> form_words("a cut file per page beside -o, or a .toml file", {})
    'a cut file per page in the kit'
    """
    for cli_words, web_words in WEB_WORDS:
        text = re.sub(cli_words, web_words, text)
    return NAMED.sub(lambda found: labels.get(found.group(1), found.group(0)), text)


def without(text: str, keys) -> str:
    """Click's help ``text`` with every aside and sentence that names one of the options
    ``keys`` left out: the help of a page on which those fields are not offered.

    >>> without("a4 or WxH (with --laser-card: the instructions' pages). Blank.", {"laser-card"})
    'a4 or WxH. Blank.'
    >>> without("Snub steps. With --cutter: cut them. Then weave.", ["cutter"])
    'Snub steps. Then weave.'
    """
    named = "|".join(re.escape(k) for k in sorted(keys))
    if not named:
        return text
    option = rf"(?<![\w-])--(?:{named})\b"
    text = re.sub(rf"\s*\((?:[^()]*?{option}[^()]*)\)", "", text)
    sentences = re.split(r"(?<=[.!?])\s+(?=[A-Z\[])", text)
    return " ".join(s for s in sentences if not re.search(option, s))


def refusal_words(message: str, labels: dict[str, str], fields: dict[str, str]) -> str:
    """A refusal (click's message, a reader's) in the form's words: the option click's hint
    names (``'--levels' / '-n'``, ``'INPUT'``) as its field, ``fields``: option key -> the
    field's name; the rest as :func:`form_words` turns a help.

    >>> refusal_words("Invalid value for '--levels' / '-n': 0 is not in the range 1<=x<=8.",
    ...               {}, {"levels": "Levels"})
    'Invalid value for “Levels”: 0 is not in the range 1<=x<=8.'
    >>> refusal_words("--material goes with --laser-card", {"material": "“Material”",
    ...               "laser-card": "“Laser-cut card” ticked"}, {})
    '“Material” goes with “Laser-cut card” ticked'
    """
    def field(found: re.Match) -> str:
        k = (found.group(1) or found.group(2)).lower()
        return f"“{fields[k]}”" if k in fields else found.group(0)

    return form_words(HINT.sub(field, message), labels)


def bounds(t) -> str:
    """'from 1 to 8', 'over 0, at most 10000' (click's bounds, open or closed)."""
    def number(x) -> str:
        return f"{x:g}" if isinstance(x, float) else str(x)

    low = None if t.min is None else ("over " if t.min_open else "from ") + number(t.min)
    high = None if t.max is None else ("below " if t.max_open else "to ") + number(t.max)
    if low and high and not t.min_open and not t.max_open:
        return f"{low} {high}"
    return ", ".join(w for w in (low, high and high.replace("to ", "at most ")) if w)


def field_label(k: str) -> str:
    """The label of the field of option ``k``."""
    return {"laser-card": "Laser-cut card", "no-smooth": "No smoothing (skip operation 4)",
            "allow-nonconvex": "Allow non-convex faces", "name": "Figure",
            "input": "Input", "cell": "Cell size", "formats": "Files per sheet"}.get(
        k, k.replace("-", " ").capitalize())
