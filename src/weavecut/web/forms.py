"""The web forms, generated from the click commands' own options, so the form and the CLI
cannot drift (a request's values are checked by the command itself: ``queries``).

``fields(name)`` lists a command's options as form fields: the query key is the long option
name without dashes (``--tile-size`` -> ``tile-size``), the INPUT argument is ``input`` (a
figure's NAME ``name``); label, help, default, choices, bounds and unit come from the click
parameter, the help in the form's words (``words.form_words``: fields, not flags). Options
that make no sense on the web are hidden: where the output goes and how it is printed
(``-o``, ``--json``, ``--html``, ``--preview``, ``--list``, ``--force``: the job adds what it
needs) and every option naming a file."""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass, field, replace

import click

from .. import inputs, presets
from ..cli.common import Finite, Formats, Length, PageSize, option_key
from ..schema import nearest
from .jobs import laser_formats, output_formats
from .words import FORMAT_LABELS, TICKED, bounds, field_label, form_words, without

COMMANDS = ("strands", "puzzle", "weave", "subdivide", "figure")  # a page each, in this order
HIDDEN = frozenset({"output", "output-dir", "force", "json", "preview", "html", "list"})
PRESETS = {"palette": "palettes", "material": "materials", "laser": "laser",
           "cutter": "cutters"}  # options whose value names a preset, by key
PRIMARY = {  # shown first; the other options fold away under "More options"
    "strands": ("input", "size", "levels", "palette", "page", "laser-card", "cutter",
                "material", "formats"),  # the last two shown with the laser card only
    "puzzle": ("input", "size", "levels", "material", "palette", "mode", "numbers", "formats"),
    "weave": ("input", "levels", "palette", "style", "outline-level", "size"),
    "subdivide": ("input", "levels", "scheme", "size", "earlier-levels"),
    "figure": ("name",),
}
STARTING = {  # what a page shows before anything is chosen (the argument has no default)
    "strands": ("input", "square-grid"), "weave": ("input", "square-grid"),
    "subdivide": ("input", "pentagon"), "figure": ("name", "square-grid-weaving"),
}
NEEDS = {  # fields that count only with a flag on ("laser-card") or off ("!laser-card")
    "strands": {"material": "laser-card", "laser": "laser-card", "formats": "laser-card",
                "format": "!laser-card"},
}
FORMAT = "format"  # the kit's file format: the suffix of the -o the job gives (not an option)
UPLOAD = re.compile(r"upload:([0-9a-f]{64})")
INPUT = re.compile(r"([a-z0-9-]{1,40})(?::([0-9]{1,5}(?:x[0-9]{1,5})?))?")


class FormError(ValueError):
    """A query the command refuses: the CLI's one-line ``message``, the form ``key`` it
    belongs to (None: the whole form) and the HTTP status."""

    def __init__(self, message: str, key: str | None = None, status: int = 400) -> None:
        super().__init__(message)
        self.message, self.key, self.status = message, key, status


@dataclass(frozen=True)
class Choice:
    value: str
    label: str
    description: str = ""
    swatches: tuple[str, ...] = ()
    group: str = ""
    parameter: str = ""  # a built-in input's parameter ("N", "WxH"), if it takes one
    kind: str = ""  # a built-in input's kind: "surface" (in space: a ball) or "flat"


@dataclass(frozen=True)
class Field:
    """One form field: a click parameter as the web shows it."""

    key: str
    label: str
    kind: str  # input, figure, flag, choice, preset, length, integer, number, page, text
    help: str
    default: str | None
    required: bool
    group: str  # main, more, drawing
    choices: tuple[Choice, ...] = ()
    minimum: float | None = None
    maximum: float | None = None
    unit: str = ""
    needs: str = ""  # a flag's key this field counts with ("!key": without), from NEEDS
    not_for: str = ""  # the kind of input the command refuses it for (``kit_refuses``)
    help_for: tuple[tuple[str, str], ...] = ()  # (kind, help without the fields it lacks)
    param: click.Parameter | None = field(default=None, compare=False, repr=False)


def group() -> click.Group:
    from ..cli.app import cli

    return cli


def command(name: str) -> click.Command:
    """The click command of a page; FormError 404 for any other name."""
    if name not in COMMANDS:
        raise FormError(f"no page {name!r}{nearest(name, COMMANDS)}; the pages are "
                        f"{', '.join(COMMANDS)}", status=404)
    return group().commands[name]


def key(param: click.Parameter) -> str:
    """The query key of a parameter: its long option name without dashes, ``input``."""
    if isinstance(param, click.Argument):
        return "input" if param.name == "input_mesh" else param.name
    return option_key(param)


def is_hidden(param: click.Parameter) -> bool:
    return key(param) in HIDDEN or isinstance(param.type, click.Path)


@functools.cache
def fields(name: str) -> tuple[Field, ...]:
    """The visible fields of command ``name``, in the order of its parameters."""
    primary = PRIMARY.get(name, ())
    out = []
    for p in command(name).params:
        if is_hidden(p):
            continue
        k = key(p)
        where = "main" if k in primary else ("drawing" if not p.expose_value else "more")
        made = _field(p, k, where, NEEDS.get(name, {}).get(k, ""), name)
        refused = [kind for kind, (_, why) in kit_refuses(name).items() if k in why]
        own = getattr(p, "help", None) or ""
        shorter = tuple((kind, web_help(without(own, gone), name))
                        for kind, gone in _gone(name).items() if without(own, gone) != own)
        out.append(replace(made, not_for=refused[0] if refused else "", help_for=shorter))
    return tuple(out)


def _gone(name: str) -> dict[str, set[str]]:
    """Kind of input -> the fields a page of command ``name`` does not offer for it: those
    the command refuses for it and those that need one of them (``NEEDS``)."""
    needs = NEEDS.get(name, {})
    return {kind: set(why) | {k for k, flag in needs.items() if flag in why}
            for kind, (_, why) in kit_refuses(name).items()}


def kit_refuses(name: str) -> dict:
    """The CLI's ``KIT_REFUSES`` of command ``name`` (a ball takes no cutter), or {}."""
    from ..cli import strands_command

    return strands_command.KIT_REFUSES if name == "strands" else {}


def input_kind(value: str, uploads=None) -> str:
    """"surface" or "flat" for a built-in input (``value`` as a query gives it) or an upload
    ``uploads`` (``uploads.Store``) has read, "" for an unknown one."""
    upload, found = UPLOAD.fullmatch(value or ""), INPUT.fullmatch(value or "")
    if upload:
        return uploads.kind(upload.group(1)) if uploads is not None else ""
    if found is None or found.group(1) not in inputs.INPUTS:
        return ""
    return "surface" if found.group(1) in inputs.SURFACES else "flat"


@functools.cache
def format_field(name: str) -> Field | None:
    """The kit's file format, where command ``name`` writes a file (the suffixes its -o
    takes: ``jobs.output_formats``); None where it writes a folder (``puzzle``)."""
    offered = output_formats(command(name).name)
    if not offered:
        return None
    own = name == "figure"  # a raster figure is PNG only: its own format by default
    text = ("The format of the file the kit holds"
            + (": the figure's own (SVG, or PNG for a raster figure) if none is chosen."
               if own else f" [default: {offered[0]}]."))
    return Field(FORMAT, "File format", "choice", text, None if own else offered[0], False,
                 "main", tuple(Choice(s, FORMAT_LABELS.get(s, s.upper())) for s in offered),
                 needs=NEEDS.get(name, {}).get(FORMAT, ""))


def form_fields(name: str) -> tuple[Field, ...]:
    """``fields(name)`` and the file format (``format_field``), as the page shows them."""
    extra = format_field(name)
    return fields(name) + ((extra,) if extra else ())


def web_help(text: str, name: str) -> str:
    """Click's help of an option of command ``name`` as the form shows it (``labels``)."""
    return form_words(text, labels(name))


@functools.cache
def labels(name: str) -> dict[str, str]:
    """Option key -> how a sentence on command ``name``'s page names its field."""
    return {key(p): f"“{field_label(key(p))}”" + " ticked" * bool(getattr(p, "is_flag", 0))
            for p in command(name).params if not is_hidden(p)}


def _field(p: click.Parameter, k: str, where: str, needs: str, name: str) -> Field:
    ticked = TICKED.get(name, {}).get(k, "")  # a flag the form ticks at first (sent as "off")
    default = "on" if ticked else str(p.default) if isinstance(p.default, (str, int, float)) \
        and p.default is not False else None  # click's UNSET, None, False: no default to show
    text = " ".join(filter(None, (web_help(getattr(p, "help", None) or "", name), ticked)))
    base = {"key": k, "label": field_label(k), "help": text,
            "required": p.required or k == "name",
            "group": where, "param": p, "default": default, "needs": needs}
    t = p.type
    if isinstance(p, click.Argument):
        if k == "input":
            return Field(kind="input", choices=input_choices(), **base)
        return Field(kind="figure", choices=figure_choices(), **base)
    if getattr(p, "is_flag", False):
        return Field(kind="flag", **base)
    if k in PRESETS:
        return Field(kind="preset", choices=preset_choices(PRESETS[k]), **base)
    if isinstance(t, click.Choice):
        return Field(kind="choice", choices=tuple(Choice(str(c), str(c)) for c in t.choices),
                     **base)
    if isinstance(t, Length):
        unit = "with a unit: mm, cm or in" if type(t) is not Length else "mm, cm or in"
        return Field(kind="length", unit=unit, minimum=t.minimum, **base)
    if isinstance(t, (click.IntRange, Finite)):
        return Field(kind="integer" if isinstance(t, click.IntRange) else "number",
                     minimum=t.min, maximum=t.max, unit=bounds(t), **base)
    if isinstance(t, Formats):  # ticked at first: what the command writes without --formats
        return Field(kind="formats", choices=tuple(Choice(f, FORMAT_LABELS.get(f, f)) for f in
                     presets.LASER_FORMATS), **{**base, "default": laser_formats(name)})
    if isinstance(t, PageSize):
        pages = ("a4", "letter", "a3", *presets.names("pages"))
        return Field(kind="page", choices=tuple(Choice(n, n) for n in pages), **base)
    return Field(kind="text", **base)


@functools.cache
def input_choices() -> tuple[Choice, ...]:
    return tuple(Choice(n, n, e.description, group="Surfaces: woven balls" if n in
                        inputs.SURFACES else "Flat", parameter=e.parameter, kind=input_kind(n))
                 for n, e in inputs.INPUTS.items())


@functools.cache
def figure_choices() -> tuple[Choice, ...]:
    from ..figures.gallery import FIGURES

    return tuple(Choice(n, n, d) for n, (d, _) in FIGURES.items())


@functools.cache
def preset_choices(kind: str) -> tuple[Choice, ...]:
    out = []
    for n in presets.names(kind):
        doc = presets.load(kind, n)
        colours = doc.get("colours") or [c for f in doc.get("families", ()) for c in f]
        out.append(Choice(n, n, str(doc.get("description", "")), tuple(colours[:24])))
    return tuple(out)
