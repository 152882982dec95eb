"""What the app says when it refuses: every message a page, ``/check``, a job or an upload
answers with passes through :func:`said` on its way out, so a maker reads the form's words
(“Cell size”, “Laser-cut card” ticked) where the CLI says ``--cell`` and ``--laser-card``, and
the field it belongs to is found from the CLI's own words first (:func:`key_of_message`).
"""

from __future__ import annotations

import functools
import re

from . import forms
from .words import refusal_words

HINT = re.compile(r"'(?:-\w' / ')?--([a-z][a-z0-9-]*)'")


def key_of_message(message: str, name: str) -> str | None:
    """The form key a CLI message names (``Invalid value for '--size': ...``), if any."""
    known = {f.key for f in forms.fields(name)}
    for found in HINT.finditer(message):
        if found.group(1) in known:
            return found.group(1)
    if re.search(r"'-o'|\.[a-z0-9]+ (?:woven model|drawing)\b", message) and \
            forms.format_field(name):
        return forms.FORMAT  # the output's format: the only part of -o the form chooses
    return None


def said(error: forms.FormError, name: str | None) -> forms.FormError:
    """``error`` as the page of command ``name`` shows it (None: any page, an upload's): its
    key (from the CLI's words where it has none) and its message in the form's words."""
    name = name if name in forms.COMMANDS else None  # no page (404): any page's words
    key = error.key
    if key is None and name is not None and error.status != 404:
        key = key_of_message(error.message, name)
    return forms.FormError(in_form_words(error.message, name), key, error.status)


def in_form_words(message: str, name: str | None) -> str:
    """``message`` in the words of command ``name``'s page (None: of any page)."""
    labels, fields = _words(name)
    return refusal_words(message, labels, fields)


@functools.cache
def _words(name: str | None) -> tuple[dict[str, str], dict[str, str]]:
    """(option key -> its field in a sentence, option key -> the field's label) of the page of
    ``name``, or of every page (the first page's label where two differ)."""
    labels, fields = {}, {}
    for n in reversed(forms.COMMANDS) if name is None else (name,):
        labels.update(forms.labels(n))
        fields.update({f.key: f.label for f in forms.form_fields(n)})
        found = forms.format_field(n)
        if found is not None:
            fields["output"] = found.label  # -o: the form chooses its format only
    return labels, fields
