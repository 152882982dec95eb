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
from dataclasses import dataclass, field, replace

import numpy as np
import shapely
from numpy.typing import NDArray

from ..numeric import affine, affine_matrix, dot, matmul, snap, transform
from ..weave.colour import Palette, crossing_pairs, greedy_classes
from ..weave.model import Weave
from ..layout.contrast import text_colour_on
from ..layout.drawing import Text
from ..layout.labels import (
    MIN_CAP,
    centred_text,
    inner_centres,
    largest_fit,
    text_box,
    unit_box,
    upright,
)
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
    # the turn may carry a strand onto its image walking the other way: flip the image so that
    # it heads where the chosen candidate does
    want = base[seeds] + jbest * sym.angle + np.pi * flip
    flip = _angle_gap(base[reps], want) > np.pi / 2
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


def copy_family_colours(weave: Weave, plan: ModulePlan, pal: Palette) -> list[str]:
    """A colour per strand that tells the copies apart: with three or more copies, copy j takes
    shade family j and its module strands the family's shades in turn (neighbours differ);
    extras the next family. With fewer copies the copies are not what the eye must separate,
    so crossing strands simply differ (greedy colouring over the flat palette)."""
    fams = pal.families
    if plan.k < 3:
        cls = greedy_classes(weave.n_strands, crossing_pairs(weave), len(pal.flat))
        return [pal.flat[c] for c in cls.tolist()]
    out = [""] * len(plan.labels)
    for j, row in enumerate(plan.copies.tolist()):  # copies
        fam = fams[j % len(fams)]
        for i, s in enumerate(row):
            out[s] = fam[i % len(fam)]
    fam = fams[plan.k % len(fams)]
    for i, s in enumerate(plan.extras.tolist()):
        out[s] = fam[i % len(fam)]
    return out


def tint(colour: str, share: float = LIGHT) -> str:
    """``colour`` mixed with white; ``share`` of the colour is kept."""
    rgb = np.array([int(colour[i:i + 2], 16) for i in (1, 3, 5)], dtype=float)
    mixed = np.round(255 - share * (255 - rgb)).astype(int)
    return "#{:02x}{:02x}{:02x}".format(*mixed.tolist())


@dataclass(frozen=True, eq=False)
class Strip:
    """One strand (or a piece of it) as paper, in mm, long axis along x, walking towards +x.

    Parameters
    ----------
    strand : the strand
    label : its ID (a piece of a split strip: "A7 1/2")
    outline : shapely Polygon, the cut line (union of every tile it visits)
    tiles : (n,) shapely Polygons, the visited tiles in walking order
    fills : (n,) fill per tile (own: strand colour, under: light)
    over : (n,) True where the strand is on top (its own tiles)
    names : (n,) per tile, the ID of the strand on top there
    frame : (3, 3) the affine map from the weave's model units to this strip's mm
    texts : labels (filled in by :func:`label_strip`)
    arrows : (a,) shapely Polygons, direction arrows, filled with ``arrow_ink``
    glue : shapely Polygons where a piece of a split strip overlaps the next, or None
    plates : label backgrounds in the fill of an under tile too small for its label, drawn
        over the neighbouring tiles; ``plate_fills`` their fills
    folds : fold lines (shapely lines, drawn dashed) of a strip unfolded from a surface;
        ``fold_inks`` their colours (dark on light tiles, light on dark ones)
    tab : the text on the glue band ("glue", or "glue 2" where numbered tabs pair up)
    mark : text for the first tile, where the glue band of the piece before goes ("2"), or ""
    flap : a label tab holding the ID where no own tile can (cut with the strip, cut off after
        weaving), or None; ``flap_edge`` the line where it meets its tile (drawn dashed),
        ``flap_fill`` its fill
    left_out : under tiles whose name fits neither the tile nor a plate over its neighbours
        (the assembly sheet shows those crossings)
    """

    strand: int
    label: str
    outline: shapely.Polygon
    tiles: NDArray[np.object_]
    fills: tuple[str, ...]
    over: NDArray[np.bool_]
    names: tuple[str, ...]
    frame: NDArray[np.float64]
    texts: tuple[Text, ...] = ()
    arrows: NDArray[np.object_] = field(default_factory=lambda: np.zeros(0, dtype=object))
    arrow_ink: str = "#000000"
    glue: NDArray[np.object_] | None = None
    plates: NDArray[np.object_] = field(default_factory=lambda: np.zeros(0, dtype=object))
    plate_fills: tuple[str, ...] = ()
    folds: NDArray[np.object_] = field(default_factory=lambda: np.zeros(0, dtype=object))
    fold_inks: tuple[str, ...] = ()
    tab: str = "glue"
    mark: str = ""
    flap: shapely.Polygon | None = None
    flap_edge: shapely.LineString | None = None
    flap_fill: str = "#ffffff"
    left_out: tuple[int, ...] = ()

    @property
    def cut(self) -> shapely.Polygon:
        """The cut line: the outline and the label tab, if any."""
        if self.flap is None:
            return self.outline
        # the tab grown by a hair: its base, collinear with its tile's edge only up to rounding,
        # would leave a slit in the union that a cutter follows into the strip; the hair's
        # steps are simplified away
        eps = 1e-6 * max(self.length, 1.0)
        grown = shapely.buffer(self.flap, eps, join_style="mitre")
        return shapely.simplify(outline_of(np.array([self.outline, grown]), eps), 10 * eps)

    @property
    def length(self) -> float:
        x0, _, x1, _ = self.outline.bounds
        return x1 - x0

    @property
    def width(self) -> float:
        _, y0, _, y1 = self.outline.bounds
        return y1 - y0

    def moved(self, matrix: NDArray[np.float64], angle: float = 0.0) -> Strip:
        """The strip through the affine ``matrix`` (3, 3), a turn by ``angle`` degrees plus a
        shift; its texts turn with it and are then set upright."""
        f = transform(matrix)
        texts = []
        for t in self.texts:
            x, y = f(np.array([[t.x, t.y]]))[0]
            texts.append(upright(replace(t, x=float(x), y=float(y), angle=t.angle + angle)))
        return replace(self, outline=shapely.transform(self.outline, f),
                       tiles=shapely.transform(self.tiles, f),
                       arrows=shapely.transform(self.arrows, f),
                       glue=None if self.glue is None else shapely.transform(self.glue, f),
                       plates=shapely.transform(self.plates, f),
                       folds=shapely.transform(self.folds, f),
                       flap=None if self.flap is None else shapely.transform(self.flap, f),
                       flap_edge=None if self.flap_edge is None
                       else shapely.transform(self.flap_edge, f),
                       texts=tuple(texts), frame=matmul(matrix, self.frame))


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


def strip_width(weave: Weave) -> float:
    """Median width of the strips, model units: the short side of the smallest rectangle round
    each octagon (a strip is as wide as the octagons it is made of)."""
    coords, offsets = tile_rings(weave)
    sizes = np.diff(offsets)
    keep = sizes == 8 if (sizes == 8).any() else sizes == sizes.max()
    ring_id = np.repeat(np.arange(len(sizes)), sizes)
    polys = shapely.polygons(shapely.linearrings(coords, indices=ring_id))[keep]
    rects = shapely.get_coordinates(shapely.get_exterior_ring(
        shapely.minimum_rotated_rectangle(polys))).reshape(len(polys), -1, 2)
    sides = np.hypot(*(rects[:, 1:3] - rects[:, 0:2]).transpose(2, 0, 1))
    return float(np.median(sides.min(axis=1)))


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
                 strands, copy: int = 0, labels: tuple[str, ...] | None = None) -> list[Strip]:
    """An unlabelled Strip for every strand in ``strands``, ``scale`` mm per model unit.

    With ``copy`` j > 0 the strips keep the shape of ``strands`` but are coloured and labelled
    as their images under the turn by j * 2 pi / k (so every copy has the same layout).
    ``labels`` replaces the plan's strand IDs (the paper's module prints: no copy letter).
    """
    tiles = model_tiles(weave)
    centres = tile_centres(weave)
    tile_mm = octagon_size(weave) * scale
    image = plan.symmetry.strand_powers()[copy]
    names = plan.labels if labels is None else labels
    names = [names[t] for t in image.tolist()]
    cols = [colours[t] for t in image.tolist()]
    c = plan.symmetry.centre
    back = matmul(matmul(affine(0.0, c), affine(-np.degrees(copy * plan.symmetry.angle))),
                  affine(0.0, -c))
    out = []
    for s in np.asarray(strands).tolist():  # strands, not mesh elements
        visits, over = weave.strand(s)
        if plan.reversed[s]:
            visits, over = visits[::-1], over[::-1]
        strip = _strip(weave, s, visits, over, tiles, centres, names, cols, scale, tile_mm)
        out.append(replace(strip, strand=int(image[s]), frame=matmul(strip.frame, back)))
    return out


def outline_of(shapes, eps: float) -> shapely.Polygon:
    """The cut line round ``shapes`` (tiles of one strip): their union without holes; tiles
    that only touch at a corner are joined by growing them ``eps``."""
    outline = shapely.union_all(shapes)
    if outline.geom_type != "Polygon":  # tiles touching at a corner: keep one piece
        outline = shapely.union_all(shapely.buffer(shapes, eps, join_style="mitre"))
    if outline.geom_type != "Polygon":
        outline = max(shapely.get_parts(outline), key=lambda g: g.area)
    return shapely.Polygon(outline.exterior)


def flat_angle(outline) -> float:
    """Degrees to turn ``outline`` so that its smallest rectangle's long side lies along x."""
    rect = np.asarray(shapely.minimum_rotated_rectangle(outline).exterior.coords)[:4]
    edges = np.diff(np.vstack([rect, rect[:1]]), axis=0)
    long = edges[np.argmax(snap(np.hypot(edges[:, 0], edges[:, 1])))]
    return float(-np.degrees(np.arctan2(long[1], long[0])))


def _strip(weave, s, visits, over, tiles, centres, labels, colours, scale, tile_mm) -> Strip:
    # a twisted tile of an irregular mesh becomes the polygons it encloses
    shapes = shapely.make_valid(tiles[visits], method="structure", keep_collapsed=False)
    pts = centres[visits]
    outline = outline_of(shapes, 1e-6 * tile_mm / scale)
    theta = flat_angle(outline)  # long side along x, walking towards +x
    travel = transform(affine(theta))((pts[-1] - pts[0])[None])[0]
    turn = affine(theta + 180.0 if len(pts) > 1 and travel[0] < 0 else theta, scale=scale)
    x0, y0 = shapely.transform(outline, transform(turn)).bounds[:2]
    frame = matmul(affine(0.0, (-x0, -y0)), turn)
    place = transform(frame)

    over_strand = weave.tile_over[visits]
    fills = tuple(colours[s] if o else tint(colours[t]) for o, t in
                  zip(over.tolist(), over_strand.tolist()))
    names = tuple(labels[t] for t in over_strand.tolist())
    return Strip(int(s), labels[s], shapely.transform(outline, place),
                 shapely.transform(shapes, place), fills, np.asarray(over, dtype=bool), names,
                 frame, arrow_ink=text_colour_on(colours[s]))


PAD = 0.3  # mm between a label and its tile's edge
PLATE = 0.4  # mm a label's plate reaches beyond its text
ANGLES = tuple(np.arange(0.0, 180.0, 15.0).tolist())  # label turns tried (strip frame)
ID_SIZE = 6.0  # largest cap height of a strip's ID (mm)
NAME_SIZE = 3.0  # largest cap height of the ID printed in an under tile (well below an ID)


def label_strip(strip: Strip, tile_mm: float) -> Strip:
    """``strip`` with its labels: its ID in its largest own tile (and in the other half of a
    long strip), the ID of the strand on top in every under tile, and direction arrows in own
    tiles that hold no ID. Every label is fitted into its tile (less ``PAD``) as large as it goes
    up to a cap, or spread over the neighbouring tiles on a plate; a name that still cannot
    reach ``MIN_CAP`` is left out (the assembly sheet shows that crossing); an ID no own tile
    holds goes on a label tab (:func:`label_flap`), or is kept at the size that fits (so the
    caller can name the tile size that works)."""
    band = None if strip.glue is None else shapely.union_all(strip.glue)
    regions = shapely.intersection(strip.tiles, strip.outline)
    if band is not None:
        regions = shapely.difference(regions, band)
    regions = shapely.buffer(regions, -PAD, join_style="mitre")
    centres = inner_centres(regions)
    own = np.flatnonzero(strip.over & ~shapely.is_empty(regions))
    under = np.flatnonzero(~strip.over & ~shapely.is_empty(regions))
    # the strip's ID: largest own tile; a long strip also in the largest of its other half
    id_tiles: list[int] = []
    # the first tile of a piece with a mark keeps its room for the mark
    cand = own[own != 0] if strip.mark and (own != 0).any() else own
    if len(cand):
        id_size, _ = _fit_text(regions[cand], centres[cand],
                               [strip.label.partition(" ")[0]] * len(cand), ID_SIZE)
        rank = np.lexsort((np.arange(len(cand)), -snap(shapely.area(regions[cand]))))
        first = rank[0] if id_size[rank[0]] >= MIN_CAP else int(np.argmax(snap(id_size)))
        id_tiles = [int(cand[first])]
        if len(cand) >= 6:
            half = cand > cand[first] if cand[first] < cand[len(cand) // 2] else cand < cand[first]
            id_tiles += [int(cand[r]) for r in rank.tolist() if half[r]
                         and id_size[r] >= MIN_CAP][:1]
    # IDs first (spread onto the neighbours if they must), a piece's number ("2/3") in another
    # own tile, then the names round them
    name, _, part = strip.label.partition(" ")
    wanted = [(i, name, ID_SIZE) for i in id_tiles]
    if part and id_tiles:
        spare = [int(cand[r]) for r in rank.tolist() if int(cand[r]) not in id_tiles]
        if spare:
            wanted.append((spare[0], part, NAME_SIZE))
        else:  # one own tile: it says both ("B 2/3")
            wanted[0] = (id_tiles[0], strip.label, ID_SIZE)
    if strip.mark:
        wanted.append((0, strip.mark, NAME_SIZE))
    texts, plates, plate_fills = _place(strip, wanted[:1], regions, centres, band)
    if len(wanted) > 1:
        more = _place(strip, wanted[1:], regions, centres, band,
                      [*plates, *(text_box(t) for t in texts)])
        texts += more[0]
        plates = np.array([*plates, *more[1]], dtype=object)
        plate_fills += more[2]
    id_wanted = wanted
    taken = [*plates, *(text_box(t) for t in texts)]
    if taken:
        regions = shapely.difference(regions, shapely.buffer(shapely.union_all(taken), PAD))
        centres = inner_centres(regions)
    wanted = [(int(i), strip.names[i], NAME_SIZE) for i in under
              if strip.names[i] and not shapely.is_empty(regions[i])]
    more, more_plates, more_fills = _place(strip, wanted, regions, centres, band, taken)
    texts += more
    plates = np.array([*plates, *more_plates], dtype=object)
    plate_fills += more_fills
    wanted = id_wanted + wanted
    # an under tile too small for the name (a border tile at 23 cm): the assembly sheet shows
    # that crossing, the strip leaves it out
    left_out = tuple(w[0] for t, w in zip(texts, wanted) if t.size < MIN_CAP
                     and w not in id_wanted)
    texts = [t for t, w in zip(texts, wanted) if t.size >= MIN_CAP or w in id_wanted]
    if len(plates):
        regions = shapely.difference(regions, shapely.buffer(shapely.union_all(plates), PAD))
    # arrows: the first and the last own tile without an ID, pointing the way the strand goes
    arrows = []
    free = [i for i in own.tolist() if i not in id_tiles and not shapely.is_empty(regions[i])]
    ends = sorted({free[0], free[-1]}) if free else []
    if ends:
        pts = np.array([(c.x, c.y) for c in shapely.centroid(strip.tiles)])
        dirs = [pts[min(i + 1, len(pts) - 1)] - pts[max(i - 1, 0)] for i in ends]
        unit = [arrow_polygon((0.5, 0.0), (1.0, 0.0), 1.0) for _ in ends]
        unit = [shapely.transform(u, transform(turn_to(d))) for u, d in zip(unit, dirs)]
        length = largest_fit(regions[ends], unit, centres[ends], 2.0, 0.45 * tile_mm)
        arrows = [shapely.transform(u, lambda xy, z=z, c=centres[i]: xy * z + c)
                  for u, z, i in zip(unit, length.tolist(), ends) if np.isfinite(z)]
    if texts and texts[0].size < MIN_CAP and id_wanted:  # no own tile reads: a label tab
        tabbed = label_flap(strip, texts[0].text)
        if tabbed is not None:
            strip, texts[0] = tabbed
    if band is not None:  # "glue" on the band, where it fits
        zone = shapely.buffer(shapely.intersection(band, strip.outline), -PAD, join_style="mitre")
        c = inner_centres([zone])
        size, angle = _fit_text([zone], c, [strip.tab], NAME_SIZE)
        if size[0] >= MIN_CAP:
            texts.append(centred_text(c[0], strip.tab, float(size[0]), float(angle[0])))
    return replace(strip, texts=tuple(texts), arrows=np.array(arrows, dtype=object),
                   plates=plates, plate_fills=plate_fills, left_out=left_out)


FLAP_MARGIN = 0.6  # mm between a label tab's text and its edges
FLAP_STEP = 1.5  # mm, the least step between a label tab's corner and its edge's end
FLAP_REACH = 1.5  # a label tab's base may reach past its edge (along its line) up to this share
END_FACING = 0.9  # cosine: a strand's end edge faces the way the strand leaves its last tile


def label_flap(strip: Strip, text: str) -> tuple[Strip, Text] | None:
    """(``strip`` with a label tab, the tab's ``text`` at ``MIN_CAP``), or None where no end
    edge takes one. The tab is a rectangle on a free end edge of the strip's first or last tile
    (the edge the strand leaves by, shared with no other tile of the strip; not a glue band's),
    just large enough for the text along or across the edge plus ``FLAP_MARGIN``, outside every
    tile of the strip; the smallest tab that fits wins."""
    x0, y0, x1, y1 = unit_box(text, 0.0).bounds
    along, high = (x1 - x0) * MIN_CAP, (y1 - y0) * MIN_CAP
    n = len(strip.tiles)
    ends = [i for i in sorted({0, n - 1}) if not (strip.glue is not None and i == n - 1)]
    body = shapely.union_all(strip.tiles)
    best = None
    for i in ends:  # two ends
        tile = strip.tiles[i]
        if tile.geom_type != "Polygon":
            continue
        ring = np.asarray(tile.exterior.coords)
        a, b = ring[:-1], ring[1:]
        mid = (a + b) / 2
        length = np.hypot(*(b - a).T)
        unit = (b - a) / np.maximum(length, 1e-12)[:, None]
        normal = np.column_stack([unit[:, 1], -unit[:, 0]])
        centre = np.asarray(tile.centroid.coords[0])
        normal *= np.sign(dot(normal, mid - centre))[:, None]
        others = shapely.union_all(np.delete(strip.tiles, i))
        free = shapely.distance(shapely.points(mid), others) > 1e-6 * max(strip.length, 1.0) \
            if n > 1 else np.ones(len(mid), dtype=bool)
        if n > 1:
            nb = np.asarray(strip.tiles[1 if i == 0 else n - 2].centroid.coords[0])
            away = (centre - nb) / max(float(np.hypot(*(centre - nb))), 1e-12)
            facing = dot(normal, away) >= END_FACING
        else:
            facing = np.ones(len(mid), dtype=bool)
        for e in np.flatnonzero(free & facing).tolist():  # an edge or two
            # text along the edge, or across it: (base on the edge, depth, text angle)
            for base, depth, direction in ((along, high, unit[e]), (high, along, normal[e])):
                base, depth = base + 2 * FLAP_MARGIN, depth + 2 * FLAP_MARGIN
                if base > FLAP_REACH * length[e]:
                    continue
                base = _tab_base(base, float(length[e]))
                p, q = mid[e] - unit[e] * base / 2, mid[e] + unit[e] * base / 2
                flap = shapely.Polygon([p, q, q + normal[e] * depth, p + normal[e] * depth])
                if shapely.intersection(flap, body).area > 1e-6 * flap.area:
                    continue
                if best is None or flap.area < best[0].area - 1e-9:
                    angle = float(np.degrees(np.arctan2(direction[1], direction[0])))
                    best = (flap, shapely.LineString([p, q]), mid[e] + normal[e] * depth / 2,
                            angle)
    if best is None:
        return None
    flap, edge, centre, angle = best
    fill = next((f for f, o in zip(strip.fills, strip.over.tolist()) if o), "#ffffff")
    label = centred_text(centre, text, MIN_CAP, angle, text_colour_on(fill))
    return replace(strip, flap=flap, flap_edge=edge, flap_fill=fill), label


def _tab_base(base: float, edge: float) -> float:
    """A label tab's ``base`` widened so that its corners meet its ``edge``'s ends, or pass them
    by at least ``FLAP_STEP``: no step a cutter's knife tears at."""
    if base <= edge:
        return edge if base > edge - 2 * FLAP_STEP else base
    return max(base, edge + 2 * FLAP_STEP)


def _place(strip: Strip, wanted, regions, centres, band, taken=()):
    """(texts, plates, plate fills) for ``wanted`` (tile, text, largest size) labels: each
    fitted into its tile; one that does not reach ``MIN_CAP`` there, or lies on something in
    ``taken``, is spread over its neighbouring tiles on a plate of its tile's fill, clear of
    ``taken`` and of the labels placed before it."""
    if not wanted:
        return [], np.zeros(0, dtype=object), ()
    idx = np.array([w[0] for w in wanted])
    size, angle = _fit_text(regions[idx], centres[idx], [w[1] for w in wanted],
                            np.array([w[2] for w in wanted]))
    texts = [centred_text(centres[i], t, float(z), float(a), text_colour_on(strip.fills[i]))
             for (i, t, _), z, a in zip(wanted, size, angle)]
    plates, fills = [], []
    n = len(strip.tiles)
    clash = shapely.intersects(np.array([text_box(t) for t in texts], dtype=object)[:, None],
                               np.array([*taken, None], dtype=object)[None, :]).any(axis=1)
    for k in np.flatnonzero((size < MIN_CAP) | clash).tolist():  # the few cramped labels
        i, text, _ = wanted[k]
        wide = shapely.intersection(shapely.union_all(strip.tiles[max(i - 1, 0):i + 2]),
                                    strip.outline)
        blocked = [band, *taken, *plates, *(text_box(t) for j, t in enumerate(texts)
                                            if j != k and t.size >= MIN_CAP)]
        blocked = [g for g in blocked if g is not None]
        if blocked:
            wide = shapely.difference(wide, shapely.buffer(shapely.union_all(blocked), PAD))
        wide = shapely.buffer(wide, -PAD - PLATE, join_style="mitre")
        zone = shapely.intersection(wide, shapely.buffer(strip.tiles[i], 2 * MIN_CAP))
        inner = inner_centres([zone])[0]
        mid = shapely.get_coordinates(shapely.centroid(zone)).reshape(-1, 2)[:1]
        spots = np.vstack([inner, mid, (inner + mid) / 2]) if len(mid) else inner[None]
        z, a = _fit_text([wide] * len(spots), spots, [text] * len(spots), MIN_CAP)
        best = int(np.argmax(snap(z)))
        near, z, a = spots[best:best + 1], z[best:best + 1], a[best:best + 1]
        if z[0] >= MIN_CAP - 1e-9:
            texts[k] = centred_text(near[0], text, float(z[0]), float(a[0]),
                                    text_colour_on(strip.fills[i]))
            plates.append(shapely.buffer(text_box(texts[k]), PLATE, join_style="mitre"))
            fills.append(strip.fills[i])
    return texts, np.array(plates, dtype=object), tuple(fills)


def turn_to(d) -> NDArray[np.float64]:
    """(3, 3) the turn taking the x axis to the direction ``d``."""
    d = np.asarray(d, dtype=float) / max(float(np.hypot(*d)), 1e-12)
    return affine_matrix(d[0], -d[1], d[1], d[0])


def _fit_text(regions, centres, texts, high: float):
    """(size, angle) of the largest fit of every text in its region, along or across the strip
    (cap heights below ``MIN_CAP`` are kept: the caller reports them)."""
    n = len(texts)
    if n == 0:
        return np.zeros(0), np.zeros(0)
    regions = np.asarray(regions, dtype=object)
    reps = len(ANGLES)
    shapes = [unit_box(t, a) for a in ANGLES for t in texts]
    fits = largest_fit(np.tile(regions, reps), shapes, np.tile(np.asarray(centres), (reps, 1)),
                       0.2, np.tile(np.broadcast_to(np.asarray(high, float), (n,)), reps), 10)
    sizes = np.nan_to_num(fits.reshape(reps, n).T, nan=0.0)
    pick = snap(sizes).argmax(axis=1)  # the first angle of equal sizes
    return sizes[np.arange(n), pick], np.asarray(ANGLES)[pick]
