"""A subdivided mesh as a Drawing: the final level outlined over its input, drawn faintly."""

from __future__ import annotations

import numpy as np

from ..mesh import Mesh, edge_lengths
from .drawing import Drawing, Fit, Layer, Sheet, Style, mesh_bounds, mesh_polygons

UNDERLAY = "#7fa7d9"


def line_width(mesh: Mesh, fit: Fit) -> float:
    """A stroke width (mm) that keeps small faces readable: a tenth of the median edge."""
    median = float(np.median(edge_lengths(mesh))) * fit.scale
    return float(np.clip(0.1 * median, 0.02, 0.35))


def mesh_drawing(meshes: list[Mesh], size: float, margin: float = 10.0,
                 title: str = "weave-cut") -> Drawing:
    """One sheet, ``size`` mm on the longer side plus margins, a layer per mesh.

    ``meshes`` go from the input (level 0) to the final level; the last is drawn black, the
    input light blue underneath, the levels between as hidden layers a user can switch on.
    """
    boxes = np.array([mesh_bounds(m) for m in meshes])
    x0, y0 = boxes[:, :2].min(axis=0)
    x1, y1 = boxes[:, 2:].max(axis=0)
    w, h = x1 - x0, y1 - y0
    scale = size / max(w, h)
    width, height = w * scale + 2 * margin, h * scale + 2 * margin
    fit = Fit.into((x0, y0, x1, y1), width, height, margin)
    layers = []
    last = len(meshes) - 1
    for t, mesh in enumerate(meshes):
        if t == last:
            style = Style("#000000", line_width(mesh, fit))
        elif t == 0:
            style = Style(UNDERLAY, 2 * line_width(mesh, fit), fill="#eef3fa")
        else:
            style = Style("#555555", line_width(mesh, fit))
        role = "cut" if t == last else "guide"
        visible = t in (0, last)
        layers.append(Layer(f"level-{t}", role, (mesh_polygons(mesh, fit, style),), visible))
    return Drawing((Sheet(width, height, tuple(layers)),), title)
