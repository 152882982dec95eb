"""The paper's figures of the classic schemes' weaves (section 5.3/5.4), and the registry of
the classic-scheme figures (the stages of section 2 are drawn in ``figures.scheme_stages``).

Every panel is drawn from the engine: the weaves come from ``weave/``; the strands that run along a
parent strand are found from face provenance: inside the band of tiles it passes they are on
top of many faces, strands that cross the band of a few. ``FIGURES`` has the shape of
``figures.subdivision.FIGURES``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import shapely
from numpy.typing import NDArray

from .. import inputs
from ..subdivision import subdivide
from ..weave.face_split import face_split_mesh, face_split_weave
from ..weave.colour import palette, strand_colours
from ..weave.model import Weave
from ..weave.quad import quad_weave
from ..weave.schemes import scheme_weaves
from ..weave.two_colouring import (
    catmull_clark_colouring,
    disc_two_colouring,
    triangle_colouring_step,
    triangle_three_colouring,
)
from ..layout.drawing import (
    Drawing,
    Fit,
    Layer,
    Style,
    mesh_bounds,
    mesh_polygons,
    polygons_from_shapely,
)
from ..layout.mesh_figure import line_width
from ..layout.weave_figure import tile_centres, weave_layers
from .panels import BLUE, WHITE, Panel, compose, edge_coords, segments
from .scheme_stages import (
    bounds_of,
    dashed,
    dots_layer,
    fig_scheme_stages,
    quad_dominant_input,
    stage_panel,
)

HIGHLIGHT = ("#0f7173", "#e07a1f", "#8e3bb6")   # a strand's descendants, one colour each
PALE = "#e6e6e6"


# -- weave panels ------------------------------------------------------------------------

def weave_panel(weave: Weave, colours: list[str], caption: str, dots=(), input_mesh=None,
                dashed_edges=None, ribbons: bool = True, region=None) -> Panel:
    """A weave (ribbons over its faces, or coloured tiles), with optional vertex dots, the
    input mesh on top, dashed edges, and a ``region`` (shapely polygon) outlined."""
    def draw(fit: Fit) -> list[Layer]:
        lw = line_width(weave.mesh, fit)
        layers = weave_layers(weave, colours, fit, ribbons=ribbons)
        if dashed_edges is not None and len(dashed_edges):
            layers.append(Layer("removed-edges", "guide", (segments(
                fit(dashed(dashed_edges)), Style("#000000", 0.8 * lw)),)))
        if region is not None:
            parts = shapely.get_parts(shapely.transform(region, fit))
            layers.append(Layer("strand-region", "guide", (polygons_from_shapely(
                list(parts), Style("#000000", 1.6 * lw)),)))
        if input_mesh is not None:
            layers.append(Layer("input", "guide", (mesh_polygons(
                input_mesh, fit, Style("#000000", 1.6 * lw)),)))
        layers.append(dots_layer(fit, lw, dots))
        return layers

    return Panel(bounds_of(weave.mesh), draw, caption)


def family_colours(n_strands: int, groups: list[NDArray[np.bool_]]) -> list[str]:
    """Strand colours: strands of group k in HIGHLIGHT[k], all others pale."""
    out = np.full(n_strands, PALE, dtype=object)
    for colour, group in zip(HIGHLIGHT, groups):
        out[group] = colour
    return out.tolist()


def _band(parent: Weave, strand: int) -> NDArray[np.bool_]:
    """(F,) True for the parent faces in the tiles ``strand`` passes, over or under."""
    tile = parent.face_tile
    return (tile >= 0) & ((parent.tile_over[tile] == strand) | (parent.tile_under[tile] == strand))


def along(parent: Weave, child: Weave, parent_face: NDArray, strand: int) -> NDArray[np.bool_]:
    """(S_child,) the child strands that run along ``strand``: inside the tiles it passes
    (``parent_face`` maps child faces to parent faces, across one step or several), each is
    on top of at least half as many faces as the child strand on top of most faces there;
    strands that only cross the band are on top of a few."""
    top = child.tile_over[child.face_tile]
    keep = _band(parent, strand)[parent_face] & (top >= 0)
    faces = np.bincount(top[keep], minlength=child.n_strands)
    return faces >= max(faces.max(), 1) / 2


def footprint(parent: Weave, strand: int) -> shapely.Geometry:
    """The band of tiles ``strand`` passes (the region its children share), as one polygon."""
    mesh = parent.mesh
    polys = shapely.polygons(shapely.linearrings(mesh.vertices[mesh.face_indices],
                                                 indices=mesh.half_edge_face))
    return shapely.union_all(polys[_band(parent, strand)])


def _one_each(mask: NDArray[np.bool_]) -> list[NDArray[np.bool_]]:
    """One mask per strand of ``mask`` (so siblings get different colours)."""
    return [np.arange(len(mask)) == s for s in np.flatnonzero(mask)]


def central_strand(weave: Weave) -> int:
    """A long strand through the middle: of the strands on top of at least half as many tiles
    as the longest, the one whose tiles' mean is nearest the centre of the mesh."""
    own = np.bincount(weave.visit_strand[weave.visit_over], minlength=weave.n_strands)
    centres = tile_centres(weave)[weave.strand_visits[weave.visit_over]]
    strands = weave.visit_strand[weave.visit_over]
    mean = np.stack([np.bincount(strands, weights=centres[:, k], minlength=weave.n_strands)
                     for k in range(2)], axis=1) / np.maximum(own, 1)[:, None]
    x0, y0, x1, y1 = mesh_bounds(weave.mesh)
    far = np.hypot(mean[:, 0] - (x0 + x1) / 2, mean[:, 1] - (y0 + y1) / 2)
    far[own < own.max() / 2] = np.inf
    return int(np.argmin(far))


def all_colours(weave: Weave) -> list[str]:
    """Every strand in a colour of the okabe-ito palette (crossing strands differ)."""
    return strand_colours([weave], palette("okabe-ito"))


# -- Figure Catmull-ClarkWeaving --------------------------------------------------------------

def fig_two_colourings() -> Drawing:
    grid = inputs.get("square-grid:4x4")
    c1 = disc_two_colouring(grid)
    w = quad_weave(grid, c1)
    square = weave_panel(w, all_colours(w), "square grid: c1 blue, c2 white",
                         dots=[(grid.vertices[c1], BLUE), (grid.vertices[~c1], WHITE)])
    h = subdivide(quad_dominant_input(), 2, "catmull-clark")
    weaves = scheme_weaves(h, "catmull-clark")
    first = central_strand(weaves[0])
    kids = along(weaves[0], weaves[1], h[2].parent_face, first)
    panels = [square]
    for k, (level, weave) in enumerate(zip(h[1:], weaves), start=1):
        edge_points = catmull_clark_colouring(level)
        groups = [np.arange(weave.n_strands) == first] if k == 1 else _one_each(kids)
        caption = ("Catmull-Clark: edge points white" if k == 1
                   else f"another step: {int(kids.sum())} parallel strands")
        panels.append(weave_panel(weave, family_colours(weave.n_strands, groups), caption,
                                  dots=[(level.mesh.vertices[~edge_points], BLUE),
                                        (level.mesh.vertices[edge_points], WHITE)]))
    return compose(panels, 3, cell=70, title="Weaving from a two-colouring; Catmull-Clark")


# -- Figures LoopWeaving and Sqrt3Weaving ------------------------------------------------------

def fig_loop_split() -> Drawing:
    h = subdivide(inputs.get("triangle-grid:3x3"), 2, "loop")
    weaves = scheme_weaves(h, "loop")
    c1 = triangle_colouring_step(h[0].mesh, triangle_three_colouring(h[0].mesh))
    mesh = h[1].mesh
    e = mesh.topology.edges
    removed = edge_coords(mesh, ~c1[e[:, 0]] & ~c1[e[:, 1]])
    strand = central_strand(weaves[0])
    kids = along(weaves[0], weaves[1], h[2].parent_face, strand)
    dots = [(mesh.vertices[c1], BLUE), (mesh.vertices[~c1], WHITE)]
    return compose([
        weave_panel(weaves[0], [""] * weaves[0].n_strands,
                    "remove the dashed c2-c2 edges", dots=dots, dashed_edges=removed,
                    ribbons=False),
        weave_panel(weaves[0], family_colours(weaves[0].n_strands,
                                              [np.arange(weaves[0].n_strands) == strand]),
                    "glued triangles: a strand"),
        weave_panel(weaves[1], family_colours(weaves[1].n_strands, _one_each(kids)),
                    f"Loop step: {int(kids.sum())} parallel strands"),
    ], 3, cell=70, title="Loop weave: a strand splits into two parallel strands")


def fig_sqrt3_split() -> Drawing:
    h = subdivide(inputs.get("triangle-grid:6x6"), 3, "sqrt3")
    weaves = scheme_weaves(h, "sqrt3")
    strand = central_strand(weaves[0])
    region = footprint(weaves[0], strand)
    two_steps = h[2].parent_face[h[3].parent_face]          # level-3 face -> level-1 face
    three = along(weaves[0], weaves[2], two_steps, strand)
    return compose([
        weave_panel(weaves[0], family_colours(weaves[0].n_strands,
                                              [np.arange(weaves[0].n_strands) == strand]),
                    "\u221a3 weave: a strand", region=region),
        weave_panel(weaves[1], all_colours(weaves[1]), "one step: strands run across it",
                    region=region),
        weave_panel(weaves[2], family_colours(weaves[2].n_strands, _one_each(three)),
                    f"two steps: {int(three.sum())} parallel strands along it", region=region),
    ], 3, cell=80, title="sqrt3 weave: two steps split a strand into three")


# -- Figure FaceSplitWeaving ----------------------------------------------------------------

def fig_face_split_construction() -> Drawing:
    mesh = quad_dominant_input()
    n_v = mesh.n_vertices
    quads = face_split_mesh(mesh)
    centres = quads.vertices[n_v:]
    spokes = np.stack([mesh.vertices[mesh.face_indices],
                       centres[mesh.half_edge_face]], axis=1)
    weave = face_split_weave(mesh)
    colours = all_colours(weave)
    bounds = bounds_of(mesh)

    def spokes_panel(caption: str, with_edges: bool) -> Panel:
        def draw(fit: Fit) -> list[Layer]:
            lw = line_width(mesh, fit)
            layers = []
            if with_edges:
                layers.append(Layer("mesh", "cut", (mesh_polygons(mesh, fit,
                                                                  Style("#000000", lw)),)))
            layers.append(Layer("spokes", "cut", (segments(fit(spokes),
                                                           Style(BLUE, lw)),)))
            layers.append(dots_layer(fit, lw, [(mesh.vertices, BLUE), (centres, WHITE)]))
            return layers
        return Panel(bounds, draw, caption)

    used = np.zeros(quads.n_vertices, dtype=bool)
    used[quads.face_indices] = True
    c1 = np.arange(quads.n_vertices) < n_v
    dots = [(quads.vertices[used & c1], BLUE), (quads.vertices[used & ~c1], WHITE)]
    return compose([
        stage_panel(mesh, "arbitrary input mesh", [(mesh.vertices, BLUE)], bounds=bounds),
        spokes_panel("add face mid-points and spokes", True),
        spokes_panel("remove the old edges", False),
        stage_panel(quads, "two-coloured quad mesh", dots, bounds=bounds),
        weave_panel(weave, colours, "induced weave"),
        weave_panel(weave, colours, "weave over the input mesh", input_mesh=mesh),
    ], 3, cell=60, title="Face-split weave for an arbitrary mesh")


FIGURES: dict[str, tuple[str, Callable[[], Drawing | bytes]]] = {
    "scheme-stages": ("Loop, butterfly, sqrt3 and mid-edge stage by stage (input, insert, "
                      "connect, smooth) and the singularities of Catmull-Clark and Doo-Sabin",
                      fig_scheme_stages),
    "two-colourings": ("a square grid's two-colouring and weave; Catmull-Clark's two-colouring "
                       "before and after another step", fig_two_colourings),
    "loop-split": ("Loop's weave: dashed c2-c2 edges removed, a strand, its two parallel "
                   "children", fig_loop_split),
    "sqrt3-split": ("sqrt3's weave: a strand, the crossing strands of the next step, its three "
                    "parallel grandchildren", fig_sqrt3_split),
    "face-split-construction": ("the six steps of the face-split weave on an arbitrary mesh",
                                fig_face_split_construction),
}
