"""Regenerate the generated example meshes (the hand-drawn ones are edited by hand).

    python tools/make_examples.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from weavecut.inputs import _weld
from weavecut.mesh_io import write_mesh
from weavecut.validation import validate

HERE = Path(__file__).resolve().parents[1] / "examples"


def voronoi_patch(n: int = 18, seed: int = 7):
    """Convex Voronoi cells of n random points, clipped to a 10 x 7 rectangle."""
    rng = np.random.default_rng(seed)
    box = shapely.box(0, 0, 10, 7)
    points = shapely.multipoints(rng.uniform((0.5, 0.5), (9.5, 6.5), size=(n, 2)))
    cells = shapely.get_parts(shapely.voronoi_polygons(points, extend_to=box))
    cells = [shapely.set_precision(shapely.intersection(c, box), 1e-6) for c in cells]
    rings = [np.asarray(shapely.geometry.polygon.orient(c).exterior.coords)[:-1] for c in cells]
    return validate(_weld(rings, decimals=5))


def rhombus_star():
    """Five 72-degree rhombi around a centre: a star whose tips and notches alternate."""
    t = np.pi / 2 + 2 * np.pi * np.arange(5) / 5
    tips = 2 * np.column_stack([np.cos(t), np.sin(t)])
    rings = []
    for i in range(5):
        a, b = tips[i], tips[(i + 1) % 5]
        rings.append(np.array([[0.0, 0.0], a, a + b, b]))
    return validate(_weld(rings))


def cad_plate(path: Path) -> None:
    """A DXF as a CAD user draws it, in centimetres: a rounded 16 x 10 cm plate (an LWPOLYLINE
    with arc bulges) on layer OUTLINE, a 4 x 2 grid of 2 cm squares drawn with every edge once
    as LINEs on layer GRID, a note on layer NOTES and a block that is ignored."""
    import ezdxf

    ezdxf.options.write_fixed_meta_data_for_testing = True  # same bytes every time
    doc = ezdxf.new("R2000")
    doc.units = ezdxf.units.CM
    msp = doc.modelspace()
    r, w, h = 2.0, 16.0, 10.0
    bulge = np.tan(np.pi / 8)  # a quarter circle
    msp.add_lwpolyline([(r, 0, 0), (w - r, 0, bulge), (w, r, 0), (w, h - r, bulge), (w - r, h, 0),
                        (r, h, bulge), (0, h - r, 0), (0, r, bulge)], format="xyb", close=True,
                       dxfattribs={"layer": "OUTLINE"})
    for i in range(5):
        msp.add_line((20 + 2 * i, 0), (20 + 2 * i, 4), dxfattribs={"layer": "GRID"})
    for j in range(3):
        msp.add_line((20, 2 * j), (28, 2 * j), dxfattribs={"layer": "GRID"})
    msp.add_text("weave-cut example plate", dxfattribs={"layer": "NOTES", "height": 0.5}
                 ).set_placement((0, -1))
    block = doc.blocks.new("LOGO")
    block.add_circle((0, 0), 1.0)
    msp.add_blockref("LOGO", (8, 5), dxfattribs={"layer": "OUTLINE"})
    doc.saveas(path)


if __name__ == "__main__":
    write_mesh(voronoi_patch(), HERE / "voronoi-patch.json")
    write_mesh(voronoi_patch(), HERE / "voronoi-patch.obj")
    write_mesh(rhombus_star(), HERE / "rhombus-star.json")
    cad_plate(HERE / "plate.dxf")
