"""Checkers for the TOML files weave-cut reads (presets and recipes), the recipe's schema, and
a bounded TOML reader.

Every preset kind has one ``Table`` of these checkers (types, ranges, units, allowed and
required keys: ``presets.schemas()``). ``read_toml`` refuses anything that is not a regular
UTF-8 file of at most ``MAX_BYTES`` or nests deeper than ``MAX_DEPTH`` *before* the parser
sees it (a 50,000-deep dotted key takes tomllib a minute and gigabytes); ``Table.check`` then
names the file, table and key of the first problem and suggests the nearest key for a
misspelt one::

    poplar.toml: kerf: '-1mm' must be >= 0 mm
    lightburn.toml: [cut] colour: 'red' is not a #rrggbb colour
    recipe.toml job 2 (weave): unknown key 'level' (did you mean 'levels'?); weave takes ...

Checking returns nothing: a valid document is used as written, so every consumer keeps parsing
its own values, now knowing that they parse.
"""

from __future__ import annotations

import math
import os
import re
import stat
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from . import units
from .errors import WeaveCutError
from .text import nearest  # noqa: F401  (here for the schema's users)

MAX_BYTES = 256 * 1024
MAX_DEPTH = 8


class SchemaError(WeaveCutError, ValueError):
    """A TOML file is unreadable, too large or too deep, or breaks its schema."""


# --- bounded reading ----------------------------------------------------------------------

_TOKENS = re.compile(r"""
    \"\"\"(?:[^\\]|\\.)*?\"\"\"    # multi-line basic string
  | '''.*?'''                  # multi-line literal string
  | "(?:[^"\\\n]|\\.)*"          # basic string
  | '[^'\n]*'                    # literal string
  | \#[^\n]*                     # comment
  | [\[\]{}=,.\n]                # structure
  | [^"'#\[\]{}=,.\n]+           # anything else
  | ["']                         # an unterminated quote
""", re.S | re.X)


def toml_depth(text: str) -> int:
    """The deepest nesting TOML ``text`` can build: table headers, dotted keys, arrays and
    inline tables all count (an over-estimate for malformed text, which the parser refuses).

    Examples
    --------
    >>> toml_depth('a = 1'), toml_depth('[x.y]\\nb.c = [[1], {d = 2}]')
    (1, 6)
    """
    stack: list[tuple[str, int]] = []  # open arrays and inline tables, dots at opening
    mode, header, dots, deepest = "key", 0, 0, 0
    for m in _TOKENS.finditer(text):
        t = m.group()
        if t == "\n" and not stack:
            mode, dots = "key", 0
        elif t == "[" and mode in ("key", "header") and not stack:
            header = 1 if mode == "header" else 0  # [[a]] adds a list
            mode, dots = "header", 0
        elif t == "]" and mode == "header":
            header, mode, dots = header + dots + 1, "done", 0
            deepest = max(deepest, header + 1)  # the document, then the header's tables
        elif t == "." and mode in ("key", "header"):
            dots += 1
        elif t == "=" and mode == "key":
            mode = "value"
            deepest = max(deepest, header + len(stack) + dots + 1)
        elif t in "[{" and mode == "value":
            stack.append((t, dots))
            deepest = max(deepest, header + len(stack) + dots + 1)
            mode = "key" if t == "{" else mode
        elif t in "]}" and stack:
            dots, mode = stack.pop()[1], "value"
        elif t == "," and stack and stack[-1][0] == "{":
            mode, dots = "key", stack[-1][1]
    return deepest


def read_toml(path: str | os.PathLike, error: type[SchemaError] = SchemaError) -> dict:
    """Parse the TOML file ``path`` after bounding it: a regular file (never a FIFO or device),
    UTF-8, at most MAX_BYTES and MAX_DEPTH deep; every failure is one ``error`` naming it."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as exc:
        raise error(f"cannot read {path}: {exc.strerror}") from exc
    mode = os.fstat(fd).st_mode
    if not stat.S_ISREG(mode):  # before fdopen, which refuses a folder with an OSError
        os.close(fd)
        raise error(f"cannot read {path}: " + ("it is a folder, not a TOML file"
                                               if stat.S_ISDIR(mode) else "not a regular file"))
    with os.fdopen(fd, "rb") as f:
        try:
            data = f.read(MAX_BYTES + 1)
        except OSError as exc:
            raise error(f"cannot read {path}: {exc.strerror}") from exc
    if len(data) > MAX_BYTES:
        raise error(f"{path}: larger than {MAX_BYTES // 1024} KiB; not a weave-cut TOML file")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(f"{path}: not UTF-8 text (byte {exc.start})") from exc
    if toml_depth(text) > MAX_DEPTH:
        raise error(f"{path}: nested deeper than {MAX_DEPTH} levels")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise error(f"{path}: {exc}") from exc


# --- fields -------------------------------------------------------------------------------

def _kind(value) -> str:
    return {bool: "a boolean", int: "an integer", float: "a number", str: "a string",
            list: "a list", dict: "a table"}.get(type(value), type(value).__name__)


@dataclass(frozen=True)
class Text:
    """A string of at most ``longest`` characters."""

    longest: int = 200

    def problem(self, value) -> str | None:
        if not isinstance(value, str):
            return f"expected a string, got {_kind(value)}"
        if len(value) > self.longest:
            return f"longer than {self.longest} characters"
        return None


@dataclass(frozen=True)
class Number:
    """A finite int or float in [lo, hi] (lo excluded when ``open_lo``), ``unit`` for messages."""

    lo: float
    hi: float
    open_lo: bool = False
    unit: str = ""

    def problem(self, value) -> str | None:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return f"expected a number, got {_kind(value)}"
        return self.bounds(value, repr(value))

    def bounds(self, x: float, shown: str) -> str | None:
        unit = f" {self.unit}" if self.unit else ""
        if not math.isfinite(x):
            return f"{shown} is not a finite number"
        if x < self.lo or (self.open_lo and x == self.lo):
            return f"{shown} must be {'>' if self.open_lo else '>='} {self.lo:g}{unit}"
        if x > self.hi:
            return f"{shown} must be <= {self.hi:g}{unit}"
        return None


@dataclass(frozen=True)
class Whole(Number):
    """A whole number (an int, not a float) in [lo, hi]: a count such as a laser's passes."""

    def problem(self, value) -> str | None:
        if isinstance(value, bool) or not isinstance(value, int):
            return f"expected a whole number, got {_kind(value)}"
        return self.bounds(value, repr(value))


@dataclass(frozen=True)
class Length(Number):
    """A length with its unit ('0.15mm', '2in'; ``units.length``)."""

    unit: str = "mm"

    def problem(self, value) -> str | None:
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            return f"expected a length like '3mm', got {_kind(value)}"
        try:
            mm = units.length(value)
        except ValueError as exc:
            return str(exc)
        return self.bounds(mm, repr(value))


@dataclass(frozen=True)
class Sheet:
    """A page or sheet size: 'WxH' with units, or a name ``size`` knows (``units.page_size``:
    a paper name; ``presets.page_size`` also takes a page preset)."""

    size: Callable[[str], tuple[float, float]] = units.page_size

    def problem(self, value) -> str | None:
        if not isinstance(value, str):
            return f"expected a size like '1000x700mm', got {_kind(value)}"
        try:
            self.size(value)
        except ValueError as exc:
            return str(exc)
        return None


@dataclass(frozen=True)
class Choice:
    """One of a few strings."""

    choices: tuple[str, ...]

    def problem(self, value) -> str | None:
        if value not in self.choices:
            return f"{value!r} is not one of {', '.join(self.choices)}"
        return None


@dataclass(frozen=True)
class Colour:
    """A '#rrggbb' colour."""

    def problem(self, value) -> str | None:
        if not (isinstance(value, str) and re.fullmatch(r"#[0-9a-fA-F]{6}", value)):
            return f"{value!r} is not a #rrggbb colour"
        return None


@dataclass(frozen=True)
class ListOf:
    """A list of ``shortest``..``longest`` items, each checked by ``item``."""

    item: object
    shortest: int = 1
    longest: int = 1000

    def problem(self, value) -> str | None:
        if not isinstance(value, list):
            return f"expected a list, got {_kind(value)}"
        if not self.shortest <= len(value) <= self.longest:
            return f"needs {self.shortest} to {self.longest} items, has {len(value)}"
        for n, v in enumerate(value, start=1):
            p = self.item.problem(v)
            if p:
                return f"item {n}: {p}"
        return None


@dataclass(frozen=True)
class Table:
    """A table with declared ``fields``; ``required`` keys must be there, ``one_of`` names
    keys of which exactly one must be there; any other key is an error."""

    fields: Mapping[str, object]
    required: tuple[str, ...] = ()
    one_of: tuple[str, ...] = ()
    label: str = ""

    def check(self, doc, where: str, error: type[SchemaError] = SchemaError) -> None:
        """Raise ``error`` naming ``where`` (file and table), the key and the problem."""
        file = where
        where = f"{file}: [{self.label}]" if self.label else f"{file}:"
        if not isinstance(doc, dict):
            raise error(f"{where} expected a table, got {_kind(doc)}")
        for key, value in doc.items():
            spec = self.fields.get(key)
            if spec is None:
                raise error(f"{where} unknown key {key!r}{nearest(key, self.fields)}; "
                            f"allowed: {', '.join(sorted(self.fields))}")
            if isinstance(spec, Table):
                spec.check(value, file, error)
                continue
            p = spec.problem(value)
            if p:
                raise error(f"{where} {p}" if isinstance(spec, Jobs) else f"{where} {key}: {p}")
        missing = [k for k in self.required if k not in doc]
        if missing:
            raise error(f"{where} missing key {missing[0]!r}")
        if self.one_of and sum(k in doc for k in self.one_of) != 1:
            raise error(f"{where} needs exactly one of {' or '.join(map(repr, self.one_of))}")


# --- the recipe (the presets' kinds: presets.schemas()) -------------------------------

ABOUT = {"name": Text(80), "description": Text(400)}


@dataclass(frozen=True)
class Scalar:
    """A recipe value: a string, a finite number, a boolean, or a short list of them."""

    def problem(self, value) -> str | None:
        if isinstance(value, list):
            return ListOf(self, 0, 100).problem(value)
        if isinstance(value, float) and not math.isfinite(value):
            return f"{value!r} is not a finite number"
        if isinstance(value, str) and len(value) > 1000:
            return "longer than 1000 characters"
        if isinstance(value, str) and "\x00" in value:
            return "contains a NUL character"
        if not isinstance(value, (str, int, float, bool)):
            return f"expected a string, number or boolean, got {_kind(value)}"
        return None


@dataclass(frozen=True)
class Jobs:
    """The ``[[job]]`` list: 1..1000 tables of scalars with a string ``command``; which keys a
    job may have depends on its command and is checked against that command's options."""

    def problem(self, value) -> str | None:
        if not isinstance(value, list) or not value:
            return "job: expected [[job]] tables"
        if len(value) > 1000:
            return "more than 1000 jobs"
        for n, job in enumerate(value, start=1):
            if not isinstance(job, dict):
                return f"job {n}: expected a [[job]] table, got {_kind(job)}"
            if not isinstance(job.get("command"), str):
                return f"job {n}: needs command = \"NAME\""
            for key, v in job.items():
                p = Scalar().problem(v)
                if p:
                    return f"job {n} {key}: {p}"
        return None


RECIPE = Table({"recipe": Table(ABOUT, label="recipe"), "job": Jobs()}, ("job",))
