"""Named presets (TOML) from ``templates/``: palettes, materials, laser colours, recipes.

A preset is found by name in ``templates/<kind>/<name>.toml`` (the folder beside ``src/`` in a
checkout, or ``$WEAVECUT_TEMPLATES``), or given as a path to a ``.toml`` file.
"""

from __future__ import annotations

import os
import tomllib
from importlib import resources
from pathlib import Path

from .errors import WeaveCutError


class PresetError(WeaveCutError, ValueError):
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
    """The file of preset ``name`` of ``kind``; a name ending in .toml is a path already."""
    path = Path(name)
    if path.suffix != ".toml":
        path = templates_dir() / kind / f"{name}.toml"
        if not path.is_file():
            raise PresetError(f"unknown {kind[:-1] if kind.endswith('s') else kind} {name!r}; "
                              f"choose one of {', '.join(names(kind)) or '(none found)'}")
    return path


def load(kind: str, name: str) -> dict:
    """The preset ``name`` (or a path to a .toml file) of ``kind`` as a dict."""
    path = find(kind, name)
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except OSError as exc:
        raise PresetError(f"cannot read {path}: {exc.strerror}") from exc
    except tomllib.TOMLDecodeError as exc:
        raise PresetError(f"{path}: {exc}") from exc
