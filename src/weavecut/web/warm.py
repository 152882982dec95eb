"""Importing this module loads every module of weave-cut a job may use (and so numpy, shapely,
scipy, ezdxf, reportlab, Pillow, svgelements): the warm parent that job processes fork from
(the embedded queue's forkserver preloads it; ``weave-cut worker`` imports it) then starts a
job in milliseconds instead of the second a fresh interpreter takes to import them.

Only imports (and ``gc.freeze``), no other effect; the command-line and web front ends and the ``__main__``
modules are left out (a job reaches its command through ``weavecut.cli.app``, loaded here).
"""

from __future__ import annotations

import importlib
import pkgutil

import weavecut


def modules() -> list[str]:
    """Every weave-cut module below the front ends, and the command group with its commands."""
    names = [m.name for m in pkgutil.walk_packages(weavecut.__path__, "weavecut.")
             if not m.name.endswith(".__main__")
             and not m.name.startswith(("weavecut.cli.", "weavecut.web."))]
    return [*names, "weavecut.cli.app", "weavecut.web.jobs", "weavecut.web.limits"]


def load() -> None:
    """Import them; then move every object made so far out of the garbage collector's sight
    (``gc.freeze``), so a forked child's collections do not touch, and so copy, the pages
    it shares with its parent."""
    import gc

    from .jobs import NOT_JOBS

    for name in modules():
        importlib.import_module(name)
    from ..cli.app import cli

    for command in cli.commands:
        if command not in NOT_JOBS:
            cli.commands[command]  # noqa: B018 - LazyCommands imports it on first access
    gc.collect()
    gc.freeze()


load()
