"""A subdivided mesh as a Drawing, cut-ready: every edge once, joined into long trails."""

from __future__ import annotations

import numpy as np

from ..mesh import Mesh
from ..mesh_geometry import edge_lengths
from . import cutpaths
from .drawing import Drawing, Fit, Layer, Sheet, Style, mesh_bounds, polylines_from_lines

UNDERLAY = "#7fa7d9"


def line_width(mesh: Mesh, fit: Fit) -> float:
    """A stroke width (mm) that keeps small faces readable: a tenth of the median edge."""
    median = float(np.median(edge_lengths(mesh))) * fit.scale
    return float(np.clip(0.1 * median, 0.02, 0.35))


def edge_trails(mesh: Mesh, fit: Fit) -> tuple[list, list]:
    """Every edge of ``mesh`` once on the sheet, joined into trails: (inner, boundary)."""
    corners = fit(np.take(mesh.vertices, mesh.face_indices, axis=0))
    graph = cutpaths.shared_edges(corners, np.asarray(mesh.face_offsets, dtype=np.int64))
    return cutpaths.trails(graph, graph.uses > 1), cutpaths.trails(graph, graph.uses == 1)


def mesh_drawing(meshes: list[Mesh], size: float, margin: float = 10.0,
                 title: str = "weave-cut", earlier: bool = False) -> Drawing:
    """One sheet, ``size`` mm on the longer side plus margins.

    ``meshes`` go from the input (level 0) to the final level. The final level is cut as a
    laser would: each shared edge once, the inner trails (layer ``cut-1-inner``) before the
    outline (``cut-2-outline``), so the part stays in the sheet until the end. With
    ``earlier`` the levels before it are drawn too, each on its own layer ``level-K`` under
    the cut (the input light blue, the others light grey), for looking at, not for cutting.
    """
    shown = meshes if earlier else meshes[-1:]
    boxes = np.array([mesh_bounds(m) for m in shown])
    x0, y0 = boxes[:, :2].min(axis=0)
    x1, y1 = boxes[:, 2:].max(axis=0)
    scale = size / max(x1 - x0, y1 - y0)
    width, height = (x1 - x0) * scale + 2 * margin, (y1 - y0) * scale + 2 * margin
    fit = Fit.into((x0, y0, x1, y1), width, height, margin)
    layers = []
    for t, mesh in enumerate(shown[:-1]):
        colour, factor = (UNDERLAY, 2.0) if t == 0 else ("#b0b0b0", 0.7)
        style = Style(colour, factor * line_width(mesh, fit))
        lines = polylines_from_lines([p for part in edge_trails(mesh, fit) for p in part], style)
        layers.append(Layer(f"level-{t}", "guide", (lines,)))
    final = meshes[-1]
    inner, outline = edge_trails(final, fit)
    cut = Style("#000000", line_width(final, fit))
    layers += [Layer("cut-1-inner", "cut", (polylines_from_lines(inner, cut),)),
               Layer("cut-2-outline", "cut", (polylines_from_lines(outline, cut),))]
    return Drawing((Sheet(width, height, tuple(layers)),), title)
