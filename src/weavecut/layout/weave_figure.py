"""A snub weave as a Drawing: tiles filled by strand colour, octagon outlines, and optionally a
coarser level's octagons, the Z middle edges and the strands' over/under crossings."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..weave.model import Weave
from .drawing import Drawing, Fit, Layer, Polygons, Polylines, Sheet, Style
from .mesh_figure import line_width


def tile_rings(weave: Weave) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Outline of every tile of a snub weave: the octagon of two pentagons glued along their
    middle edge, or the lone boundary pentagon. Returns (coords, ring offsets) in model units."""
    mesh = weave.mesh
    faces = mesh.dense_faces()
    sizes = np.diff(weave.tile_offsets)
    first = weave.tile_faces[weave.tile_offsets[:-1]]
    second = weave.tile_faces[np.minimum(weave.tile_offsets[:-1] + 1, len(weave.tile_faces) - 1)]
    p, q = faces[first], faces[second]
    # p = (p0 .. p4) with middle edge p1 -> p2; q runs it the other way: q1 = p2, q2 = p1
    octagon = np.column_stack([p[:, 2], p[:, 3], p[:, 4], p[:, 0], p[:, 1],
                               q[:, 3], q[:, 4], q[:, 0]])
    lone = sizes == 1
    counts = np.where(lone, 5, 8)
    offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    take = np.ones((len(first), 8), dtype=bool)
    take[lone, 5:] = False
    ids = octagon[take]
    return np.take(mesh.vertices, ids, axis=0), offsets


def middle_edge_lines(mesh: Mesh) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The Z middle edges of a snub level (local edge 1 of every pentagon), each once."""
    topo = mesh.topology
    middle = np.unique(topo.half_edge_edge[5 * np.arange(mesh.n_faces) + 1])
    seg = topo.edges[middle].ravel()
    return np.take(mesh.vertices, seg, axis=0), np.arange(0, len(seg) + 1, 2, dtype=np.int64)


def crossing_lines(weave: Weave, centres: NDArray[np.float64], gap: float = 0.3):
    """Strand centre-lines through their own tiles, broken where they pass under a tile.

    Returns (coords, offsets, strand of every line)."""
    mesh = weave.mesh
    faces = mesh.dense_faces()
    ends = np.column_stack([faces[weave.tile_faces[weave.tile_offsets[:-1]], 1],
                            faces[weave.tile_faces[weave.tile_offsets[:-1]], 2]])
    mid = mesh.vertices[ends].mean(axis=1)  # where a strand passes under the tile
    over = weave.visit_over
    point = np.where(over[:, None], centres[weave.strand_visits], mid[weave.strand_visits])
    strand = weave.visit_strand
    same = np.r_[strand[1:] == strand[:-1], False]
    # one segment per consecutive pair of visits, cut short on the under side
    a, b = point[:-1][same[:-1]], point[1:][same[:-1]]
    a_over = over[:-1][same[:-1]]
    seg_strand = strand[:-1][same[:-1]]
    start = np.where(a_over[:, None], a, a + gap * (b - a))
    end = np.where(a_over[:, None], b - gap * (b - a), b)
    coords = np.stack([start, end], axis=1).reshape(-1, 2)
    return coords, np.arange(0, len(coords) + 1, 2, dtype=np.int64), seg_strand


def weave_drawing(weaves: list[Weave], colours: list[str], size: float, margin: float = 10.0,
                  outline: Weave | None = None, middle_edges: bool = False,
                  crossings: bool = False, title: str = "weave-cut weave") -> Drawing:
    """One sheet with the last weave's tiles coloured by strand (``colours`` per strand)."""
    weave = weaves[-1]
    mesh = weave.mesh
    v = mesh.vertices
    x0, y0 = v.min(axis=0)
    x1, y1 = v.max(axis=0)
    scale = size / max(x1 - x0, y1 - y0)
    width, height = (x1 - x0) * scale + 2 * margin, (y1 - y0) * scale + 2 * margin
    fit = Fit.into((x0, y0, x1, y1), width, height, margin)
    lw = line_width(mesh, fit)
    coords, offsets = tile_rings(weave)
    fills = tuple(colours[s] if s >= 0 else "#ffffff" for s in weave.tile_over.tolist())
    layers = [Layer("tiles", "paint", (Polygons(fit(coords), offsets, Style("#333333", lw * 0.6),
                                                None, fills),))]
    if outline is not None:
        oc, oo = tile_rings(outline)
        layers.append(Layer("outline", "guide",
                            (Polygons(fit(oc), oo, Style("#000000", 2.5 * lw)),)))
    if middle_edges:
        mc, mo = middle_edge_lines(mesh)
        layers.append(Layer("middle-edges", "guide",
                            (Polylines(fit(mc), mo, Style("#d62728", 1.5 * lw)),)))
    if crossings:
        counts = np.diff(offsets)[:, None]
        centres = np.add.reduceat(coords, offsets[:-1], axis=0) / counts
        lc, lo, ls = crossing_lines(weave, centres)
        shapes = [Polylines(fit(lc), lo, Style("#ffffff", 3.5 * lw))]
        seg_colour = np.array(colours, dtype=object)[ls]
        for colour in sorted(set(colours)):  # one batch per colour
            pick = np.flatnonzero(seg_colour == colour)
            seg = np.stack([lc[2 * pick], lc[2 * pick + 1]], axis=1).reshape(-1, 2)
            shapes.append(Polylines(fit(seg), np.arange(0, len(seg) + 1, 2, dtype=np.int64),
                                    Style(_darker(colour), 1.5 * lw)))
        layers.append(Layer("crossings", "guide", tuple(shapes)))
    return Drawing((Sheet(width, height, tuple(layers)),), title)


def _darker(colour: str, factor: float = 0.6) -> str:
    r, g, b = (int(colour[i:i + 2], 16) for i in (1, 3, 5))
    return "#{:02x}{:02x}{:02x}".format(*(int(c * factor) for c in (r, g, b)))
