"""The fractal figures: the Z-triplet, the boundary's Lindenmayer system and the curves grown
through the levels.

``fig_z_triplet`` and ``fig_fractal_curves`` are builders of ``figures.subdivision.FIGURES``;
``fractal_drawing`` is also what ``weave-cut fractal -o`` writes.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from .. import inputs
from ..analysis import boxcount as bc
from ..analysis import fractal as fr
from ..analysis import lsystem as ls
from ..subdivision import subdivide
from ..layout.drawing import (
    Drawing,
    Fit,
    Layer,
    Polylines,
    Style,
    Text,
    mesh_bounds,
)
from ..layout.mesh_figure import line_width
from .panels import (
    BLUE,
    CURVE_COLOURS,
    GREY,
    WHITE,
    Panel,
    grow,
    compose,
    discs,
    edge_coords,
    segments,
)

# -- Figure Z-triplet -------------------------------------------------------------------

def _arc(centre, radius, a0, a1, n=24) -> NDArray[np.float64]:
    t = np.linspace(a0, a1, n)
    return np.asarray(centre) + radius * np.column_stack([np.cos(t), np.sin(t)])


ANGLE_ARC = 0.09         # radius of the 2pi/3 arcs (the edge is 1 long)
ANGLE_LABEL = 0.145      # distance from the vertex to the middle of its 2pi/3 label
ANGLE_TEXT = 0.036       # height of the 2pi/3 labels


def angle_label_point(vertex, first_arm: float) -> NDArray[np.float64]:
    """Where the middle of a 2pi/3 label goes: on the bisector of the angle that opens at
    ``first_arm`` (radians) and turns 2pi/3 counter-clockwise, ANGLE_LABEL from ``vertex``."""
    mid = first_arm + np.pi / 3
    return np.asarray(vertex, dtype=float) + ANGLE_LABEL * np.array([np.cos(mid), np.sin(mid)])


def z_triplet_panel() -> Panel:
    pts = ls.lsystem_curve(1)
    a = ls.ALPHA

    def draw(fit: Fit) -> list[Layer]:
        s = fit.scale
        lw = 0.012 * s
        # a dashed look: the original edge as short pieces
        t = np.linspace(0, 1, 41)
        dash = np.column_stack([t, np.zeros_like(t)])
        dashes = np.stack([dash[0:-1:2], dash[1::2]], axis=1)
        z = Polylines(fit(pts), np.array([0, 4]), Style("#000000", lw))
        arc_a = Polylines(fit(_arc((0, 0), 0.22, 0, a)), np.array([0, 24]), Style("#000000", 0.5 * lw))
        e1 = pts[1] - pts[0]
        back = math.atan2(-e1[1], -e1[0])          # from z0 back to u: -160.9 degrees
        # the 120-degree angles: at z0 below the Z, at z1 above it
        arcs = ((pts[1], back), (pts[2], a))        # (vertex, first arm's angle)
        arc_b, arc_c = (Polylines(fit(_arc(v, ANGLE_ARC, a0, a0 + 2 * np.pi / 3)),
                                  np.array([0, 24]), Style("#000000", 0.5 * lw))
                        for v, a0 in arcs)
        r = 0.025 * s
        ends = discs(fit(pts[[0, 3]]), r, Style("#000000", 0.4 * lw, fill=WHITE))
        mids = discs(fit(pts[[1, 2]]), r, Style("#000000", 0.4 * lw, fill=BLUE))
        size = 0.06 * s
        lab = [Text(*fit(np.array([0.24, 0.012])), "\u03b1", size=0.8 * size)]
        # each 2pi/3 on its angle's bisector just beyond the arc (the text's middle there)
        for v, a0 in arcs:
            middle = angle_label_point(v, a0)
            lab.append(Text(*fit(middle - np.array([0.0, 0.35 * ANGLE_TEXT])), "2\u03c0/3",
                            size=ANGLE_TEXT * s, anchor="middle"))
        return [Layer("edge", "guide", (segments(fit(dashes), Style(GREY, 0.6 * lw)),)),
                Layer("z-triplet", "cut", (z, arc_a, arc_b, arc_c)),
                Layer("vertices", "paint", (ends, mids)),
                Layer("labels", "label", tuple(lab))]

    return Panel((-0.08, -0.3, 1.08, 0.3), draw, "Z-triplet: |e|/\u221a7 each, \u03b1 = atan(\u221a3/5)")


def fig_z_triplet() -> Drawing:
    return compose([z_triplet_panel()], 1, cell=40, title="Z-triplet")


# -- Figure FractalCurvesAndLindenmayer -----------------------------------------------------

def fractal_curves_panel(hierarchy, born: int = 1, caption: str | None = None) -> Panel:
    """The last level's edges in grey, the boundary in black and the curves grown from the
    inner edges of level ``born`` in colour."""
    mesh = hierarchy[-1].mesh
    last = len(hierarchy) - 1
    born = min(born, last)
    start = hierarchy[born].mesh
    kinds = fr.edge_kinds(start)
    inner = np.flatnonzero(kinds > 0)
    if born > 0:  # the curves born at this level (spokes), not older ones
        inner = inner[inner >= 3 * hierarchy[born - 1].mesh.topology.n_edges]

    def draw(fit: Fit) -> list[Layer]:
        lw = line_width(mesh, fit)
        layers = [Layer("edges", "guide", (segments(fit(edge_coords(mesh)),
                                                    Style("#c8c8c8", 0.7 * lw)),)),
                  Layer("boundary", "cut", (segments(fit(bc.boundary_segments(mesh)),
                                                     Style("#000000", 2 * lw)),))]
        if len(inner):
            verts, _ = fr.follow_curves(hierarchy, born, start.topology.edges[inner, 0],
                                        inner)[-1]
            pts = fr.curve_points(mesh, verts)
            shapes = []
            for k in range(len(CURVE_COLOURS)):  # a loop over colours
                sel = pts[k::len(CURVE_COLOURS)]
                if len(sel):
                    offsets = np.arange(0, sel.shape[0] * sel.shape[1] + 1, sel.shape[1])
                    shapes.append(Polylines(fit(sel.reshape(-1, 2)), offsets,
                                            Style(CURVE_COLOURS[k], 2 * lw)))
            layers.append(Layer(f"curves-from-level-{born}", "paint", tuple(shapes)))
        return layers

    return Panel(grow(mesh_bounds(mesh), 0.02), draw,
                 caption or f"level {last}: boundary and curves born at level {born}")


def lsystem_panel() -> Panel:
    pts = ls.lsystem_curve(1)

    def draw(fit: Fit) -> list[Layer]:
        lw = 0.01 * fit.scale
        size = 0.045 * fit.scale
        lines = [("\u25bd: rot(\u03b1)    \u25b3: rot(-\u03b1)", 0),
                 ("+: rot(\u03c0/3)    -: rot(-\u03c0/3)", 1),
                 ("F \u2192 \u25bd F - F + F \u25b3", 2),
                 (f"\u03b1 = atan(\u221a3/5) = {math.degrees(ls.ALPHA):.4f}\u00b0", 3),
                 (f"D = log 3 / log \u221a7 = {ls.DIMENSION:.5f}", 4)]
        texts = tuple(Text(*fit(np.array([0.5, -0.32 - 0.13 * i])), s, size=size,
                           anchor="middle") for s, i in lines)
        return [Layer("generator", "cut", (
            Polylines(fit(pts), np.array([0, 4]), Style("#000000", lw)),
            segments(fit(np.array([[[0, 0], [1, 0]]])), Style(GREY, 0.5 * lw)),
            Polylines(fit(_arc((0, 0), 0.2, 0, ls.ALPHA)), np.array([0, 24]),
                      Style("#000000", 0.5 * lw)),
            discs(fit(pts[[0, 3]]), 0.02 * fit.scale, Style("#000000", 0.4 * lw, fill=WHITE)),
            discs(fit(pts[[1, 2]]), 0.02 * fit.scale, Style("#000000", 0.4 * lw, fill=BLUE)))),
            Layer("rules", "label", texts)]

    return Panel((-0.1, -0.95, 1.1, 0.25), draw, "the boundary's Lindenmayer system")


def fractal_drawing(hierarchy, born: int = 1) -> Drawing:
    """``weave-cut fractal -o``: the curves of the last level next to the L-system."""
    return compose([fractal_curves_panel(hierarchy, born), lsystem_panel()], 2, cell=90,
                   title="Fractal curves and the Lindenmayer system")


def fig_fractal_curves() -> Drawing:
    return fractal_drawing(subdivide(inputs.get("pentagon"), 5))
