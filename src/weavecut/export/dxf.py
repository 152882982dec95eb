"""DXF writer: R2004, millimetres ($INSUNITS = 4), one layer per Drawing layer, closed
LWPOLYLINEs for stroked rings. Sheets after the first are placed to the right of it.

Colours: a layer has its role's colour (cut red, score blue, engrave green, as laser software
expects); a shape drawn in a colour of its own carries it as a true colour (R2004 is the
oldest DXF with true colours), except black on a cut, score or engrave layer, which stays
BYLAYER. Filled polygons become solid HATCHes, one layer per fill colour
(``<layer>-<rrggbb>``, in that true colour), so a weave keeps one layer per strand colour.

The title and metadata (generator, command) open the file as 999 comment groups, as LibreCAD
stamps its own files; every reader skips comments, ``ezdxf.comments`` reads them back. Text is
in the file's code page (ANSI_1252), other characters escaped as ``\\U+XXXX`` as ezdxf does.

A drawing of strokes only (a cut file) is written as text (``dxf_text``: ezdxf's bytes without
loading ezdxf, a quarter of a second); text and fills by ezdxf (``dxf_ezdxf``).
"""

from __future__ import annotations

from ..layout.drawing import Drawing
from . import dxf_text

SUFFIX = "dxf"


def render(drawing: Drawing) -> bytes:
    if dxf_text.plain(drawing):
        return dxf_text.render(drawing)
    from . import dxf_ezdxf
    return dxf_ezdxf.render(drawing)
