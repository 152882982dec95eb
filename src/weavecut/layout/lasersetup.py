"""Laser set-up from presets: the colours a laser program expects per role (``templates/laser``)
and the material (``templates/materials``): thickness, kerf, sheet, and per operation (cut,
score, engrave) the speed, power and passes a laser program's project carries (a LightBurn
layer's). Shared by the products that write laser files (the puzzle, the paper strips cut from
card)."""

from __future__ import annotations

from dataclasses import dataclass, field

from .. import presets
from ..units import to_mm
from .drawing import Style

DEFAULT_LASER = "lightburn"
DEFAULT_FORMATS = ("svg", "dxf")  # what a laser command writes per sheet unless told
ROLES = ("engrave", "score", "cut")  # the laser's operations, in the order they run
# a material preset without an operation's table gets these (power in per cent; the speeds of
# score and engrave as a multiple of the material's cut_speed): a start to test on a scrap
DEFAULT_POWER = {"cut": 60.0, "score": 20.0, "engrave": 15.0}
DEFAULT_SPEEDUP = {"cut": 1.0, "score": 5.0, "engrave": 5.0}


@dataclass(frozen=True)
class Operation:
    """How the laser runs one operation: ``speed`` mm/s, ``power`` per cent of the laser's,
    ``passes``."""

    speed: float
    power: float
    passes: int = 1


@dataclass(frozen=True)
class LaserJob:
    """What a laser program's project holds besides the drawing: the operation of every role
    (``ROLES``), the material, and what the outlines do about the kerf (a sentence: the
    project sets no Kerf Offset, so LightBurn cuts the outlines as drawn)."""

    operations: dict
    material: str = ""
    kerf: str = ""

    def operation(self, role: str) -> Operation:
        return self.operations[role]


def laser_job(mat: dict, kerf: str = "") -> LaserJob:
    """The LaserJob of a ``material`` dict; ``kerf`` says how the outlines treat the kerf."""
    return LaserJob(dict(mat["operations"]), f"{mat['description']}; preset {mat['name']}", kerf)


def kerf_note(kerf: float, grown: str) -> str:
    """What the outlines of ``grown`` (the files that are offset) do about a ``kerf`` mm beam."""
    if kerf <= 0:
        return ("the outlines are not offset (kerf 0): set the cut layers' Kerf Offset in "
                "LightBurn to half the beam's width")
    return (f"{grown} are grown by half the {kerf:g} mm kerf, so the parts come out true to "
            "size: leave LightBurn's Kerf Offset at 0")


@dataclass(frozen=True)
class Laser:
    """Colours and stroke widths a laser program expects per role (``templates/laser``)."""

    name: str
    styles: dict = field(default_factory=dict)

    def style(self, role: str) -> Style:
        entry = self.styles.get(role, {})
        return Style(entry.get("colour", "#000000"), to_mm(entry.get("width", "0.01mm")))


def laser(name: str = DEFAULT_LASER) -> Laser:
    doc = presets.load("laser", name)
    return Laser(str(doc.get("name", name)),
                 {k: v for k, v in doc.items() if isinstance(v, dict)})


def output_formats(given: tuple[str, ...] | None, laser_name: str) -> tuple[str, ...]:
    """The formats a laser command writes: ``given`` (``--formats``), else the laser preset's
    ``formats``, else ``DEFAULT_FORMATS``; in the order of ``presets.LASER_FORMATS``."""
    if given is None:
        given = tuple(presets.load("laser", laser_name).get("formats", DEFAULT_FORMATS))
    return tuple(f for f in presets.LASER_FORMATS if f in given)


def material(name: str) -> dict:
    """A material preset (``templates/materials``) with lengths in mm: thickness, kerf,
    sheet (width, height) and cut_speed (mm/s)."""
    doc = presets.load("materials", name)
    try:
        speed = float(doc["cut_speed"])
        return {"name": str(doc.get("name", name)),
                "description": str(doc.get("description", name)),
                "thickness": to_mm(doc["thickness"]), "kerf": to_mm(doc["kerf"]),
                "sheet": presets.page_size(doc["sheet"]), "cut_speed": speed,
                "operations": {role: _operation(doc.get(role, {}), role, speed)
                               for role in ROLES}}
    except (KeyError, ValueError) as exc:
        raise presets.PresetError(f"material {name!r}: bad or missing {exc}") from exc


def _operation(table: dict, role: str, cut_speed: float) -> Operation:
    """A role's Operation from its table in a material preset; the cut runs at ``cut_speed``,
    score and engrave by default ``DEFAULT_SPEEDUP`` times faster; power and passes default to
    ``DEFAULT_POWER`` and one."""
    return Operation(float(table.get("speed", cut_speed * DEFAULT_SPEEDUP[role])),
                     float(table.get("power", DEFAULT_POWER[role])),
                     int(table.get("passes", 1)))
