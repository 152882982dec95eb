"""The paper's figures of the classic schemes stage by stage (section 2): inputs like the
paper's, and each step's stages drawn from the scheme module's own pieces (Loop's and
butterfly's 1-to-4 split with unsmoothed points, sqrt3's relaxed old vertices and face centres,
mid-edge steps), with the singularities of Catmull-Clark and Doo-Sabin. ``figures.schemes``
draws their weaves over the same inputs."""

from __future__ import annotations


import numpy as np
from numpy.typing import NDArray

from ..layout.drawing import Drawing, Fit, Layer, Style, mesh_bounds, mesh_polygons
from ..layout.mesh_figure import line_width
from ..mesh import Mesh
from ..mesh_geometry import face_centroids
from ..subdivision import butterfly, loop, sqrt3, subdivide
from .panels import BLUE, GREY, LIGHT_BLUE, RED, WHITE, Panel, compose, discs, edge_coords, grow


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


def bounds_of(*meshes: Mesh) -> tuple[float, float, float, float]:
    boxes = np.array([mesh_bounds(m) for m in meshes])
    return grow((*boxes[:, :2].min(axis=0), *boxes[:, 2:].max(axis=0)), 0.05)


def stage_panel(mesh: Mesh, caption: str, dots=(), ghost: Mesh | None = None,
                bounds=None, fills=None) -> Panel:
    """``mesh`` in black over an optional grey ``ghost`` (the stage before), ``dots`` a list
    of (points, fill colour) vertex markers, ``fills`` {colour: face ids}."""
    bounds = bounds or bounds_of(*(m for m in (mesh, ghost) if m is not None))

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
        layers.append(dots_layer(fit, lw, dots))
        return layers

    return Panel(bounds, draw, caption)


def dots_layer(fit: Fit, lw: float, dots) -> Layer:
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
    bounds = bounds_of(mesh)
    return [stage_panel(mesh, "mid-edge: input", [(mesh.vertices, WHITE)], bounds=bounds),
            points_panel(mesh, "insert edge midpoints", _edge_midpoints(mesh)),
            stage_panel(h[1].mesh, "connect", [(h[1].mesh.vertices, BLUE)], ghost=mesh,
                        bounds=bounds),
            stage_panel(h[2].mesh, "second step (= Doo-Sabin)", ghost=mesh, bounds=bounds)]


def singularity_panels(mesh: Mesh) -> list[Panel]:
    """Figure SingularitiesOfSubdivision: Catmull-Clark's irregular vertices sit where the
    input has non-quads; Doo-Sabin keeps the non-quad faces."""
    bounds = bounds_of(mesh)
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
