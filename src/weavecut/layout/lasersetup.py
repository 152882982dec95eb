"""Laser set-up from presets: the colours a laser program expects per role (``templates/laser``)
and the material (``templates/materials``): thickness, kerf, sheet and cutting speed. Shared by
the products that write laser files (the puzzle, the paper strips cut from card)."""

from __future__ import annotations

from dataclasses import dataclass, field

from .. import presets
from ..units import to_mm
from .drawing import Style

DEFAULT_LASER = "lightburn"


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


def material(name: str) -> dict:
    """A material preset (``templates/materials``) with lengths in mm: thickness, kerf,
    sheet (width, height) and cut_speed (mm/s)."""
    doc = presets.load("materials", name)
    try:
        return {"name": str(doc.get("name", name)),
                "description": str(doc.get("description", name)),
                "thickness": to_mm(doc["thickness"]), "kerf": to_mm(doc["kerf"]),
                "sheet": presets.page_size(doc["sheet"]), "cut_speed": float(doc["cut_speed"])}
    except (KeyError, ValueError) as exc:
        raise presets.PresetError(f"material {name!r}: bad or missing {exc}") from exc
