"""Commands loaded when first used, so ``weave-cut COMMAND`` imports one command's module.

A click group keeps its commands in ``group.commands``; ``LazyCommands`` is that mapping with
each command named by where it lives (``".weave_command:weave_command"``) and imported on
first access. ``weave-cut --help`` still looks at every command (for its one-line help), which
stays fast because the command modules import numpy at most; their heavy imports (shapely,
scipy, ezdxf, reportlab, Pillow) sit inside the commands.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator, MutableMapping

import click


class LazyCommands(MutableMapping):
    """Commands by name, each imported from ``"module:attribute"`` (relative to this package)
    on first access; commands added later are kept as given."""

    def __init__(self, where: dict[str, str]) -> None:
        self._where = dict(where)
        self._loaded: dict[str, click.Command] = {}

    def __getitem__(self, name: str) -> click.Command:
        if name not in self._loaded:
            module, _, attribute = self._where[name].partition(":")
            self._loaded[name] = getattr(importlib.import_module(module, __package__), attribute)
        return self._loaded[name]

    def __setitem__(self, name: str, command: click.Command) -> None:
        self._where.setdefault(name, "")
        self._loaded[name] = command

    def __delitem__(self, name: str) -> None:
        del self._where[name]
        self._loaded.pop(name, None)

    def __iter__(self) -> Iterator[str]:
        return iter(self._where)

    def __len__(self) -> int:
        return len(self._where)
