"""A request's query checked by the command itself (the form's fields: ``forms``).

``parse(name, query)`` turns a query into the command's arguments: unknown keys are refused
with the nearest key, every value is confined (no file paths; a preset is a preset name; the
input is a built-in input or an uploaded drawing by its hash), then the command parses the
arguments with its own types (``command.make_context``), so a bad value gets the CLI's own
message (in the form's words: ``refusals``). Values reach the command as ``--key=value``
words, so no value becomes an option."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import click

from .. import inputs, presets
from ..schema import nearest
from .forms import (FORMAT, HIDDEN, INPUT, PRESETS, UPLOAD, Field, FormError, command,
                    figure_choices, fields, form_fields, format_field, group, input_kind,
                    is_hidden, key, kit_refuses)
from .jobs import JobSpec, default_output, output_formats
from .uploads import UploadError

MAX_PARAMS = 64  # query parameters of one request
MAX_VALUE = 200  # characters of one value
PLACEHOLDER = "web-check"  # a required hidden option's value while the command checks a query


@dataclass(frozen=True)
class Query:
    """A checked query: the command's arguments (``args``, as the job gets them), the uploaded
    files they name and the values by key, in the form's order."""

    command: str
    args: tuple[str, ...]
    files: tuple[tuple[str, Path], ...]  # uploads: (the name args use, the stored file)
    values: dict
    output: str = ""  # the kit's -o (``jobs.default_output`` in the chosen ``format``)

    def job_files(self) -> tuple[tuple[str, bytes], ...]:
        """``files`` as a job takes them: (name, bytes)."""
        return tuple((name, path.read_bytes()) for name, path in self.files)


def parse(name: str, items: list[tuple[str, str]], uploads=None) -> Query:
    """Check a query against command ``name`` and return its arguments; FormError names the
    key and carries the CLI's own message. ``uploads`` (``uploads.Store``) resolves
    ``input=upload:ID``."""
    cmd = command(name)
    if len(items) > MAX_PARAMS:
        raise FormError(f"{len(items):,} parameters; a form of {name} has at most {MAX_PARAMS}")
    by_key = {f.key: f for f in form_fields(name)}
    raw: dict[str, str] = {}
    for k, value in items:
        if k not in by_key:
            why = ("the web app names and packs the files itself" if k in HIDDEN else
                   f"{name} takes {', '.join(by_key)}")
            raise FormError(f"unknown parameter {k[:40]!r}{nearest(k, by_key)}; {why}")
        kind = by_key[k].kind  # a flag's last value counts: a form's hidden "off", then "on"
        if k in raw and kind != "flag" and not (kind == "formats" and value.strip()):
            raise FormError(f"{k} is given twice", k)
        if (len(value) > MAX_VALUE or any(ord(c) < 32 or c in "/\\" for c in value)
                or value.lower().endswith(".toml") or value.startswith((".", "~"))):
            raise FormError(f"{k}: a value of at most {MAX_VALUE} characters, no file (the web "
                            "app reads no file named by a request) and no control character", k)
        if value.strip():  # a form's checkboxes send formats=svg&formats=dxf: svg,dxf
            raw[k] = ",".join(filter(None, (raw.get(k) if kind != "flag" else "", value.strip())))
    args, files, values = [], [], {}
    for f in fields(name):
        if f.key not in raw and not (f.kind == "flag" and f.default):
            continue
        value = values[f.key] = raw.get(f.key, f.default)
        if f.kind == "input":
            word, file = _input(value, uploads)
            args.append(word)
            files += [file] if file else []
        elif f.kind == "figure":
            args.append(_figure(value))
        elif f.kind == "flag":
            try:
                on = click.BOOL.convert(value, f.param, None)
            except click.BadParameter as exc:
                raise FormError(exc.format_message(), f.key) from None
            values[f.key] = on
            args += [_long(f.param)] if on else []
        else:
            if f.kind == "preset":
                _preset(f, value)
            args.append(f"{_long(f.param)}={value}")
    check(cmd, name, args, input_kind(values.get("input", ""), uploads))
    return Query(name, tuple(args), tuple(files), values, _output(name, args, raw, values))


def _output(name: str, args: list[str], raw: dict[str, str], values: dict) -> str:
    """The kit's -o in the ``format`` chosen (the command's default without one)."""
    chosen = raw.get(FORMAT, "")
    offered = output_formats(name, args)
    if chosen and not offered and chosen == format_field(name).default:
        chosen = ""  # the default is no choice (a form sent without its script sends it)
    if chosen:
        values[FORMAT] = chosen
        if not offered:
            raise FormError("format: this kit is a folder of files for each sheet; choose "
                            "them with formats (svg, dxf, lbrn2)", FORMAT)
        if chosen not in offered:
            raise FormError(f"unknown format {chosen!r}{nearest(chosen, offered)}; use "
                            f"{', '.join(offered)}", FORMAT)
    return default_output(JobSpec("kit", name, tuple(args)), chosen)


def _long(param: click.Parameter) -> str:
    return max(param.opts, key=len)


def _input(value: str, uploads) -> tuple[str, tuple[str, Path] | None]:
    found = UPLOAD.fullmatch(value)
    if found:
        try:
            name, path = uploads.argument(found.group(1))
        except UploadError as exc:
            raise FormError(exc.message, "input", exc.status) from None
        return name, (name, path)
    spec = INPUT.fullmatch(value)
    if spec is None or spec.group(1) not in inputs.INPUTS:
        raise FormError(f"unknown input {value!r}{nearest(value, inputs.INPUTS)}; choose a "
                        "built-in input or upload a drawing", "input")
    return value, None


def _figure(value: str) -> str:
    names = [c.value for c in figure_choices()]
    if value not in names:
        raise FormError(f"unknown figure {value!r}{nearest(value, names)}", "name")
    return value


def _preset(f: Field, value: str) -> None:
    """A preset by name (``parse`` refused a .toml file already)."""
    try:
        presets.find(PRESETS[f.key], value)
    except presets.PresetError as exc:
        raise FormError(str(exc), f.key) from None


def check(cmd: click.Command, name: str, args: list[str], kind: str = "") -> None:
    """Let the command parse ``args`` with its own types, as the CLI does (a required hidden
    option, -o, gets a placeholder: parsing writes nothing), and refuse what it refuses for
    the ``kind`` of a built-in input (``kit_refuses``); FormError with its message."""
    fill = [f"{_long(p)}={PLACEHOLDER}" for p in cmd.params
            if isinstance(p, click.Option) and p.required and is_hidden(p)]
    root = click.Context(group(), info_name="weave-cut")
    try:
        with cmd.make_context(name, [*args, *fill], parent=root) as ctx:
            if kind and kit_refuses(name):
                from ..cli.strands_command import refuse_for_kit

                refuse_for_kit(kind, ctx.params["input_mesh"])
    except click.UsageError as exc:
        param = getattr(exc, "param", None)
        raise FormError(exc.format_message(), key(param) if param is not None else None) \
            from None

