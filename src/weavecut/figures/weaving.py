"""The paper's weaving figures (section 5) and its scheme figures (sections 2 and 5.3).

``FIGURES`` has the same shape as ``figures.subdivision.FIGURES``; ``figures.gallery`` joins them.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import inputs
from ..mesh import Mesh
from ..puzzle.colouring import colour_puzzle
from ..puzzle.pieces import build_puzzle
from ..subdivision import subdivide
from ..weave.colour import palette, strand_colours
from ..weave.schemes import scheme_weaves
from ..weave.snub_weave import snub_weaves
from ..layout.drawing import Drawing, Layer, Polylines, Style, mesh_bounds, mesh_polygons
from .panels import Panel, compose, mesh_panel
from ..layout.mesh_figure import line_width
from ..layout.weave_figure import middle_edge_lines, snub_under_points, tile_outline_lines, weave_layers

HIGHLIGHT = "#0f7173"


def _weave_panel(weave, colours, caption, **options) -> Panel:
    return Panel(mesh_bounds(weave.mesh), lambda fit: weave_layers(weave, colours, fit,
                                                                   **options), caption)


def _grid_panel(level_mesh: Mesh, grid: Mesh, caption: str, middle: bool = False,
                tiles=None) -> Panel:
    """The level-1 mesh over the grid; optionally its middle edges or its glued tiles."""
    def draw(fit):
        lw = line_width(level_mesh, fit)
        layers = [Layer("grid", "guide", (mesh_polygons(grid, fit, Style("#7fa7d9", 2 * lw,
                                                                          "#eef3fa")),)),
                  Layer("mesh", "guide", (mesh_polygons(level_mesh, fit, Style("#000000",
                                                                               lw)),))]
        if middle:
            mc, mo = middle_edge_lines(level_mesh)
            layers.append(Layer("middle-edges", "guide",
                                (Polylines(fit(mc), mo, Style("#d62728", 2.5 * lw)),)))
        if tiles is not None:
            oc, oo = tile_outline_lines(tiles)
            layers = [layers[0], Layer("tiles", "guide", (
                Polylines(fit(oc), oo, Style("#000000", 1.5 * lw)),))]
        return layers
    return Panel(mesh_bounds(level_mesh), draw, caption)


def fig_square_grid_weaving() -> Drawing:
    """Figure SquareGridWeaving (a)-(f) on a 4 x 4 grid."""
    grid = inputs.get("square-grid:4x4")
    hierarchy = subdivide(grid, 3)
    weaves = snub_weaves(hierarchy)
    one = weaves[0]
    # (d): one long strand in colour, the others white
    lengths = np.bincount(one.visit_strand[one.visit_over], minlength=one.n_strands)
    chosen = int(np.argmax(lengths))
    single = ["" if s != chosen else HIGHLIGHT for s in range(one.n_strands)]
    pal = palette("maritime-12")
    # (e), (f): the chosen strand's descendants in its shades, everything else light grey
    two, three = weaves[1], weaves[2]
    kids = two.parent_strand == chosen
    grand = kids[np.maximum(three.parent_strand, 0)] & (three.parent_strand >= 0)
    c2 = strand_colours(weaves[:2], pal)
    c3 = strand_colours(weaves, pal)
    shade2 = [c if k else "#e9e9e9" for c, k in zip(c2, kids.tolist())]
    shade3 = [c if k else "#e9e9e9" for c, k in zip(c3, grand.tolist())]
    panels = [
        _grid_panel(hierarchy[1].mesh, grid, "1st refinement of a square grid"),
        _grid_panel(hierarchy[1].mesh, grid, "middle edges of the Z-triplets",
                    middle=True),
        _grid_panel(hierarchy[1].mesh, grid, "pentagons glued along middle edges",
                    tiles=one),
        _weave_panel(one, single, "a strand, through the middle edges"),
        _weave_panel(two, shade2, "2nd: it splits into two twisted strands",
                     outline=one),
        _weave_panel(three, shade3, "3rd: a twisted pair of twisted strands",
                     outline=two),
    ]
    return compose(panels, columns=2, cell=85.0, title="square-grid weaving")


def fig_pentagon_weave() -> Drawing:
    """The pentagon's weave at level 3 and at level 4 over its level-3 octagons, in the jigsaw
    puzzle's paints: its front (level 3) and back (level 4) assignment."""
    puzzle = build_puzzle(subdivide(inputs.get("pentagon"), 4))
    colouring = colour_puzzle(puzzle, palette("puzzle"))
    weaves = puzzle.weaves
    panels = [_weave_panel(weaves[2], list(colouring.front_strands),
                           "level 3 weave: the puzzle's front"),
              _weave_panel(weaves[3], list(colouring.back_strands),
                           "level 4 over the level-3 octagons: the back", outline=weaves[2],
                           under_points=snub_under_points(weaves[3]))]
    return compose(panels, columns=2, cell=110.0, title="pentagon weave")


SCHEME_INPUTS = (("loop", "triangle-grid:3x2"), ("butterfly", "triangle-grid:3x2"),
                 ("sqrt3", "triangle-grid:3x2"), ("midedge", "square-grid:3x2"),
                 ("doo-sabin", "hex-grid:2x2"), ("catmull-clark", "hex-grid:2x2"),
                 ("dual", "triangle-grid:3x2"), ("akleman", "pentagon-flower"))


def fig_schemes() -> Drawing:
    """Every classic scheme, one or two steps, over its input (paper section 2)."""
    panels = []
    for scheme, name in SCHEME_INPUTS:
        mesh = inputs.get(name)
        steps = 2 if scheme in ("midedge", "sqrt3") else 1
        level = subdivide(mesh, steps, scheme)[-1].mesh
        panels.append(mesh_panel(level, f"{scheme} x{steps} on {name}", underlay=mesh))
    return compose(panels, columns=4, cell=55.0, title="subdivision schemes")


def fig_scheme_weaves() -> Drawing:
    """The weaves of section 5.3 as knotwork ribbons: Catmull-Clark, Loop, sqrt3, face-split."""
    cases = (("catmull-clark", "square-grid:3x3", 2, False),
             ("loop", "triangle-grid:3x3", 1, False),
             ("sqrt3", "triangle-grid:3x3", 2, False),
             ("dual", "hex-grid:3x3", 0, True))
    pal = palette("okabe-ito")
    panels = []
    for scheme, name, levels, face_split in cases:
        weaves = scheme_weaves(subdivide(inputs.get(name), levels, scheme), scheme, face_split)
        label = "face-split weave" if face_split else f"{scheme} level {levels}"
        panels.append(_weave_panel(weaves[-1], strand_colours(weaves[-1:], pal),
                                   label, ribbons=True))
    return compose(panels, columns=4, cell=60.0, title="weaves of other schemes")


FIGURES: dict[str, tuple[str, Callable[[], Drawing | bytes]]] = {
    "square-grid-weaving": ("square grid weaving (a)-(f): mesh, middle edges, octagons, a "
                            "strand, its split into two and four", fig_square_grid_weaving),
    "pentagon-weave": ("the pentagon's weave at levels 3 and 4 in the puzzle's front and back "
                       "paints",
                       fig_pentagon_weave),
    "schemes": ("Loop, butterfly, sqrt3, mid-edge, Doo-Sabin, Catmull-Clark, dual, Akleman on "
                "the paper's kinds of input", fig_schemes),
    "scheme-weaves": ("weaves of Catmull-Clark, Loop, sqrt3 and the face-split weave as "
                      "ribbons", fig_scheme_weaves),
}
