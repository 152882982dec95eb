"""The paper's figures of the classic schemes (section 2) and of their weaves (section 5.3/5.4).

Every panel is drawn from the engine: the stages of a step are the scheme module's own pieces
(Loop's and butterfly's 1-to-4 split with unsmoothed points, sqrt3's relaxed old vertices and
face centres, mid-edge steps), the weaves come from ``weave/``; the strands that run along a
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
from ..mesh import Mesh
from ..mesh_geometry import face_centroids
from ..subdivision import butterfly, loop, sqrt3, subdivide
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
from .panels import BLUE, GREY, LIGHT_BLUE, RED, WHITE, Panel, compose, discs, edge_coords, grow
from .panels import segments

HIGHLIGHT = ("#0f7173", "#e07a1f", "#8e3bb6")   # a strand's descendants, one colour each
PALE = "#e6e6e6"


# -- inputs like the paper's ---------------------------------------------------------------

def triangle_input() -> Mesh:
    """A small irregular triangulation (inner vertices of valence 5 and 6), like the paper's
    ``triangulation_Input``."""
    v = [(0.0, 0.0), (1.0, 0.0), (0.5, 0.87), (-0.5, 0.87), (-1.0, 0.0), (-0.5, -0.87),
         (0.5, -0.87), (1.5, 0.9), (1.6, -0.5)]
    faces = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5], [0, 5, 6], [0, 6, 1], [1, 7, 2],
             [1, 8, 7], [1, 6, 8]]
    return Mesh.from_faces(v, faces)


def quad_dominant_input() -> Mesh:
    """Quads around one pentagon and one triangle, like the paper's ``quadDominant_input``."""
    v = [(x, y) for y in range(3) for x in range(4)] + [(1.5, 2.45), (2.35, 2.75)]
    g = [[x + 4 * y for x in range(4)] for y in range(3)]
    p, t = 12, 13
    faces = [[g[0][0], g[0][1], g[1][1], g[1][0]], [g[0][1], g[0][2], g[1][2], g[1][1]],
             [g[0][2], g[0][3], g[1][3], g[1][2]], [g[1][0], g[1][1], g[2][1], g[2][0]],
             [g[1][1], g[1][2], g[2][2], p, g[2][1]], [g[1][2], g[1][3], g[2][3], g[2][2]],
             [p, g[2][2], t]]
    return Mesh.from_faces(v, faces)


# -- drawing pieces ----------------------------------------------------------------------

def dashed(segs: NDArray[np.float64], pieces: int = 7) -> NDArray[np.float64]:
    """(n * pieces, 2, 2) every other piece of each segment cut into 2 * pieces - 1 parts."""
    t = np.linspace(0.0, 1.0, 2 * pieces)
    a, b = segs[:, None, 0], segs[:, None, 1]
    pts = a + (b - a) * t[None, :, None]
    return np.stack([pts[:, 0::2], pts[:, 1::2]], axis=2).reshape(-1, 2, 2)


def _bounds(*meshes: Mesh) -> tuple[float, float, float, float]:
    boxes = np.array([mesh_bounds(m) for m in meshes])
    return grow((*boxes[:, :2].min(axis=0), *boxes[:, 2:].max(axis=0)), 0.05)


def stage_panel(mesh: Mesh, caption: str, dots=(), ghost: Mesh | None = None,
                bounds=None, fills=None) -> Panel:
    """``mesh`` in black over an optional grey ``ghost`` (the stage before), ``dots`` a list
    of (points, fill colour) vertex markers, ``fills`` {colour: face ids}."""
    bounds = bounds or _bounds(*(m for m in (mesh, ghost) if m is not None))

    def draw(fit: Fit) -> list[Layer]:
        lw = line_width(mesh, fit)
        layers = []
        for colour, faces in (fills or {}).items():
            layers.append(Layer(f"fill-{colour.lstrip('#')}", "paint", (mesh_polygons(
                mesh, fit, Style(None, 0, fill=colour), faces=faces),)))
        if ghost is not None:
            layers.append(Layer("before", "guide", (mesh_polygons(ghost, fit,
                                                                  Style(GREY, 0.7 * lw)),)))
        layers.append(Layer("mesh", "cut", (mesh_polygons(mesh, fit, Style("#000000", lw)),)))
        layers.append(_dots(fit, lw, dots))
        return layers

    return Panel(bounds, draw, caption)


def _dots(fit: Fit, lw: float, dots) -> Layer:
    r = 0.028 * fit.scale
    return Layer("vertices", "paint", tuple(
        discs(fit(np.asarray(p, dtype=float).reshape(-1, 2)), r, Style("#000000", 0.5 * lw,
                                                                         fill=c))
        for p, c in dots if len(p)))



def points_panel(mesh: Mesh, caption: str, new_points, colour: str = BLUE) -> Panel:
    """The input mesh with its vertices white and ``new_points`` (to be inserted) in colour."""
    return stage_panel(mesh, caption, [(mesh.vertices, WHITE), (new_points, colour)])


def _edge_midpoints(mesh: Mesh) -> NDArray[np.float64]:
    return edge_coords(mesh).mean(axis=1)


# -- Figures LoopSubdivision, ButterflySubdivision, Sqrt3Subdivision, MidEdgeSubdivision --

def split_stages(mesh: Mesh, scheme, name: str, moved: str) -> list[Panel]:
    """Input, edge points inserted, 1-to-4 split, and the scheme's smoothed step."""
    n_v = mesh.n_vertices
    mids = _edge_midpoints(mesh)
    connected = loop.split_1_to_4(mesh, np.concatenate([mesh.vertices, mids])).mesh
    done = scheme.step(mesh).mesh
    return [stage_panel(mesh, f"{name}: input", [(mesh.vertices, WHITE)]),
            points_panel(mesh, "insert edge midpoints", mids),
            stage_panel(connected, "connect", [(connected.vertices[:n_v], WHITE),
                                               (connected.vertices[n_v:], BLUE)]),
            stage_panel(done, f"smooth ({moved})", [(done.vertices[:n_v], WHITE),
                                                   (done.vertices[n_v:], BLUE)],
                        ghost=connected)]


def sqrt3_stages(mesh: Mesh) -> list[Panel]:
    """Input, face centres, the 1-to-3 split on relaxed old vertices, the edge flip."""
    n_v = mesh.n_vertices
    centres = face_centroids(mesh)
    level = sqrt3.step(mesh)
    fi = mesh.face_indices
    fans = np.column_stack([fi, fi[mesh.next_half_edge], mesh.half_edge_face + n_v])
    connected = Mesh.from_faces(level.mesh.vertices, fans.tolist())
    return [stage_panel(mesh, "\u221a3: input", [(mesh.vertices, WHITE)]),
            points_panel(mesh, "insert face barycentres", centres),
            stage_panel(connected, "connect, smooth (white moved)",
                        [(connected.vertices[:n_v], WHITE), (connected.vertices[n_v:], BLUE)],
                        ghost=mesh),
            stage_panel(level.mesh, "flip the old edges", [(level.mesh.vertices[:n_v], WHITE),
                                                           (level.mesh.vertices[n_v:], BLUE)])]


def midedge_stages(mesh: Mesh) -> list[Panel]:
    """Input, edge midpoints, the mid-edge step, and a second step (= one Doo-Sabin step)."""
    h = subdivide(mesh, 2, "midedge")
    bounds = _bounds(mesh)
    return [stage_panel(mesh, "mid-edge: input", [(mesh.vertices, WHITE)], bounds=bounds),
            points_panel(mesh, "insert edge midpoints", _edge_midpoints(mesh)),
            stage_panel(h[1].mesh, "connect", [(h[1].mesh.vertices, BLUE)], ghost=mesh,
                        bounds=bounds),
            stage_panel(h[2].mesh, "second step (= Doo-Sabin)", ghost=mesh, bounds=bounds)]


def singularity_panels(mesh: Mesh) -> list[Panel]:
    """Figure SingularitiesOfSubdivision: Catmull-Clark's irregular vertices sit where the
    input has non-quads; Doo-Sabin keeps the non-quad faces."""
    bounds = _bounds(mesh)
    cc = subdivide(mesh, 2, "catmull-clark")[-1].mesh
    ds = subdivide(mesh, 2, "doo-sabin")[-1].mesh
    degree = np.bincount(cc.topology.edges.ravel(), minlength=cc.n_vertices)
    inner = ~np.isin(np.arange(cc.n_vertices), cc.topology.edges[cc.topology.boundary_edges])
    odd = cc.vertices[inner & (degree != 4)]
    return [stage_panel(mesh, "input mesh", [(mesh.vertices, WHITE)], bounds=bounds),
            stage_panel(cc, "Catmull-Clark x2: degree \u2260 4 red", [(odd, RED)],
                        bounds=bounds),
            stage_panel(ds, "Doo-Sabin x2: non-quads blue", bounds=bounds,
                        fills={LIGHT_BLUE: np.flatnonzero(ds.face_sizes != 4)})]


def fig_scheme_stages() -> Drawing:
    tri, quad = triangle_input(), quad_dominant_input()
    panels = (split_stages(tri, loop, "Loop", "white moved")
              + split_stages(tri, butterfly, "butterfly", "white kept")
              + sqrt3_stages(tri) + midedge_stages(quad) + singularity_panels(quad))
    return compose(panels, 4, cell=48, caption_size=2.3,
                   title="Loop, butterfly, sqrt3 and mid-edge stage by stage; singularities")


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
        layers.append(_dots(fit, lw, dots))
        return layers

    return Panel(_bounds(weave.mesh), draw, caption)


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
    bounds = _bounds(mesh)

    def spokes_panel(caption: str, with_edges: bool) -> Panel:
        def draw(fit: Fit) -> list[Layer]:
            lw = line_width(mesh, fit)
            layers = []
            if with_edges:
                layers.append(Layer("mesh", "cut", (mesh_polygons(mesh, fit,
                                                                  Style("#000000", lw)),)))
            layers.append(Layer("spokes", "cut", (segments(fit(spokes),
                                                           Style(BLUE, lw)),)))
            layers.append(_dots(fit, lw, [(mesh.vertices, BLUE), (centres, WHITE)]))
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
