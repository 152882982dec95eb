"""Named presets (TOML) from ``templates/``: palettes, materials, laser colours, recipes.

A preset is found by name in ``templates/<kind>/<name>.toml`` (installed with the package as
``weavecut.templates``, or ``$WEAVECUT_TEMPLATES``), or given as a path to a ``.toml`` file. Every preset is
read through ``schema.read_toml`` (bounded) and checked against its kind's schema
(``schemas``) before use. A sheet size may name a page preset (``page_size``).
"""

from __future__ import annotations

import os
from importlib import resources
from pathlib import Path

from . import units
from .schema import (ABOUT, Choice, Colour, Length, ListOf, Number, SchemaError, Sheet, Table,
                     Text, Whole, nearest, read_toml)


class PresetError(SchemaError):
    """A preset is missing or malformed."""


def templates_dir() -> Path:
    """The presets folder: ``$WEAVECUT_TEMPLATES``, or the package ``weavecut.templates``:
    ``templates/`` of the checkout, installed as package data (setup.py maps it), so an
    editable and a wheel install both find it through ``importlib.resources``."""
    env = os.environ.get("WEAVECUT_TEMPLATES")
    return Path(env) if env else Path(resources.files("weavecut.templates"))


def folders(kind: str) -> list[Path]:
    """Where presets of ``kind`` are, first first: ``templates/<kind>``; recipes also in
    ``examples/`` (installed as the package ``weavecut.examples``, with their drawings)."""
    found = [templates_dir() / kind]
    if kind == "recipes":
        try:
            found.append(Path(resources.files("weavecut.examples")))
        except ModuleNotFoundError:  # the sources on PYTHONPATH, not installed
            pass
    return [f for f in found if f.is_dir()]


def names(kind: str) -> list[str]:
    """The preset names of one kind, sorted."""
    return sorted({p.stem for folder in folders(kind) for p in folder.glob("*.toml")})


def find(kind: str, name: str) -> Path:
    """The file of preset ``name`` (or ``name`` itself if it is a path to a .toml file)."""
    path = Path(name)
    if path.suffix == ".toml":
        return path
    path = next((f / f"{name}.toml" for f in folders(kind) if (f / f"{name}.toml").is_file()),
                Path())
    if not (path.is_file() and name in names(kind)):
        raise PresetError(f"unknown {kind[:-1] if kind.endswith('s') else kind} {name!r}"
                          f"{nearest(name, names(kind))}; "
                          f"choose one of {', '.join(names(kind)) or '(none found)'}")
    return path


def load(kind: str, name: str) -> dict:
    """The preset ``name`` (or a path to a .toml file) of ``kind`` as a dict, checked against
    ``schemas()[kind]`` when there is one (recipes are checked by ``build``)."""
    path = find(kind, name)
    doc = read_toml(path, PresetError)
    schema = schemas().get(kind)
    if schema is not None:
        schema.check(doc, str(path), PresetError)
    return doc


def page_size(value: str) -> tuple[float, float]:
    """A paper name (a4, a3, letter), a page preset (``templates/pages/NAME.toml``) or ``WxH``
    with units -> (width, height) in mm (``units.page_size`` without the presets).

    Examples
    --------
    >>> page_size("a5"), page_size("100x50mm")
    ((148.0, 210.0), (100.0, 50.0))
    """
    key = value.strip().lower()
    if key in units.PAPER_SIZES or "x" in key:
        return units.page_size(value)
    if key in names("pages"):  # a preset's own problem is said as such (PresetError)
        doc = load("pages", key)
        return (units.to_mm(doc["width"]), units.to_mm(doc["height"]))
    raise ValueError(f"{key!r} is not a page size"
                     f"{nearest(key, [*units.PAPER_SIZES, *names('pages')])}: use a4, a3, "
                     f"letter, a preset ({', '.join(names('pages'))}) or WxH like 200x300mm")


def _stroke(role: str) -> Table:
    return Table({"colour": Colour(), "width": Length(0, 10)}, ("colour",),
                 label=role)


LASER_FORMATS = ("svg", "dxf", "lbrn2")  # the files a laser command may write per sheet


def _operation(role: str) -> Table:
    """A laser operation's settings in a material preset (a LightBurn layer's): speed (the
    cut's is the material's ``cut_speed``), power (per cent of the laser's) and passes."""
    speed = {} if role == "cut" else {"speed": Number(0, 10_000, open_lo=True, unit="mm/s")}
    return Table({**speed, "power": Number(0, 100, open_lo=True, unit="%"),
                  "passes": Whole(1, 100)}, label=role)


def schemas() -> dict[str, Table]:
    """Each preset kind's schema: the limits of untrusted presets (the README's table "What a
    preset may hold"). Built at each call (microseconds, a few per command), not once at
    import: a table built at import is out of reach of mutation testing, which swaps a
    function's body in each test process after the import, so no test could fail for a
    wrong limit here."""
    return {
        "palettes": Table({**ABOUT, "colours": ListOf(Colour(), 1, 256),
                           "families": ListOf(ListOf(Colour(), 1, 16), 1, 256),
                           "family_names": ListOf(Text(40), 1, 256),
                           "colour_names": ListOf(Text(40), 1, 4096)},
                          one_of=("colours", "families")),
        "materials": Table({**ABOUT, "thickness": Length(0, 100, open_lo=True),
                            "kerf": Length(0, 5), "sheet": Sheet(page_size),
                            "cut_speed": Number(0, 10_000, open_lo=True, unit="mm/s"),
                            **{r: _operation(r) for r in ("cut", "score", "engrave")}},
                           ("thickness", "kerf", "sheet", "cut_speed")),
        "laser": Table({**ABOUT, **{r: _stroke(r) for r in ("cut", "score", "engrave")},
                        "formats": ListOf(Choice(LASER_FORMATS), 1, len(LASER_FORMATS))},
                       ("cut", "score", "engrave")),
        "pages": Table({**ABOUT, "width": Length(0, 10_000, open_lo=True),
                        "height": Length(0, 10_000, open_lo=True)}, ("width", "height")),
        "cutters": Table({**ABOUT, "marks": Choice(("square-and-corners", "corners", "frame")),
                          "inset": Length(0, 100), "length": Length(0, 100, open_lo=True),
                          "thickness": Length(0, 20, open_lo=True), "clearance": Length(0, 100),
                          "max_width": Length(0, 10_000, open_lo=True),
                          "max_height": Length(0, 10_000, open_lo=True),
                          "min_feature": Length(0, 100), "brand": Text(40)},
                         ("marks", "inset", "length", "thickness", "clearance", "min_feature")),
    }
