"""Building blocks for multi-panel figures: a Panel is model bounds plus a function from a
Fit to layers; ``compose`` lays panels out on one sheet with captions."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import shapely
from numpy.typing import NDArray

from ..analysis import boxcount as bc
from ..analysis import fractal as fr
from ..mesh import Mesh
from ..layout.drawing import (
    Drawing,
    Fit,
    Layer,
    Polygons,
    Polylines,
    Sheet,
    Style,
    Text,
    mesh_bounds,
    mesh_polygons,
)
from ..layout.mesh_figure import line_width

BLUE = "#3b6fb6"
LIGHT_BLUE = "#cfe0f5"
GREY = "#9a9a9a"
RED = "#e0302a"
WHITE = "#ffffff"
CURVE_COLOURS = ("#e0302a", "#2a8f3f", "#3b6fb6", "#c77d14", "#8e3bb6")



@dataclass(frozen=True)
class Panel:
    """One panel: model-space ``bounds`` and a function from a Fit to the panel's layers."""

    bounds: tuple[float, float, float, float]
    draw: Callable[[Fit], list[Layer]]
    caption: str = ""


def compose(panels: list[Panel], columns: int, cell: float = 70.0, gap: float = 6.0,
            title: str = "weave-cut figure", caption_size: float = 2.6) -> Drawing:
    """Panels on a grid of ``columns``, each scaled into a ``cell`` mm high box (the width
    follows the panel's aspect), captions underneath."""
    aspects = [(b[2] - b[0]) / (b[3] - b[1]) for b in (p.bounds for p in panels)]
    rows = math.ceil(len(panels) / columns)
    widths = [max(aspects[i] for i in range(c, len(panels), columns)) * cell
              for c in range(min(columns, len(panels)))]
    text_h = 3 * caption_size if any(p.caption for p in panels) else 0.0
    width = sum(widths) + gap * (len(widths) + 1)
    height = rows * (cell + text_h) + gap * (rows + 1)
    layers = []
    for i, panel in enumerate(panels):
        r, c = divmod(i, columns)
        x = gap + sum(widths[:c]) + gap * c
        y = height - gap - (r + 1) * (cell + text_h) - gap * r + text_h
        b = panel.bounds
        scale = min(widths[c] / (b[2] - b[0]), cell / (b[3] - b[1]))
        fit = Fit(scale, (x + (widths[c] - (b[2] - b[0]) * scale) / 2 - b[0] * scale,
                          y + (cell - (b[3] - b[1]) * scale) / 2 - b[1] * scale))
        prefix = f"{chr(ord('a') + i)}-" if len(panels) > 1 else ""
        for layer in panel.draw(fit):
            layers.append(Layer(prefix + layer.name, layer.role, layer.shapes, layer.visible))
        if panel.caption:
            label = f"({chr(ord('a') + i)}) {panel.caption}" if len(panels) > 1 else panel.caption
            layers.append(Layer(prefix + "caption", "label", (
                Text(x + widths[c] / 2, y - 1.6 * caption_size, label, size=caption_size,
                     anchor="middle"),)))
    return Drawing((Sheet(width, height, tuple(layers)),), title)


def discs(points: NDArray[np.float64], radius: float, style: Style) -> Polygons:
    """A small 16-gon around every point (vertex markers)."""
    t = np.linspace(0, 2 * np.pi, 16, endpoint=False)
    ring = np.column_stack([np.cos(t), np.sin(t)]) * radius
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    coords = (pts[:, None, :] + ring[None]).reshape(-1, 2)
    return Polygons(coords, np.arange(0, len(coords) + 1, 16, dtype=np.int64), style)


def segments(coords: NDArray[np.float64], style: Style) -> Polylines:
    """Polylines of (n, 2, 2) segments."""
    coords = np.asarray(coords, dtype=float).reshape(-1, 2)
    return Polylines(coords, np.arange(0, len(coords) + 1, 2, dtype=np.int64), style)


def edge_coords(mesh: Mesh, edges=None) -> NDArray[np.float64]:
    """(n, 2, 2) endpoints of the mesh's edges (all, or the ids / mask given)."""
    return bc.mesh_segments(mesh, edges)


def clip_segments(segs: NDArray[np.float64], box) -> NDArray[np.float64]:
    """The parts of (n, 2, 2) segments inside ``box`` (x0, y0, x1, y1), as segments."""
    lines = shapely.linestrings(segs.reshape(-1, 2), indices=np.repeat(np.arange(len(segs)), 2))
    inter = shapely.intersection(lines, shapely.box(*box))
    parts = shapely.get_parts(inter[~shapely.is_empty(inter)])
    parts = parts[shapely.get_type_id(parts) == 1]
    if not len(parts):
        return np.zeros((0, 2, 2))
    coords, index = shapely.get_coordinates(parts, return_index=True)
    first = np.r_[True, index[1:] != index[:-1]]
    last = np.r_[index[1:] != index[:-1], True]
    return np.stack([coords[first], coords[last]], axis=1)


def clip_faces(mesh: Mesh, box) -> list[NDArray[np.float64]]:
    """The faces of ``mesh`` cut to ``box``, as rings (for panels showing part of a mesh)."""
    polys = shapely.polygons(shapely.linearrings(mesh.vertices[mesh.face_indices],
                                                 indices=mesh.half_edge_face))
    inter = shapely.intersection(polys, shapely.box(*box))
    inter = inter[~shapely.is_empty(inter)]
    return [np.asarray(g.exterior.coords)[:-1] for g in shapely.get_parts(inter)
            if g.geom_type == "Polygon"]


CHUNK = 4000  # points per Polylines: rsvg (libxml) rejects SVGs with many very long paths


def curve_polylines(hierarchy, style: Style, fit: Fit) -> tuple[Polylines, ...]:
    """Every edge of the last level, chained into the curves they grew from (level-0 edges and
    the spokes of every level), so the SVG repeats each point about once, not twice; split
    into batches of about CHUNK points."""
    last = len(hierarchy) - 1
    lines = []
    for s in range(last + 1):
        mesh = hierarchy[s].mesh
        n_e = mesh.topology.n_edges
        if s == 0:
            ids = np.arange(n_e)
        else:
            ids = np.arange(3 * hierarchy[s - 1].mesh.topology.n_edges, n_e)
        if not len(ids):
            continue
        verts, _ = fr.follow_curves(hierarchy, s, mesh.topology.edges[ids, 0], ids)[-1]
        lines.append(verts)
    mesh = hierarchy[-1].mesh
    counts = np.concatenate([np.full(len(v), v.shape[1]) for v in lines])
    ids = np.concatenate([v.ravel() for v in lines])
    offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    coords = fit(np.take(mesh.vertices, ids, axis=0))
    cuts = np.unique(np.searchsorted(offsets, np.arange(0, offsets[-1], CHUNK)))
    cuts = np.r_[cuts, len(offsets) - 1]
    return tuple(Polylines(coords[offsets[a]:offsets[b]], offsets[a:b + 1] - offsets[a], style)
                 for a, b in zip(cuts[:-1], cuts[1:]) if b > a)


def grow(bounds, by: float) -> tuple[float, float, float, float]:
    x0, y0, x1, y1 = bounds
    pad = by * max(x1 - x0, y1 - y0)
    return (x0 - pad, y0 - pad, x1 + pad, y1 + pad)


def mesh_panel(mesh: Mesh, caption: str, underlay: Mesh | None = None,
               fills: dict[str, NDArray] | None = None, bounds=None,
               stroke: str = "#000000") -> Panel:
    """A mesh drawn in black over an optional light-blue underlay, faces optionally filled."""
    if bounds is None:
        boxes = np.array([mesh_bounds(m) for m in (mesh, underlay) if m is not None])
        bounds = grow((*boxes[:, :2].min(axis=0), *boxes[:, 2:].max(axis=0)), 0.02)

    def draw(fit: Fit) -> list[Layer]:
        lw = line_width(mesh, fit)
        layers = []
        if underlay is not None:
            layers.append(Layer("input", "guide", (mesh_polygons(
                underlay, fit, Style(BLUE, 2 * lw, fill=LIGHT_BLUE)),)))
        for colour, faces in (fills or {}).items():
            if len(faces):
                layers.append(Layer(f"fill-{colour.lstrip('#')}", "paint", (mesh_polygons(
                    mesh, fit, Style(None, 0, fill=colour), faces=faces),)))
        layers.append(Layer("mesh", "cut", (mesh_polygons(mesh, fit, Style(stroke, lw)),)))
        return layers

    return Panel(bounds, draw, caption)


