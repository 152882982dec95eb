"""Regenerate the generated example meshes (the hand-drawn ones are edited by hand).

    python examples/make_examples.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from weavecut.inputs import _weld
from weavecut.mesh_io import write_mesh
from weavecut.validation import validate

HERE = Path(__file__).parent


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


if __name__ == "__main__":
    write_mesh(voronoi_patch(), HERE / "voronoi-patch.json")
    write_mesh(voronoi_patch(), HERE / "voronoi-patch.obj")
    write_mesh(rhombus_star(), HERE / "rhombus-star.json")
