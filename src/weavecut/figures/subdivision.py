"""The paper's figures, by name: ``FIGURES = {name: (description, builder)}``.

A builder takes no arguments and returns a Drawing (vector figures) or PNG bytes (raster
figures). ``weave-cut figure NAME -o OUT`` writes one; ``weave-cut figure --list`` lists them.
Multi-panel figures are laid out on one sheet with a caption under every panel.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from .. import inputs
from ..analysis import convexity as cv
from ..analysis import fractal as fr
from ..analysis import levels as lv
from ..mesh import Mesh
from ..mesh_geometry import edge_lengths, signed_areas
from ..subdivision import snub, subdivide
from ..layout.drawing import (
    Drawing,
    Fit,
    Layer,
    Polygons,
    Polylines,
    Style,
    Text,
    mesh_bounds,
    mesh_polygons,
    polygons_from_rings,
)
from ..layout.mesh_figure import line_width
from .panels import (
    BLUE,
    CURVE_COLOURS,
    GREY,
    LIGHT_BLUE,
    RED,
    WHITE,
    Panel,
    grow,
    clip_faces,
    clip_segments,
    compose,
    curve_polylines,
    discs,
    edge_coords,
    mesh_panel,
    segments,
)

# -- Figure Z-triplet and operations 1-3 ------------------------------------------------

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
    pts = fr.lsystem_curve(1)
    a = fr.ALPHA

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


def paper_input() -> Mesh:
    """A small input like the paper's Figure InputMesh: convex faces around two inner vertices,
    with a boundary to the right (the view box :data:`PAPER_VIEW` cuts off the rest)."""
    v = [(0.0, 0.55), (0.1, -0.5), (1.0, 1.1), (1.25, 0.05), (1.0, -1.05),
         (-1.2, 1.5), (-1.5, 0.0), (-1.2, -1.5), (0.1, 2.0), (0.2, -2.0)]
    i1, i2, o1, o2, o3, l1, l2, l3, top, bottom = range(10)
    faces = [[i2, o2, o1, i1], [i1, o1, top], [i1, top, l1, l2], [i1, l2, i2],
             [i2, l2, l3, bottom], [i2, bottom, o3, o2]]
    return Mesh.from_faces(v, faces)


PAPER_VIEW = (-0.95, -1.3, 1.45, 1.35)


def _clipped_mesh_layers(mesh: Mesh, fit: Fit, box, lw: float, fill: str | None,
                         edges=None, stroke: str = "#000000") -> list[Layer]:
    layers = []
    if fill:
        layers.append(Layer("faces", "paint", (polygons_from_rings(
            [fit(r) for r in clip_faces(mesh, box)], Style(None, 0, fill=fill)),)))
    segs = clip_segments(edge_coords(mesh, edges), box)
    layers.append(Layer("edges", "cut", (segments(fit(segs), Style(stroke, lw)),)))
    return layers


def _inside(points, box) -> NDArray[np.bool_]:
    x0, y0, x1, y1 = box
    return ((points[:, 0] >= x0) & (points[:, 0] <= x1) & (points[:, 1] >= y0)
            & (points[:, 1] <= y1))


def operations_panels() -> list[Panel]:
    mesh = paper_input()
    level = snub.step(mesh, smooth=False)
    child = level.mesh
    box = PAPER_VIEW
    n_v, n_e = mesh.n_vertices, mesh.topology.n_edges

    def vertex_layer(fit, lw, ids_colours):
        shapes = []
        for pts, colour in ids_colours:
            pts = pts[_inside(pts, box)]
            shapes.append(discs(fit(pts), 0.03 * fit.scale, Style("#000000", 0.4 * lw,
                                                                   fill=colour)))
        return Layer("vertices", "paint", tuple(shapes))

    def input_draw(fit):
        lw = 0.012 * fit.scale
        return _clipped_mesh_layers(mesh, fit, box, lw, LIGHT_BLUE) + [
            vertex_layer(fit, lw, [(mesh.vertices, WHITE)])]

    def ops12_draw(fit):
        lw = 0.012 * fit.scale
        zig = level.edge_part != snub.SPOKE
        old = _clipped_mesh_layers(mesh, fit, box, 0.6 * lw, LIGHT_BLUE, stroke=GREY)
        new = _clipped_mesh_layers(child, fit, box, lw, None, edges=zig)
        return old + [Layer("z-triplets", "cut", new[0].shapes)] + [vertex_layer(
            fit, lw, [(child.vertices[:n_v], WHITE), (child.vertices[n_v:n_v + 2 * n_e], BLUE),
                      (child.vertices[n_v + 2 * n_e:], RED)])]

    def op3_draw(fit):
        lw = 0.012 * fit.scale
        faces = _clipped_mesh_layers(mesh, fit, box, 0.6 * lw, LIGHT_BLUE, stroke=GREY)[:1]
        new = _clipped_mesh_layers(child, fit, box, lw, None)
        return faces + [Layer("pentagons", "cut", new[0].shapes)] + [vertex_layer(
            fit, lw, [(child.vertices[:n_v], WHITE), (child.vertices[n_v:n_v + 2 * n_e], BLUE),
                      (child.vertices[n_v + 2 * n_e:], RED)])]

    return [Panel(box, input_draw, "input M0 (faces blue)"),
            Panel(box, ops12_draw, "operations 1 and 2"),
            Panel(box, op3_draw, "operation 3")]


def fig_z_triplet() -> Drawing:
    return compose([z_triplet_panel()], 1, cell=40, title="Z-triplet")


def fig_operations() -> Drawing:
    return compose([z_triplet_panel(), *operations_panels()], 4, cell=55,
                   title="Operations 1-3 of the pentagon snub step")


# -- Figure smoothingOp -----------------------------------------------------------------

def _edge_ratio(mesh: Mesh) -> NDArray[np.float64]:
    """(F,) longest over shortest edge of every face."""
    length = edge_lengths(mesh)[mesh.topology.half_edge_edge].reshape(-1, 5)
    return length.max(axis=1) / length.min(axis=1)


def fig_smoothing() -> Drawing:
    rough = subdivide(inputs.get("pentagon"), 4, smooth=False)[-1].mesh
    ratio = _edge_ratio(rough)
    long_faces = np.flatnonzero(ratio > np.quantile(ratio, 0.9))
    bad = np.flatnonzero(cv.nonconvex_faces(rough))
    # detail: around the first non-convex face
    c = rough.vertices[rough.dense_faces()[bad[0]]].mean(axis=0)
    half = 0.12
    detail = (c[0] - half, c[1] - half, c[0] + half, c[1] + half)

    def detail_draw(fit):
        lw = 0.35
        rings = clip_faces(Mesh(rough.vertices, np.arange(0, 5 * len(bad) + 1, 5),
                                rough.dense_faces()[bad].ravel()), detail)
        return [Layer("nonconvex", "paint", (polygons_from_rings(
            [fit(r) for r in rings], Style(None, 0, fill=BLUE)),)),
            Layer("edges", "cut", (segments(fit(clip_segments(edge_coords(rough), detail)),
                                            Style("#000000", lw)),))]

    coarse = subdivide(inputs.get("pentagon"), 1, smooth=False)[-1].mesh
    moved = snub.step(inputs.get("pentagon"), smooth=True).mesh
    level2_rough = snub.step(coarse, smooth=False).mesh
    level2 = snub.step(coarse, smooth=True).mesh
    shift = np.flatnonzero(np.hypot(*(level2.vertices - level2_rough.vertices).T) > 1e-12)

    def smooth_draw(fit):
        lw = 0.006 * fit.scale
        r = 0.02 * fit.scale
        arrows = np.stack([level2_rough.vertices[shift], level2.vertices[shift]], axis=1)
        return [Layer("before", "guide", (mesh_polygons(level2_rough, fit, Style(GREY, lw)),)),
                Layer("after", "cut", (mesh_polygons(level2, fit, Style("#000000", lw)),)),
                Layer("moves", "guide", (segments(fit(arrows), Style(RED, lw)),)),
                Layer("vertices", "paint", (
                    discs(fit(level2_rough.vertices[shift]), r, Style("#000000", 0.5 * lw,
                                                                     fill=WHITE)),
                    discs(fit(level2.vertices[shift]), r, Style("#000000", 0.5 * lw,
                                                                fill=BLUE))))]

    del moved
    bounds = grow(mesh_bounds(rough), 0.02)
    return compose([
        mesh_panel(rough, "no smoothing, level 4",
                   fills={LIGHT_BLUE: long_faces, BLUE: bad}),
        Panel(detail, detail_draw, "detail: a non-convex face"),
        Panel(bounds, smooth_draw, "smoothing: white to blue"),
    ], 3, cell=70, caption_size=2.4, title="Non-smoothed against smoothed refinement")


# -- Figures FirstSnubRefinementSteps and snubRefinementNonPentagonal --------------------

def fig_first_steps() -> Drawing:
    h = subdivide(inputs.get("pentagon"), 4)
    return compose([mesh_panel(h[t].mesh, f"level {t}", underlay=h[0].mesh)
                    for t in range(1, 5)], 4, cell=55,
                   title="First pentagon snub refinement steps")


def fig_non_pentagonal() -> Drawing:
    cases = [("tiling-8-4", 4, "8-4 mesh, level 4"), ("ngon:24", 3, "24-gon, level 3"),
             ("ngon:24", 4, "24-gon, level 4"),
             ("triangulated-ngon:24", 3, "triangulated 24-gon, level 3")]
    panels = []
    for spec, levels, caption in cases:
        h = subdivide(inputs.get(spec), levels)
        panels.append(mesh_panel(h[-1].mesh, caption, underlay=h[0].mesh))
    return compose(panels, 4, cell=60, title="Snub refinement of non-pentagonal inputs")


# -- Figure SubdivisionEdges --------------------------------------------------------------

COVERAGE = 0.3
ZOOM_CENTRE = (-0.33, 0.40)
ZOOM_HALF = 0.09


def edge_render_panel(hierarchy, caption: str, zoom_centre=ZOOM_CENTRE,
                      zoom_half: float = ZOOM_HALF) -> Panel:
    """All edges of the last level, width scaled to the edge length; a zoom-in box magnified
    into an inset to the right of the mesh."""
    mesh = hierarchy[-1].mesh
    x0, y0, x1, y1 = grow(mesh_bounds(mesh), 0.01)
    inset_side = y1 - y0
    gap = 0.08 * inset_side
    ix0 = x1 + gap
    bounds = (x0, y0, ix0 + 0.6 * inset_side, y1)
    zx, zy = zoom_centre
    zoom = (zx - zoom_half, zy - zoom_half, zx + zoom_half, zy + zoom_half)
    side = 0.6 * inset_side
    inset = (ix0, y1 - side, ix0 + side, y1)
    magnify = side / (2 * zoom_half)

    area = float(np.abs(signed_areas(mesh)).sum())
    total = float(edge_lengths(mesh).sum())

    def draw(fit: Fit) -> list[Layer]:
        # ink covers about COVERAGE of the mesh however many edges there are: level 8 turns
        # grey, not black (the paper's level 9 would be black at its line width)
        lw = float(np.clip(COVERAGE * area / total * fit.scale, 0.01, 0.3))
        curves = curve_polylines(hierarchy, Style("#000000", lw), fit)
        segs = clip_segments(edge_coords(mesh), zoom)
        to_inset = (segs - np.array(zoom[:2])) * magnify + np.array(inset[:2])
        lw_in = float(np.clip(lw * magnify, 0.01, 0.3))
        box = np.array([[zoom[0], zoom[1]], [zoom[2], zoom[1]], [zoom[2], zoom[3]],
                        [zoom[0], zoom[3]]])
        frame = np.array([[inset[0], inset[1]], [inset[2], inset[1]], [inset[2], inset[3]],
                          [inset[0], inset[3]]])
        links = np.array([[box[1], frame[0]], [box[2], frame[3]]])
        return [Layer("edges", "cut", curves),
                Layer("zoom", "cut", (segments(fit(to_inset), Style("#000000", lw_in)),)),
                Layer("zoom-boxes", "guide", (
                    Polygons(fit(np.vstack([box, frame])), np.array([0, 4, 8]),
                             Style(RED, 0.25)),
                    segments(fit(links), Style(RED, 0.15))))]

    return Panel(bounds, draw, caption)


def fig_edge_renders() -> Drawing:
    h = subdivide(inputs.get("pentagon"), 8)
    panels = [edge_render_panel(h[:t + 1], f"level {t}") for t in range(5, 9)]
    return compose(panels, 2, cell=80, title="Edges of refinement levels 5-8")


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
                  Layer("boundary", "cut", (segments(fit(fr.boundary_segments(mesh)),
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
    pts = fr.lsystem_curve(1)

    def draw(fit: Fit) -> list[Layer]:
        lw = 0.01 * fit.scale
        size = 0.045 * fit.scale
        lines = [("\u25bd: rot(\u03b1)    \u25b3: rot(-\u03b1)", 0),
                 ("+: rot(\u03c0/3)    -: rot(-\u03c0/3)", 1),
                 ("F \u2192 \u25bd F - F + F \u25b3", 2),
                 (f"\u03b1 = atan(\u221a3/5) = {math.degrees(fr.ALPHA):.4f}\u00b0", 3),
                 (f"D = log 3 / log \u221a7 = {fr.DIMENSION:.5f}", 4)]
        texts = tuple(Text(*fit(np.array([0.5, -0.32 - 0.13 * i])), s, size=size,
                           anchor="middle") for s, i in lines)
        return [Layer("generator", "cut", (
            Polylines(fit(pts), np.array([0, 4]), Style("#000000", lw)),
            segments(fit(np.array([[[0, 0], [1, 0]]])), Style(GREY, 0.5 * lw)),
            Polylines(fit(_arc((0, 0), 0.2, 0, fr.ALPHA)), np.array([0, 24]),
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


# -- convexity -----------------------------------------------------------------------------

def convexity_drawing(mesh: Mesh, size: float = 200.0, title: str = "non-convex faces"
                      ) -> Drawing:
    """The mesh in grey, non-convex faces filled red, reflex corners marked by blue dots."""
    bad = np.flatnonzero(cv.nonconvex_faces(mesh))

    def draw(fit: Fit) -> list[Layer]:
        lw = line_width(mesh, fit)
        layers = [Layer("mesh", "guide", (mesh_polygons(mesh, fit, Style("#777777", lw)),))]
        if len(bad):
            layers.append(Layer("nonconvex", "paint", (mesh_polygons(
                mesh, fit, Style("#000000", lw, fill=RED, opacity=0.85), faces=bad),)))
            pts = mesh.vertices[mesh.face_indices[cv.reflex_corners(mesh)]]
            layers.append(Layer("reflex-corners", "paint", (
                discs(fit(pts), max(3 * lw, 0.4), Style(None, 0, fill="#1030c0")),)))
        return layers

    label = (f"{len(bad)} non-convex face(s) of {mesh.n_faces:,} (red), reflex corners blue"
             if len(bad) else f"all {mesh.n_faces:,} faces convex")
    panel = Panel(grow(mesh_bounds(mesh), 0.02), draw, label)
    return compose([panel], 1, cell=size, title=title, caption_size=3.5)


# -- Figure colorLevels (raster) ---------------------------------------------------------------

LEVEL_ZOOM = (0.29, 0.09, 0.39, 0.19)


def _frame(rgb: NDArray[np.uint8], box, colour=(224, 48, 42), width: int = 2) -> None:
    r0, c0, r1, c1 = box
    rgb[r0:r0 + width, c0:c1] = colour
    rgb[r1 - width:r1, c0:c1] = colour
    rgb[r0:r1, c0:c0 + width] = colour
    rgb[r0:r1, c1 - width:c1] = colour


def level_image_png(size: int = 1200, zoom_size: int = 560, levels: int = 9,
                    zoom_levels: int = 12, zoom=LEVEL_ZOOM) -> bytes:
    """Figure colorLevels: the pentagon to level 9 (left, the zoom box framed in red); right,
    the box as the left image has it (enlarged pixels), and recomputed to level 12."""
    mesh = inputs.get("pentagon")
    big, grid = lv.level_image(mesh, levels, size)
    deep, _ = lv.level_image(mesh, zoom_levels, zoom_size, zoom)
    left = lv.colour(big)
    x0, _, _, y1 = grid.window
    c0 = int(round((zoom[0] - x0) / grid.pixel))
    c1 = int(round((zoom[2] - x0) / grid.pixel))
    r0 = int(round((y1 - zoom[3]) / grid.pixel))
    r1 = int(round((y1 - zoom[1]) / grid.pixel))
    crop = left[r0:r1, c0:c1]
    rows = np.minimum(np.arange(zoom_size) * crop.shape[0] // zoom_size, crop.shape[0] - 1)
    cols = np.minimum(np.arange(zoom_size) * crop.shape[1] // zoom_size, crop.shape[1] - 1)
    near = crop[rows][:, cols]
    _frame(left, (r0 - 2, c0 - 2, r1 + 2, c1 + 2))
    gap = 16
    height = max(left.shape[0], 2 * zoom_size + gap)
    canvas = np.full((height, left.shape[1] + gap + zoom_size, 3), 255, dtype=np.uint8)
    canvas[:left.shape[0], :left.shape[1]] = left
    for k, rgb in enumerate((near, lv.colour(deep))):
        rgb = rgb.copy()
        _frame(rgb, (0, 0, rgb.shape[0], rgb.shape[1]))
        top = k * (zoom_size + gap)
        canvas[top:top + rgb.shape[0], left.shape[1] + gap:left.shape[1] + gap + rgb.shape[1]] \
            = rgb
    legend = _legend(max(zoom_levels, levels) + 1, width=canvas.shape[1])
    return lv.png_bytes(np.concatenate([canvas, legend], axis=0))


def _legend(n: int, width: int, height: int = 28) -> NDArray[np.uint8]:
    """A strip of the level colours 0..n-1 (no text: the README explains the scale)."""
    out = np.full((height, width, 3), 255, dtype=np.uint8)
    cell = min(40, width // max(n, 1))
    colours = lv.colour(np.arange(n, dtype=np.uint8)[None, :])[0]
    for k in range(n):  # a loop over levels
        out[6:height - 6, k * cell + 2:(k + 1) * cell - 2] = colours[k]
    return out


# -- registry --------------------------------------------------------------------------------

FIGURES: dict[str, tuple[str, Callable[[], Drawing | bytes]]] = {
    "z-triplet": ("an edge replaced by a Z-triplet, with alpha and the 2pi/3 angles",
                  fig_z_triplet),
    "operations": ("Z-triplet and operations 1-3 on a small input with a boundary to the right",
                   fig_operations),
    "smoothing": ("non-smoothed refinement (long-edged and non-convex faces) against smoothing",
                  fig_smoothing),
    "first-steps": ("the first four snub refinement steps of a pentagon", fig_first_steps),
    "non-pentagonal": ("8-4 mesh level 4, 24-gon levels 3 and 4, triangulated 24-gon level 3",
                       fig_non_pentagonal),
    "fractal-curves": ("level-5 curves and the boundary's Lindenmayer system",
                       fig_fractal_curves),
    "edge-renders": ("edges of levels 5-8 of a pentagon with zoom-in boxes", fig_edge_renders),
    "level-image": ("pixels coloured by the first level with a vertex in them: level 9, and a "
                    "zoom to level 12 (PNG)", level_image_png),
}
