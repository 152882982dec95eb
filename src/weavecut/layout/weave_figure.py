"""A snub weave as a Drawing: tiles filled by strand colour, octagon outlines, and optionally a
coarser level's octagons, the Z middle edges and the strands' over/under crossings."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..weave.model import Weave, tile_ring_ids
from ..numeric import distinct, median
from .drawing import Drawing, Fit, Layer, Polylines, Sheet, Style, mesh_polygons
from .mesh_figure import line_width


def tile_rings(weave: Weave) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Outline of every tile of a snub weave: the octagon of two pentagons glued along their
    middle edge, or the lone boundary pentagon. Returns (coords, ring offsets) in model units."""
    ids, offsets = tile_ring_ids(weave)
    return np.take(weave.mesh.vertices, ids, axis=0), offsets


def middle_edge_lines(mesh: Mesh) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The Z middle edges of a snub level (local edge 1 of every pentagon), each once."""
    topo = mesh.topology
    middle = distinct(topo.half_edge_edge[5 * np.arange(mesh.n_faces) + 1])
    seg = topo.edges[middle].ravel()
    return np.take(mesh.vertices, seg, axis=0), np.arange(0, len(seg) + 1, 2, dtype=np.int64)


def snub_under_points(weave: Weave) -> NDArray[np.float64]:
    """(T, 2) where a strand passes under each snub tile: the middle of its middle edge."""
    faces = weave.mesh.dense_faces()
    first = weave.tile_faces[weave.tile_offsets[:-1]]
    return weave.mesh.vertices[faces[first][:, 1:3]].mean(axis=1)


def tile_centres(weave: Weave) -> NDArray[np.float64]:
    """(T, 2) mean of the face centroids of every tile."""
    mesh = weave.mesh
    sums = np.add.reduceat(np.take(mesh.vertices, mesh.face_indices, axis=0),
                           mesh.face_offsets[:-1], axis=0)
    centroids = sums / mesh.face_sizes[:, None]
    per_face = centroids[weave.tile_faces]
    return np.add.reduceat(per_face, weave.tile_offsets[:-1], axis=0) / np.diff(
        weave.tile_offsets)[:, None]


def tile_outline_lines(weave: Weave) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Segments of the edges between different tiles and on the boundary, each once."""
    mesh = weave.mesh
    u = mesh.face_indices.astype(np.int64)
    w = u[mesh.next_half_edge]
    key = np.minimum(u, w) * max(mesh.n_vertices, 1) + np.maximum(u, w)
    order = np.argsort(key, kind="stable")
    k = key[order]
    paired = np.r_[k[1:] == k[:-1], False]
    twin = np.full(len(u), -1, dtype=np.int64)
    a, b = order[paired], order[np.r_[False, paired[:-1]]]
    twin[a], twin[b] = b, a
    tile = weave.face_tile[mesh.half_edge_face]
    h = np.arange(len(u))
    show = (twin < 0) | ((h < twin) & (tile != tile[np.maximum(twin, 0)]))
    seg = np.column_stack([u[show], w[show]]).ravel()
    return np.take(mesh.vertices, seg, axis=0), np.arange(0, len(seg) + 1, 2, dtype=np.int64)


def crossing_lines(weave: Weave, over_points: NDArray, under_points: NDArray,
                   gap: float = 0.3):
    """Strand centre-lines through their tiles, broken where they pass under a tile.

    Returns (coords, offsets, strand of every segment)."""
    over = weave.visit_over
    point = np.where(over[:, None], over_points[weave.strand_visits],
                     under_points[weave.strand_visits])
    strand = weave.visit_strand
    nxt = np.r_[np.arange(1, len(strand)), 0]
    # closed strands also join their last visit to the first
    last = np.r_[strand[1:] != strand[:-1], True]
    first_of = np.flatnonzero(np.r_[True, strand[1:] != strand[:-1]])
    nxt[last] = first_of
    use = ~last | weave.strand_closed[strand]
    a, b = point[use], point[nxt[use]]
    a_over, b_over = over[use], over[nxt[use]]
    start = np.where(a_over[:, None], a, a + gap * (b - a))
    end = np.where(b_over[:, None], b, b - gap * (b - a))
    coords = np.stack([start, end], axis=1).reshape(-1, 2)
    return coords, np.arange(0, len(coords) + 1, 2, dtype=np.int64), strand[use]


def weave_drawing(weaves: list[Weave], colours: list[str], size: float, margin: float = 10.0,
                  title: str = "weave-cut weave", **options) -> Drawing:
    """One sheet, ``size`` mm on its longer side plus margins, with ``weave_layers``."""
    v = weaves[-1].mesh.vertices
    x0, y0 = v.min(axis=0)
    x1, y1 = v.max(axis=0)
    scale = size / max(x1 - x0, y1 - y0)
    width, height = (x1 - x0) * scale + 2 * margin, (y1 - y0) * scale + 2 * margin
    fit = Fit.into((x0, y0, x1, y1), width, height, margin)
    layers = weave_layers(weaves[-1], colours, fit, **options)
    return Drawing((Sheet(width, height, tuple(layers)),), title)


def weave_layers(weave: Weave, colours: list[str], fit: Fit, outline: Weave | None = None,
                 middle_edges: bool = False, crossings: bool = False, ribbons: bool = False,
                 under_points: NDArray | None = None) -> list[Layer]:
    """The weave's tiles coloured by the strand on top (``colours`` per strand, "" for white);
    ``ribbons`` draws the strands as ribbons with gaps where they pass under instead;
    ``crossings`` thin centre-lines over the tiles; ``outline`` a coarser weave's tiles;
    ``middle_edges`` the Z middle edges (snub weaves)."""
    mesh = weave.mesh
    lw = line_width(mesh, fit)
    centres = tile_centres(weave)
    unders = centres if under_points is None else under_points
    colour_of = np.array([c or "#ffffff" for c in colours] + ["#ffffff"], dtype=object)
    layers = []
    if ribbons:
        band = 0.3 * float(median(np.hypot(*np.diff(
            centres[weave.strand_visits], axis=0).T))) * fit.scale
        lc, lo, ls = crossing_lines(weave, centres, unders, gap=0.2)
        layers.append(Layer("faces", "guide", (mesh_polygons(mesh, fit, Style("#dddddd", lw)),)))
        layers.append(Layer("ribbons", "paint", _by_colour(fit(lc), ls, colour_of, band, lw)))
    else:
        fills = tuple(colour_of[weave.tile_over[weave.face_tile]].tolist())
        layers.append(Layer("tiles", "paint", (mesh_polygons(mesh, fit, Style(None), fills),)))
        oc, oo = tile_outline_lines(weave)
        layers.append(Layer("tile-outlines", "guide",
                            (Polylines(fit(oc), oo, Style("#333333", lw * 0.6)),)))
    if outline is not None:
        oc, oo = tile_outline_lines(outline)
        layers.append(Layer("outline", "guide", (Polylines(fit(oc), oo,
                                                           Style("#000000", 2.5 * lw)),)))
    if middle_edges:
        mc, mo = middle_edge_lines(mesh)
        layers.append(Layer("middle-edges", "guide",
                            (Polylines(fit(mc), mo, Style("#d62728", 1.5 * lw)),)))
    if crossings and not ribbons:
        lc, lo, ls = crossing_lines(weave, centres, unders)
        layers.append(Layer("crossings", "guide", _by_colour(fit(lc), ls, colour_of,
                                                             1.5 * lw, lw, darken=True)))
    return layers


def _by_colour(coords, strand, colour_of, width: float, casing: float, darken: bool = False):
    """Segments (pairs of rows of ``coords``) as one white casing plus a batch per colour."""
    seg = np.arange(0, len(coords) + 1, 2, dtype=np.int64)
    shapes = [Polylines(coords, seg, Style("#ffffff", width + 2 * casing))]
    seg_colour = colour_of[strand]
    for colour in sorted(set(seg_colour.tolist())):
        pick = np.flatnonzero(seg_colour == colour)
        pts = np.stack([coords[2 * pick], coords[2 * pick + 1]], axis=1).reshape(-1, 2)
        stroke = _darker(colour) if darken else colour
        shapes.append(Polylines(pts, np.arange(0, len(pts) + 1, 2, dtype=np.int64),
                                Style(stroke, width)))
    return tuple(shapes)


def _darker(colour: str, factor: float = 0.6) -> str:
    r, g, b = (int(colour[i:i + 2], 16) for i in (1, 3, 5))
    return "#{:02x}{:02x}{:02x}".format(*(int(c * factor) for c in (r, g, b)))
