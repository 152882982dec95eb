"""Named presets (TOML) from ``templates/``: palettes, materials, laser colours, recipes.

A preset is found by name in ``templates/<kind>/<name>.toml`` (installed with the package as
``weavecut.templates``, or ``$WEAVECUT_TEMPLATES``), or given as a path to a ``.toml`` file. Every preset is
read through ``schema.read_toml`` (bounded) and checked against its kind's schema before use.
"""

from __future__ import annotations

import os
from importlib import resources
from pathlib import Path

from .schema import SCHEMAS, SchemaError, nearest, read_toml


class PresetError(SchemaError):
    """A preset is missing or malformed."""


def templates_dir() -> Path:
    """The presets folder: ``$WEAVECUT_TEMPLATES``, or the package ``weavecut.templates``:
    ``templates/`` of the checkout, installed as package data (setup.py maps it), so an
    editable and a wheel install both find it through ``importlib.resources``."""
    env = os.environ.get("WEAVECUT_TEMPLATES")
    return Path(env) if env else Path(resources.files("weavecut.templates"))


def names(kind: str) -> list[str]:
    """The preset names of one kind, sorted."""
    folder = templates_dir() / kind
    return sorted(p.stem for p in folder.glob("*.toml")) if folder.is_dir() else []


def find(kind: str, name: str) -> Path:
    """The file of preset ``name`` (or ``name`` itself if it is a path to a .toml file)."""
    path = Path(name)
    if path.suffix == ".toml":
        return path
    path = templates_dir() / kind / f"{name}.toml"
    if not (path.is_file() and name in names(kind)):
        raise PresetError(f"unknown {kind[:-1] if kind.endswith('s') else kind} {name!r}"
                          f"{nearest(name, names(kind))}; "
                          f"choose one of {', '.join(names(kind)) or '(none found)'}")
    return path


def load(kind: str, name: str) -> dict:
    """The preset ``name`` (or a path to a .toml file) of ``kind`` as a dict, checked against
    ``schema.SCHEMAS[kind]`` when there is one (recipes are checked by ``build``)."""
    path = find(kind, name)
    doc = read_toml(path, PresetError)
    if kind in SCHEMAS:
        SCHEMAS[kind].check(doc, str(path), PresetError)
    return doc
