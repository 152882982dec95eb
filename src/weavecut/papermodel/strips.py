"""Printable paper strands (paper section 5.2): modules from symmetry, one strip per strand.

The weave's rotation group C_k splits the strands into orbits. A *module* is one strand per
full orbit, chosen so that all of them head the same way (for the square grid turned by
pi / 4: north to south); the turn by j * 2 pi / k makes copy j of the module, and the k copies
hold every strand exactly once. Strands that some rotation fixes are printed once, as extras.

A *strip* is one strand cut from paper: the union of every tile it visits, its own tiles in its
colour, the tiles it passes under printed light with the ID of the strand on top there. Strips
are laid out in millimetres, long axis along x, walking towards +x; ``pages`` packs them.
"""

from __future__ import annotations

import string
from dataclasses import dataclass, replace

import numpy as np
import shapely
from numpy.typing import NDArray

from ..weave.colour import Palette, crossing_pairs, greedy_classes
from ..weave.model import Weave
from ..layout.drawing import Text
from .symmetry import Symmetry, rotate, rotation_group, strand_orbits, tile_centres
from ..layout.weave_figure import tile_rings

LIGHT = 0.22  # share of the over strand's colour in an under-crossing tile (rest white)


@dataclass(frozen=True, eq=False)
class ModulePlan:
    """Which strand is printed where.

    Parameters
    ----------
    symmetry : the weave's rotation group C_k
    copies : (k, M) strands; row j is copy j of the module (the module turned by j * 2 pi / k),
        column i is module strand i + 1
    extras : (X,) strands fixed by some rotation, printed once
    reversed : (S,) True where the printed direction runs against the weave's walking order
    labels : (S,) strand IDs: copy letter and module number ("B7"), extras "X1", "X2", ...
    """

    symmetry: Symmetry
    copies: NDArray[np.int64]
    extras: NDArray[np.int64]
    reversed: NDArray[np.bool_]
    labels: tuple[str, ...]

    @property
    def k(self) -> int:
        return self.copies.shape[0]


def copy_letter(j: int) -> str:
    letters = string.ascii_uppercase
    return letters[j] if j < 26 else letters[j // 26 - 1] + letters[j % 26]


def _angle_gap(a: NDArray, b: float) -> NDArray:
    return np.abs(np.angle(np.exp(1j * (a - b))))


def plan_modules(weave: Weave, heading: float = -np.pi / 2,
                 symmetry: Symmetry | None = None) -> ModulePlan:
    """Modules of ``weave``: one strand per full orbit, each printed heading near ``heading``.

    ``heading`` is an angle in the weave's frame; of the k turned copies of an orbit's strand
    (and, for odd k, their reverses) the one whose start-to-end direction is nearest to it
    joins the module. Module strands are numbered across that direction, left to right.
    """
    sym = rotation_group(weave) if symmetry is None else symmetry
    k = sym.order
    orbit, size = strand_orbits(sym)
    powers = sym.strand_powers()  # (k, S)
    tpowers = sym.tile_powers()  # (k, T)
    centres = tile_centres(weave)
    first = weave.strand_visits[weave.strand_offsets[:-1]]
    last = weave.strand_visits[weave.strand_offsets[1:] - 1]
    direction = centres[last] - centres[first]
    base = np.arctan2(direction[:, 1], direction[:, 0])

    seeds = np.flatnonzero((orbit == np.arange(weave.n_strands)) & (size == k))
    # candidate (copy j, flip) per orbit seed: direction base + j * angle (+ pi if flipped)
    j = np.arange(k)
    cand = base[seeds, None, None] + j[None, :, None] * sym.angle + np.array([0, np.pi])
    gap = _angle_gap(cand, heading) + 1e-9 * (j[None, :, None] + k * np.array([0, 1]))
    best = gap.reshape(len(seeds), -1).argmin(axis=1)
    jbest, flip = np.divmod(best, 2)
    reps = powers[jbest, seeds]
    # order across the heading: x in a frame where the heading points down
    mid = np.array([centres[weave.strand_visits[a:b]].mean(axis=0) for a, b in
                    zip(weave.strand_offsets[reps].tolist(), weave.strand_offsets[reps + 1].tolist())]
                   ).reshape(-1, 2)
    across = rotate(mid, -np.pi / 2 - heading, (0.0, 0.0))[:, 0] if len(reps) else np.zeros(0)
    order = np.lexsort((reps, np.round(across, 6)))
    reps, flip = reps[order], flip[order].astype(bool)
    copies = powers[:, reps] if len(reps) else np.zeros((k, 0), dtype=np.int64)

    # printed direction: the module strand's (possibly flipped) walk, turned along its orbit
    rev = np.zeros(weave.n_strands, dtype=bool)
    rep_first = first[reps]
    rep_first = np.where(flip, last[reps], rep_first)
    for jj in range(k):  # k copies, not mesh elements
        members = copies[jj]
        rev[members] = tpowers[jj, rep_first] != first[members]
    extras = np.flatnonzero(size < k)
    labels = np.empty(weave.n_strands, dtype=object)
    for jj in range(k):
        labels[copies[jj]] = [f"{copy_letter(jj)}{i + 1}" for i in range(copies.shape[1])]
    labels[extras] = [f"X{i + 1}" for i in range(len(extras))]
    return ModulePlan(sym, copies, extras, rev, tuple(labels.tolist()))


def orbit_colours(weaves: list[Weave], plan: ModulePlan, pal: Palette) -> list[str]:
    """A colour per strand, the same for every copy of a module strand (print k identical
    copies). With a palette of shade families and a coarser level, module strands that
    follow the same parent orbit share a hue and take its shades (the braided pairs)."""
    weave = weaves[-1]
    n = weave.n_strands
    # nodes: module columns, then extras
    node = np.full(n, -1, dtype=np.int64)
    m = plan.copies.shape[1]
    node[plan.copies.ravel()] = np.tile(np.arange(m), plan.k)
    node[plan.extras] = m + np.arange(len(plan.extras))
    n_nodes = m + len(plan.extras)
    pairs = node[crossing_pairs(weave)]
    pairs = np.unique(np.sort(pairs[pairs[:, 0] != pairs[:, 1]], axis=1), axis=0) \
        if len(pairs) else pairs
    if pal.shaded and len(weaves) >= 2 and weave.parent_strand is not None:
        # family: the parent strand of the node's copy-A strand (rotating a copy rotates
        # its parent too, so the choice is the same for every copy)
        rep = np.zeros(n_nodes, dtype=np.int64)
        rep[:m] = plan.copies[0]
        rep[m:] = plan.extras
        ps = weave.parent_strand[rep]
        fam_key = np.where(ps >= 0, ps, weaves[-2].n_strands + np.arange(n_nodes))
        keys, fam_node = np.unique(fam_key, return_inverse=True)
        fpairs = fam_node[pairs] if len(pairs) else pairs
        fpairs = fpairs[fpairs[:, 0] != fpairs[:, 1]] if len(fpairs) else fpairs
        fpairs = np.unique(np.sort(fpairs, axis=1), axis=0) if len(fpairs) else fpairs
        family = greedy_classes(len(keys), fpairs.reshape(-1, 2), len(pal.families))
        order = np.lexsort((np.arange(n_nodes), fam_node))
        starts = np.r_[True, fam_node[order][1:] != fam_node[order][:-1]]
        group_start = np.maximum.accumulate(np.where(starts, np.arange(n_nodes), 0))
        shade = np.empty(n_nodes, dtype=np.int64)
        shade[order] = np.arange(n_nodes) - group_start
        fams = [pal.families[f % len(pal.families)] for f in family[fam_node].tolist()]
        node_colour = [f[s % len(f)] for f, s in zip(fams, shade.tolist())]
    else:
        flat = pal.flat
        cls = greedy_classes(n_nodes, pairs.reshape(-1, 2), len(flat))
        node_colour = [flat[c] for c in cls.tolist()]
    return [node_colour[i] for i in node.tolist()]


def copy_colours(plan: ModulePlan, pal: Palette) -> list[str]:
    """A colour per strand: one colour per module copy (the paper's 4-colour scheme)."""
    flat = pal.flat
    out = [flat[-1]] * len(plan.labels)
    for j in range(plan.k):
        for s in plan.copies[j].tolist():
            out[s] = flat[j % len(flat)]
    return out


def tint(colour: str, share: float = LIGHT) -> str:
    """``colour`` mixed with white; ``share`` of the colour is kept."""
    rgb = np.array([int(colour[i:i + 2], 16) for i in (1, 3, 5)], dtype=float)
    mixed = np.round(255 - share * (255 - rgb)).astype(int)
    return "#{:02x}{:02x}{:02x}".format(*mixed.tolist())


def ink_for(colour: str) -> str:
    """Black or white text, whichever reads better on ``colour``."""
    r, g, b = (int(colour[i:i + 2], 16) / 255 for i in (1, 3, 5))
    return "#000000" if 0.299 * r + 0.587 * g + 0.114 * b > 0.55 else "#ffffff"


@dataclass(frozen=True, eq=False)
class Strip:
    """One strand as a piece of paper, in mm, long axis along x, walking towards +x.

    Parameters
    ----------
    strand : the strand
    label : its ID
    outline : shapely Polygon, the cut line (union of every tile it visits)
    tiles : (n,) shapely Polygons, the visited tiles in walking order
    fills : (n,) fill per tile (own: strand colour, under: light)
    texts : IDs on the strip (strand ID, and the strand on top over every under tile)
    arrows : (a,) shapely Polygons, direction arrows, filled with ``arrow_ink``
    glue : shapely Polygons where a piece of a split strip overlaps the next, or None
    """

    strand: int
    label: str
    outline: shapely.Polygon
    tiles: NDArray[np.object_]
    fills: tuple[str, ...]
    texts: tuple[Text, ...]
    arrows: NDArray[np.object_]
    arrow_ink: str = "#000000"
    glue: NDArray[np.object_] | None = None

    @property
    def length(self) -> float:
        x0, _, x1, _ = self.outline.bounds
        return x1 - x0

    @property
    def width(self) -> float:
        _, y0, _, y1 = self.outline.bounds
        return y1 - y0


def model_tiles(weave: Weave) -> NDArray[np.object_]:
    """(T,) every tile as a shapely Polygon in model units."""
    coords, offsets = tile_rings(weave)
    ring_id = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
    return shapely.polygons(shapely.linearrings(coords, indices=ring_id))


def octagon_size(weave: Weave) -> float:
    """Median distance across an octagon (farthest corners), model units."""
    coords, offsets = tile_rings(weave)
    sizes = np.diff(offsets)
    octs = coords[np.repeat(sizes == 8, sizes)].reshape(-1, 8, 2)
    if len(octs) == 0:
        octs = coords[np.repeat(sizes == 5, sizes)].reshape(-1, 5, 2)
    d = np.linalg.norm(octs[:, :, None, :] - octs[:, None, :, :], axis=-1).max(axis=(1, 2))
    return float(np.median(d))


def arrow_polygon(tip, direction, length: float) -> shapely.Polygon:
    """A filled arrow of ``length`` mm ending at ``tip``, pointing along ``direction``."""
    d = np.asarray(direction, dtype=float)
    d = d / max(np.hypot(*d), 1e-12)
    n = np.array([-d[1], d[0]])
    t = np.asarray(tip, dtype=float)
    w, head = 0.12 * length, 0.4 * length
    pts = [t, t - head * d + 0.3 * length * n, t - head * d + w * n, t - length * d + w * n,
           t - length * d - w * n, t - head * d - w * n, t - head * d - 0.3 * length * n]
    return shapely.Polygon(pts)


def build_strips(weave: Weave, plan: ModulePlan, colours: list[str], scale: float,
                 strands, copy: int = 0) -> list[Strip]:
    """A Strip for every strand in ``strands``, ``scale`` mm per model unit.

    With ``copy`` j > 0 the strips keep the shape of ``strands`` but are coloured and labelled
    as their images under the turn by j * 2 pi / k (so every copy has the same layout).
    """
    tiles = model_tiles(weave)
    centres = tile_centres(weave)
    tile_mm = octagon_size(weave) * scale
    image = plan.symmetry.strand_powers()[copy]
    labels = [plan.labels[t] for t in image.tolist()]
    cols = [colours[t] for t in image.tolist()]
    out = []
    for s in np.asarray(strands).tolist():  # strands, not mesh elements
        visits, over = weave.strand(s)
        if plan.reversed[s]:
            visits, over = visits[::-1], over[::-1]
        strip = _strip(weave, s, visits, over, tiles, centres, labels, cols, scale, tile_mm)
        out.append(replace(strip, strand=int(image[s])))
    return out


def _strip(weave, s, visits, over, tiles, centres, labels, colours, scale, tile_mm) -> Strip:
    shapes = shapely.transform(tiles[visits], lambda xy: xy * scale)
    pts = centres[visits] * scale
    outline = shapely.union_all(shapes)
    if outline.geom_type != "Polygon":  # tiles touching at a corner: keep one piece
        outline = shapely.union_all(shapely.buffer(shapes, 1e-6 * tile_mm, join_style="mitre"))
    # orient: long side of the minimum-area rectangle along x, walking towards +x
    rect = np.asarray(shapely.minimum_rotated_rectangle(outline).exterior.coords)[:4]
    edges = np.diff(np.vstack([rect, rect[:1]]), axis=0)
    long = edges[np.argmax(np.hypot(edges[:, 0], edges[:, 1]))]
    theta = -np.arctan2(long[1], long[0])
    travel = rotate((pts[-1] - pts[0])[None], theta, (0.0, 0.0))[0]
    if len(pts) > 1 and travel[0] < 0:
        theta += np.pi
    c, sn = np.cos(theta), np.sin(theta)
    rot = np.array([[c, sn], [-sn, c]])  # row-vector form of the turn by theta

    def move(xy):
        return xy @ rot

    outline = shapely.transform(outline, move)
    x0, y0 = outline.bounds[:2]

    def place(xy):
        return move(xy) - (x0, y0)

    outline = shapely.transform(shapely.Polygon(outline.exterior), lambda xy: xy - (x0, y0))
    shapes = shapely.transform(shapes, place)
    pts = place(pts)
    own_colour = colours[s]
    over_strand = weave.tile_over[visits]
    fills = tuple(own_colour if o else tint(colours[t]) for o, t in
                  zip(over.tolist(), over_strand.tolist()))
    size = float(np.clip(0.16 * tile_mm, 1.6, 3.2))
    texts, arrows = [], []
    for i in np.flatnonzero(~over).tolist():
        texts.append(Text(pts[i][0], pts[i][1] - size / 2, labels[int(over_strand[i])], size,
                          "middle", 0.0, "#333333"))
    own = np.flatnonzero(over)
    ink = ink_for(own_colour)
    big = float(np.clip(0.2 * tile_mm, 2.0, 4.0))
    for i in (own[[0, -1]] if len(own) > 1 else own[:1]).tolist():
        j = i + 1 if i + 1 < len(pts) else i - 1
        d = (pts[j] - pts[i]) * (1 if j > i else -1) if j >= 0 else np.array([1.0, 0.0])
        d = d / max(np.hypot(*d), 1e-12)
        p = pts[i]
        texts.append(Text(p[0], p[1] + 0.04 * tile_mm, labels[s], big, "middle", 0.0, ink))
        centre = p - (0.0, 0.2 * tile_mm)
        arrows.append(arrow_polygon(centre + d * 0.14 * tile_mm, d, 0.28 * tile_mm))
    return Strip(int(s), labels[s], outline, shapes, fills, tuple(texts),
                 np.array(arrows, dtype=object), ink)
