"""The HTML of the app: the start page (a picture per product) and a page per command (its
form, generated from the click options by ``forms``; the preview; the kit's figures; the
download; the equivalent command line and recipe). Plain HTML5, one style sheet and one
script from ``static/``; every field has a label, every control works from the keyboard."""

from __future__ import annotations

import re
from html import escape
from urllib.parse import urlencode

from .. import __version__
from ..kitpage.viewer import HINT
from . import forms, queries

FOR_A_DRAWING = {  # fields whose default the command does not use for an uploaded drawing:
    # it chooses them (the puzzle's level, with the cell: ``workshop.drawing_defaults``)
    "puzzle": {"levels": "chosen for the drawing"},
}

PRODUCTS = [  # (picture, title, what it is, link)
    ("paper-model", "Paper model", "Print strips on A4, weave them by hand into the square "
     "grid's pattern: four copies of a twelve-strip module.",
     "/strands?input=square-grid&size=27cm"),
    ("pentagon-flower", "Pentagon flower", "The paper's pentagon model: 180 strands in five "
     "copies of one module, a flower 23 cm across.",
     "/strands?input=pentagon-flower&size=23cm"),
    ("woven-ball", "Woven ball", "Six closed paper strips woven into a ball, unfolded "
     "pentagon by pentagon with fold lines and glue bands.",
     "/strands?input=dodecahedron&levels=1&project=sphere&size=12cm"),
    ("cut-by-machine", "Strips cut by machine", "Laser-cut the strips from coloured card, or "
     "print and cut them on a Silhouette, Cricut or ScanNCut.",
     "/strands?input=square-grid&size=27cm&laser-card=on&palette=maritime-4"),
    ("jigsaw-puzzle", "Jigsaw puzzle", "The two-sided laser-cut puzzle of section 6: cut "
     "files, painting guides and the order of work.", "/puzzle?numbers=on"),
    ("your-drawing", "Your own drawing", "Upload an SVG, DXF or OBJ outline (a heart, a "
     "star, a house) and make a puzzle or a weave of it.", "/puzzle#input"),
    ("weave", "Weaving patterns", "Strands and over/under crossings of any subdivision, as "
     "tiles or knotwork ribbons.", "/weave?input=square-grid&levels=2&outline-level=1"),
    ("subdivide", "Subdivisions", "The pentagon snub scheme and the classic ones, cut-ready "
     "as SVG, DXF or PDF.", "/subdivide?input=pentagon&levels=4&earlier-levels=on"),
    ("figures", "Figures of the paper", "Every figure of the paper, redrawn from the "
     "mathematics.", "/figure?name=square-grid-weaving"),
]
TITLES = {"strands": "Paper strips: models, balls, card", "puzzle": "Jigsaw puzzle",
          "weave": "Weaving pattern", "subdivide": "Subdivision", "figure": "Figure of the paper"}
DEFAULT = re.compile(r"\s*\[default: ([^\]]*)\]\s*")
NONE = {  # the choice of no preset, where the option has no default: (name, what it means)
    "cutter": ("none", "print only; cut the strips by hand"),
    "palette": ("default", "maritime-12, or the input's own"),
}


UNKNOWN = "not known: choose one"  # an item a link names that the list lacks


def _e(text) -> str:
    return escape(str(text), quote=True)


def _document(title: str, body: str, current: str = "", viewer: bool = False) -> str:
    nav = "".join(f'<a href="/{n}"{" aria-current=page" if n == current else ""}>{_e(n)}</a>'
                  for n in forms.COMMANDS)
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width,initial-scale=1\">"
            f"<title>{_e(title)}</title><link rel=\"icon\" href=\"/static/logo.svg\">"
            "<link rel=\"stylesheet\" href=\"/static/app.css\">"
            + "".join(f'<script src="/static/viewer/{n}" defer></script>'
                      for n in ("three.min.js", "viewer.js") if viewer) +
            "<script src=\"/static/app.js\" defer></script></head>\n<body>"
            "<a class=\"skip\" href=\"#main\">Skip to the content</a>"
            "<header class=\"bar\"><a class=\"brand\" href=\"/\"><img src=\"/static/logo.svg\" "
            "alt=\"\" width=\"28\" height=\"28\">weave-cut</a>"
            f"<nav aria-label=\"Commands\">{nav}</nav></header>\n"
            f"<main id=\"main\">{body}</main>\n<footer>weave-cut {_e(__version__)} runs on "
            "this computer: nothing you make or upload leaves it.</footer></body></html>\n")


def start() -> str:
    cards = "".join(
        f'<li class="product"><a href="{_e(link)}"><img src="/static/products/{pic}.webp" '
        f'alt="" width="480" height="360"><span class="name">{_e(title)}</span>'
        f'<span class="what">{_e(text)}</span></a></li>'
        for pic, title, text, link in PRODUCTS)
    return _document("weave-cut", (
        '<section class="hero"><h1>Weave it, cut it, paint it.</h1><p>Paper weaving kits, '
        "laser-cut jigsaw puzzles and the figures of <cite>Weaving patterns inspired by the "
        "pentagon snub subdivision scheme</cite>, made to measure. Choose what to make, set "
        "its size, watch the preview, download the kit.</p></section>"
        f'<ul class="products">{cards}</ul>'))


def not_found(message: str) -> str:
    return _document("Not found: weave-cut", (
        f'<section class="hero"><h1>Not found</h1><p>{_e(message)}</p>'
        '<p><a href="/">Back to the start page</a></p></section>'))


def failed(message: str) -> str:
    return _document("Error: weave-cut", (
        f'<section class="hero"><h1>Something went wrong</h1><p>{_e(message)}</p>'
        '<p><a href="/">Back to the start page</a></p></section>'))


def command_page(name: str, raw: dict[str, str], error: forms.FormError | None,
                 query: queries.Query | None, uploads: list[tuple[str, str]]) -> str:
    """The page of command ``name`` with the values ``raw`` as given (shown even when
    refused), ``error`` next to its field, ``query`` the checked values (None if refused)
    and ``uploads`` (id, label, kind of kit: ``uploads.Store.kind``) offered as inputs."""
    cmd = forms.command(name)
    groups = {"main": [], "more": [], "drawing": []}
    starting = dict([forms.STARTING[name]]) if name in forms.STARTING else {}
    value = raw.get("input") or starting.get("input", "")
    kind = forms.input_kind(value) or {f"upload:{i}": k for i, _, k in uploads}.get(value, "")
    gone = {f.key for f in forms.form_fields(name) if f.not_for and f.not_for == kind}
    for f in forms.form_fields(name):
        message = error.message if error is not None and error.key == f.key else ""
        field = _field(f, raw.get(f.key, ""), message, uploads, kind)
        if f.key in FOR_A_DRAWING.get(name, {}) and raw.get("input", "").startswith(
                "upload:"):  # the command chooses it for a drawing: no default to show
            field = field.replace(f'placeholder="{_e(f.default or "")}"',
                                  f'placeholder="{_e(FOR_A_DRAWING[name][f.key])}"', 1)
        hidden = f.key in gone  # not for this input (a ball's cutter): the script follows it
        if f.needs:  # shown only with (or without) a flag: the script follows the flag
            flag = f.needs.lstrip("!")
            on = _on(raw.get(flag, "")) and flag not in gone
            hidden = hidden or on == f.needs.startswith("!")
        drawn = FOR_A_DRAWING.get(name, {}).get(f.key)  # a default a drawing lacks
        extra = (f' data-not-for="{f.not_for}"' if f.not_for else "") + (
            f' data-needs="{_e(f.needs)}"' if f.needs else "") + (
            f' data-drawing="{_e(drawn)}"' if drawn else "")
        field = field.replace(' data-key=', f'{extra}{" hidden" * hidden} data-key=', 1)
        groups[f.group].append(field)
    general = error.message if error is not None and error.key is None else ""
    about = forms.web_help(" ".join((cmd.help or "").split("\n\n")[0].split()), name).replace(
        "INPUT", "the input")
    qs = urlencode([(k, v) for k, v in raw.items()])
    from .equivalents import command_line, recipe

    line = command_line(query) if query else ""
    toml = recipe(query) if query else ""
    more = "".join(groups["more"])
    drawing = "".join(groups["drawing"])
    body = (
        f'<div class="tool"><div class="intro"><h1>{_e(TITLES.get(name, name))} '
        f'<code>weave-cut {_e(name)}</code></h1><p>{_e(about)}</p></div>'
        f'<form id="form" class="form" action="/{name}" method="get" data-command="{name}" '
        f'novalidate><p class="error general" id="e-form" role="alert"'
        f'{"" if general else " hidden"}>{_e(general)}</p>'
        f'<div class="fields">{"".join(groups["main"])}</div>'
        + (f'<details class="more"><summary>More options</summary><div class="fields">{more}'
           '</div></details>' if more else "")
        + (f'<details class="more" id="drawing-options"><summary>Reading your drawing'
           f'</summary><div class="fields">{drawing}</div></details>' if drawing else "")
        + '<noscript><button class="button" type="submit">Update</button></noscript></form>'
        '<section class="result" aria-label="Preview and download">'
        '<figure class="preview"><div class="sheet" id="sheet">'
        '<p class="waiting">The preview appears here.</p>'
        f'<img id="preview" alt="Preview of the {_e(TITLES.get(name, name)).lower()}">'
        f'<noscript><img alt="Preview" src="/{name}/preview.svg?{_e(qs)}"></noscript></div>'
        '<figcaption id="status" role="status" aria-live="polite">Preview</figcaption>'
        '</figure><div class="actions">'
        f'<a id="download" class="button primary" href="/{name}.zip?{_e(qs)}" download>'
        'Download the kit (ZIP)</a><span class="note">every file the command writes, '
        'with its kit page</span></div>'
        '<section class="figures" aria-labelledby="h-figures"><h2 id="h-figures">The kit'
        '</h2><dl id="figures"></dl><ul id="warnings" class="warnings"></ul></section>'
        '<section class="model" id="model" aria-label="The kit\'s model in 3-D" hidden>'
        '<template><figure class="model3d" data-state="loading"><canvas role="img" '
        'aria-label="The finished model in 3-D"></canvas>'
        f'<figcaption>{_e(HINT)} <button type="button">Reset view</button> '
        '<a download="model.glb">GLB</a></figcaption></figure></template></section>'
        '</section><section class="terminal" aria-labelledby="h-terminal"><h2 id="h-terminal">At a '
        'terminal</h2><p>The same kit from the command line, byte for byte:</p>'
        f'<pre><code id="cmdline">{_e(line)}</code></pre><h3>As a recipe</h3>'
        '<p><code>weave-cut build</code> runs it, with others, into one folder:</p>'
        f'<pre><code id="recipe">{_e(toml)}</code></pre></section></div>')
    return _document(f"{TITLES.get(name, name)}: weave-cut", body, name, viewer=True)


def _field(f: forms.Field, value: str, message: str, uploads, kind: str = "") -> str:
    """A field's HTML; its help for the ``kind`` of input chosen (the script swaps in the
    help for another kind, ``data-help-KIND``, when the input changes)."""
    fid, hid, eid = f"f-{f.key}", f"h-{f.key}", f"e-{f.key}"
    shown = DEFAULT.search(f.help)
    placeholder = f.default or (shown.group(1) if shown else "")
    hint = _e(_hint_text(dict(f.help_for).get(kind, f.help)))
    if f.help_for:
        hint = (f'<span class="help" data-help="{_e(_hint_text(f.help))}"'
                + "".join(f' data-help-{k}="{_e(_hint_text(h))}"' for k, h in f.help_for)
                + f">{hint}</span>")
    hint += f' <span class="unit">{_e(f.unit)}</span>' if f.unit else ""
    describe = f'aria-describedby="{hid} {eid}"'
    invalid = ' aria-invalid="true"' if message else ""
    attrs = (f'data-key="{f.key}" data-default="{_e(f.default or "")}" data-kind="{f.kind}"')
    error = f'<p class="error" id="{eid}" role="alert"{"" if message else " hidden"}>{_e(message)}</p>'
    if f.kind == "flag":  # ticked at first (``forms.TICKED``): "off" sent without a script
        checked = " checked" if _on(value or f.default or "") else ""
        off = f'<input type="hidden" name="{f.key}" value="off">' if f.default else ""
        return (f'<div class="field flag" {attrs}>{off}<input type="checkbox" id="{fid}" '
                f'name="{f.key}"{checked} {describe}{invalid}><label for="{fid}">{_e(f.label)}'
                f'</label><p class="hint" id="{hid}">{hint}</p>{error}</div>')
    if f.kind == "preset":
        return _presets(f, value, attrs, hint, hid, error, describe)
    if f.kind == "formats":
        chosen = set((value or f.default or "").split(","))  # the command's own, at first
        boxes = "".join(
            f'<label class="check"><input type="checkbox" name="{f.key}" value="{_e(c.value)}"'
            f'{" checked" * (c.value in chosen)}> {_e(c.label)}</label>' for c in f.choices)
        return (f'<fieldset class="field formats" {attrs} {describe}><legend>{_e(f.label)}'
                f'</legend><div class="checks">{boxes}</div><p class="hint" id="{hid}">{hint}'
                f'</p>{error}</fieldset>')
    label = f'<label for="{fid}">{_e(f.label)}</label>'
    if f.kind in ("input", "figure", "choice"):
        control = _select(f, value, fid, describe + invalid, uploads)
        about = {c.value: c.description for c in f.choices}.get(
            value.partition(":")[0] if f.kind == "input" else value or f.default or "")
        if about:
            hint = f'<span class="about">{_e(about)}</span> ' + hint
    else:
        kind = {"integer": 'inputmode="numeric"', "number": 'inputmode="decimal"'}.get(f.kind, "")
        listed = f' list="l-{f.key}"' if f.choices else ""
        control = (f'<input type="text" id="{fid}" name="{f.key}" value="{_e(value)}" '
                   f'placeholder="{_e(placeholder)}" autocomplete="off" spellcheck="false" '
                   f'{kind}{listed} {describe}{invalid}>')
        if f.choices:
            control += (f'<datalist id="l-{f.key}">'
                        + "".join(f'<option value="{_e(c.value)}">' for c in f.choices)
                        + "</datalist>")
    if f.kind == "input":
        takes = {c.value: c.parameter for c in f.choices}.get(value.partition(":")[0], "")
        control = (f'<div class="input-row">{control}<input type="text" id="{fid}-param" '
                   f'class="param" aria-label="Size of the input: {_e(takes or "N or WxH")}" '
                   f'placeholder="{_e(takes)}"{"" if takes else " hidden"} '
                   f'value="{_e(value.partition(":")[2] if not value.startswith("upload:") else "")}" '
                   'autocomplete="off" spellcheck="false"></div><div class="upload">'
                   '<input type="file" id="f-upload" accept=".svg,.dxf,.obj,.json">'
                   '<label for="f-upload" class="button">Upload your drawing</label>'
                   '<span class="note">SVG, DXF or OBJ, up to 8 MiB</span></div>')
    return (f'<div class="field {f.kind}" {attrs}>{label}{control}'
            f'<p class="hint" id="{hid}">{hint}</p>{error}</div>')


def _hint_text(help_text: str) -> str:
    """A help as a field's hint shows it: without click's ``[default: ...]``."""
    return re.sub(r"\s+([.;,])(?=\s|$)", r"\1", DEFAULT.sub(" ", help_text)).strip()


def _on(value: str) -> bool:
    """A flag's query value as the form shows it (``click.BOOL``'s true words)."""
    return value.lower() in ("1", "true", "on", "yes", "y", "t")


def _select(f: forms.Field, value: str, fid: str, extra: str, uploads) -> str:
    chosen = value.partition(":")[0] if f.kind == "input" and not value.startswith(
        "upload:") else value
    options, groups = [], {}
    if f.kind == "input":
        options.append('<optgroup label="Your drawings" id="uploads">' + "".join(
            f'<option value="{_e("upload:" + i)}"' + (f' data-kind="{k}"' if k else "")
            + f'{" selected" * (value == "upload:" + i)}>{_e(label)}</option>'
            for i, label, k in uploads) + "</optgroup>")
    if not f.default and f.kind != "input":
        options.append(f'<option value=""{" selected" * (not value)}>—</option>')
    known = {c.value for c in f.choices} | {"upload:" + i for i, _, _ in uploads}
    if chosen and chosen not in known:
        # a value the command refuses (a mistyped link): offered as given and chosen, so the
        # script sends it and its refusal stays, not the first item silently made instead
        options.append(f'<option value="{_e(value)}" data-unknown selected>{_e(value)} '
                       f'({UNKNOWN})</option>')
    for c in f.choices:
        groups.setdefault(c.group, []).append(
            f'<option value="{_e(c.value)}" data-description="{_e(c.description)}"'
            + (f' data-param="{_e(c.parameter)}"' if c.parameter else "")
            + (f' data-kind="{c.kind}"' if c.kind else "")
            + f'{" selected" * (c.value == (chosen or f.default))}>{_e(c.label)}</option>')
    for g, items in groups.items():
        options.append(f'<optgroup label="{_e(g)}">{"".join(items)}</optgroup>' if g
                       else "".join(items))
    return f'<select id="{fid}" name="{f.key}" {extra}>{"".join(options)}</select>'


def _presets(f: forms.Field, value: str, attrs: str, hint: str, hid: str, error: str,
             describe: str) -> str:
    current = value or f.default or ""
    shown = DEFAULT.search(f.help)
    name, what = NONE.get(f.key, ("default", shown.group(1) if shown else ""))
    cards = [] if f.default else [
        f'<label class="preset"><input type="radio" name="{f.key}" value=""'
        f'{" checked" * (not current)}><span class="name">{_e(name)}</span>'
        f'<span class="what">{_e(what)}</span></label>']
    if current and all(c.value != current for c in f.choices):  # as _select: kept, refused
        cards.append(f'<label class="preset"><input type="radio" name="{f.key}" '
                     f'value="{_e(current)}" data-unknown checked><span class="name">'
                     f'{_e(current)}</span><span class="what">{UNKNOWN}</span></label>')
    for c in f.choices:
        n = len(c.swatches)
        dots = "".join(f'<rect x="{i}" width="1" height="1" fill="{_e(s)}"/>'
                       for i, s in enumerate(c.swatches))
        dots = dots and (f'<svg class="swatches" viewBox="0 0 {n} 1" preserveAspectRatio="none"'
                         f' aria-hidden="true">{dots}</svg>')
        cards.append(
            f'<label class="preset"><input type="radio" name="{f.key}" value="{_e(c.value)}"'
            f'{" checked" * (c.value == current)}><span class="name">{_e(c.value)}</span>'
            + dots
            + f'<span class="what">{_e(c.description)}</span></label>')
    return (f'<fieldset class="field presets" {attrs} {describe}><legend>{_e(f.label)}</legend>'
            f'<div class="cards">{"".join(cards)}</div><p class="hint" id="{hid}">{hint}</p>'
            f'{error}</fieldset>')
