"""Named presets (TOML) from ``templates/``: palettes, materials, laser colours, recipes.

A preset is found by name in ``templates/<kind>/<name>.toml`` (the folder beside ``src/`` in a
checkout, or ``$WEAVECUT_TEMPLATES``), or given as a path to a ``.toml`` file.
"""

from __future__ import annotations

import os
import tomllib
from pathlib import Path

from .errors import WeaveCutError


class PresetError(WeaveCutError, ValueError):
    """A preset is missing or malformed."""


def templates_dir() -> Path:
    env = os.environ.get("WEAVECUT_TEMPLATES")
    if env:
        return Path(env)
    return Path(__file__).resolve().parents[2] / "templates"


def names(kind: str) -> list[str]:
    """The preset names of one kind, sorted."""
    folder = templates_dir() / kind
    return sorted(p.stem for p in folder.glob("*.toml")) if folder.is_dir() else []


def load(kind: str, name: str) -> dict:
    """The preset ``name`` (or a path to a .toml file) of ``kind`` as a dict."""
    path = Path(name)
    if path.suffix != ".toml":
        path = templates_dir() / kind / f"{name}.toml"
        if not path.is_file():
            raise PresetError(f"unknown {kind[:-1] if kind.endswith('s') else kind} {name!r}; "
                              f"choose one of {', '.join(names(kind)) or '(none found)'}")
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except OSError as exc:
        raise PresetError(f"cannot read {path}: {exc.strerror}") from exc
    except tomllib.TOMLDecodeError as exc:
        raise PresetError(f"{path}: {exc}") from exc
