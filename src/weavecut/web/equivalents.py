"""What a web form amounts to at a terminal: the equivalent command line and a recipe TOML
(``weave-cut build``), so a web user can move to batch builds."""

from __future__ import annotations

import json
import shlex

from .forms import fields
from .queries import Query


def output(query: Query) -> str:
    """The -o a person would give for this kit: the job's (a folder with a slash)."""
    return query.output + ("" if "." in query.output else "/")


def _words(query: Query) -> list[tuple[str, object]]:
    """(key, value) of every value given, in the command's order; an upload by its name."""
    names = dict(query.files)
    out = []
    for f in fields(query.command):
        if f.key not in query.values:
            continue
        value = query.values[f.key]
        if f.kind == "input" and value.startswith("upload:"):
            value = next(iter(names))
        if f.kind == "integer":
            value = int(value)
        out.append((f.key, value))
    return out


def command_line(query: Query) -> str:
    words = ["weave-cut", query.command]
    for k, value in _words(query):
        if k in ("input", "name"):
            words.append(str(value))
        elif value is True:
            words.append(f"--{k}")
        elif value is not False:
            words += [f"--{k}", str(value)]
    words += ["-o", output(query).rstrip("/")]
    return " ".join(shlex.quote(w) for w in words)


def recipe(query: Query) -> str:
    """A recipe of one job (``weave-cut build RECIPE -o DIR``)."""
    lines = ["# weave-cut build this.toml -o build"]
    if query.files:
        lines.append(f"# keep your drawing beside this file as {query.files[0][0]}")
    lines += ["[recipe]", f"name = {_toml(query.command + ' from the web app')}", "",
              "[[job]]", f"command = {_toml(query.command)}"]
    for k, value in _words(query):
        if value is not False:
            lines.append(f"{'input' if k == 'name' else k} = {_toml(value)}")
    lines.append(f"output = {_toml(output(query).rstrip('/'))}")
    return "\n".join(lines) + "\n"


def _toml(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    return json.dumps(str(value), ensure_ascii=False, allow_nan=False)  # a TOML basic string
