"""The paper's figures, by name (``FIGURES = {name: (description, builder)}``), and the
subdivision figures among them: operations 1-3, smoothing, refinement steps, edge renders.

A builder takes no arguments and returns a Drawing (vector figures) or PNG bytes (raster
figures). ``weave-cut figure NAME -o OUT`` writes one; ``weave-cut figure --list`` lists them.
Multi-panel figures are laid out on one sheet with a caption under every panel. The Z-triplet
and fractal figures are built in ``figures.fractal``, the level image in
``figures.level_image``; ``convexity_drawing`` here is what ``weave-cut convexity -o`` writes.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from .. import inputs
from ..analysis import convexity as cv
from ..mesh import Mesh
from ..text import counted
from ..mesh_geometry import edge_lengths, signed_areas
from ..subdivision import snub, subdivide
from ..layout.drawing import (
    Drawing,
    Fit,
    Layer,
    Polygons,
    Style,
    mesh_bounds,
    mesh_polygons,
    polygons_from_rings,
)
from ..layout import raster
from ..layout.mesh_figure import line_width
from .fractal import fig_fractal_curves, fig_z_triplet, z_triplet_panel
from .level_image import level_image_png
from .panels import (
    BLUE,
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

# -- Figure operations 1-3 (the Z-triplet panel: figures.fractal) -----------------------

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
    """All edges of the last level, width scaled to the edge length (a greyscale picture of
    them where they are too fine to print as lines: ``layout.raster``); a zoom-in box magnified
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
        if raster.too_fine(curves):  # levels 7 and 8: lines finer than a printer's dot
            curves = (raster.picture(curves),)
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

    label = (f"{counted(len(bad), 'non-convex face')} of {mesh.n_faces:,} (red), reflex "
             "corners blue"
             if len(bad) else f"all {mesh.n_faces:,} faces convex")
    panel = Panel(grow(mesh_bounds(mesh), 0.02), draw, label)
    return compose([panel], 1, cell=size, title=title, caption_size=3.5)


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
