"""Printable paper strands (paper section 5.2): one strip per strand, laid out in millimetres.

A *strip* is one strand cut from paper: the union of every tile it visits, its own tiles in its
colour, the tiles it passes under printed light with the ID of the strand on top there. Strips
are laid out in millimetres, long axis along x, walking towards +x; ``pages`` packs them.
Which strand is printed where, and in which colour, is planned in ``modules``; ``strip_labels``
puts the labels, arrows and label tabs on a strip.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
import shapely
from numpy.typing import NDArray

from ..numeric import affine, matmul, median, snap, transform
from ..weave.model import Weave
from ..layout.contrast import text_colour_on
from ..layout.drawing import Text
from ..layout.labels import uprights
from .modules import ModulePlan
from .notches import NotchError, widen_notches
from .slim import areal, given_to_tiles, holds, outline_of, thickened, thin_parts
from .slim import SLIVER, narrowest_feature, slimmest  # noqa: F401 (the measures, as strips.*)
from .symmetry import tile_centres
from ..layout.weave_figure import tile_rings

LIGHT = 0.22  # share of the over strand's colour in an under-crossing tile (rest white)
MIN_PIECE = 3.0  # mm: the narrowest part of a paper strip that scissors cut without it tearing



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

    @cached_property
    def cut(self) -> shapely.Polygon:
        """The cut line: the outline and the label tab, if any (made once per strip: a page,
        its packing and its checks each ask)."""
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
        return moved_strips([self], [matrix], [angle])[0]


GEOMETRY = ("outline", "tiles", "arrows", "glue", "plates", "folds", "flap", "flap_edge")


def moved_strips(strips, matrices, angles) -> list[Strip]:
    """:meth:`Strip.moved` of every strip by its matrix and angle, all at once (one transform
    of every strip's shapes, the texts set upright together)."""
    parts, where = [], []  # every shape, and (strip, field, how many; None: a single shape)
    for s, strip in enumerate(strips):
        for name in GEOMETRY:
            value = getattr(strip, name)
            if value is not None:
                one = isinstance(value, shapely.Geometry)
                parts.extend([value] if one else value)
                where.append((s, name, None if one else len(value)))
    m = np.asarray(matrices, dtype=float).reshape(-1, 3, 3)
    shapes = np.array(parts, dtype=object)
    owner = np.repeat(np.repeat([s for s, _, _ in where],
                                [1 if k is None else k for _, _, k in where]),
                      shapely.get_num_coordinates(shapes)) if len(shapes) else np.zeros(0, int)
    moved = iter(_valid(shapely.transform(shapes, lambda xy: _apply(m[owner], xy))))
    fields: list[dict] = [{} for _ in strips]
    for s, name, k in where:
        fields[s][name] = next(moved) if k is None else np.array(
            [next(moved) for _ in range(k)], dtype=object)
    texts = [t for strip in strips for t in strip.texts]
    xy = _apply(np.repeat(m, [len(strip.texts) for strip in strips], axis=0),
                np.array([(t.x, t.y) for t in texts], dtype=float).reshape(-1, 2))
    turn = np.repeat(np.asarray(angles, dtype=float), [len(strip.texts) for strip in strips])
    texts = iter(uprights([replace(t, x=x, y=y, angle=t.angle + a) for t, (x, y), a in
                           zip(texts, xy.tolist(), turn.tolist())]))
    return [replace(strip, **fields[s], texts=tuple(next(texts) for _ in strip.texts),
                    frame=matmul(matrix, strip.frame))
            for s, (strip, matrix) in enumerate(zip(strips, m))]


def _valid(shapes: NDArray[np.object_]) -> NDArray[np.object_]:
    """``shapes`` with every polygon that turning made cross itself (an irregular strip whose
    outline comes within rounding of itself) made valid again, as a Polygon if it was one."""
    bad = np.flatnonzero(~shapely.is_valid(shapes))
    for k in bad.tolist():  # rare: a few shapes of an irregular mesh's strips
        fixed = areal(shapely.make_valid(shapes[k], method="structure", keep_collapsed=False))
        if shapes[k].geom_type == "Polygon" and fixed.geom_type != "Polygon":
            fixed = outline_of(shapely.get_parts(fixed), 1e-9 * max(fixed.length, 1.0))
        shapes[k] = fixed
    return shapes


def _apply(m, xy) -> NDArray[np.float64]:
    """Each point of ``xy`` (N, 2) through its own affine matrix ``m`` (N, 3, 3), as
    :func:`~weavecut.numeric.transform` maps it."""
    x, y = xy[:, 0], xy[:, 1]
    return np.stack([m[:, 0, 0] * x + m[:, 0, 1] * y + m[:, 0, 2],
                     m[:, 1, 0] * x + m[:, 1, 1] * y + m[:, 1, 2]], axis=-1)


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
    return float(median(d))


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
    return float(median(sides.min(axis=1)))


def build_strips(weave: Weave, plan: ModulePlan, colours: list[str], scale: float,
                 strands, copy: int = 0, labels: tuple[str, ...] | None = None) -> list[Strip]:
    """An unlabelled Strip for every strand in ``strands``, ``scale`` mm per model unit.

    With ``copy`` j > 0 the strips keep the shape of ``strands`` but are coloured and labelled
    as their images under the turn by j * 2 pi / k (so every copy has the same layout).
    ``labels`` replaces the plan's strand IDs (the paper's module prints: no copy letter).
    """
    return build_copies(weave, plan, colours, scale, strands, [copy], labels)[0]


def build_copies(weave: Weave, plan: ModulePlan, colours: list[str], scale: float, strands,
                 copies, labels: tuple[str, ...] | None = None) -> list[list[Strip]]:
    """:func:`build_strips` of each of ``copies``: the strips' shapes are made once, every
    copy colours and names them as its images."""
    tiles = model_tiles(weave)
    centres = tile_centres(weave)
    tile_mm = octagon_size(weave) * scale
    shapes = []
    for s in np.asarray(strands).tolist():  # strands, not mesh elements
        visits, over = weave.strand(s)
        if plan.reversed[s]:
            visits, over = visits[::-1], over[::-1]
        shapes.append((s, visits, over, *_strip_shape(visits, tiles, centres, scale, tile_mm)))
    out = []
    for copy in copies:
        image = plan.symmetry.strand_powers()[copy]
        names = plan.labels if labels is None else labels
        names = [names[t] for t in image.tolist()]
        cols = [colours[t] for t in image.tolist()]
        c = plan.symmetry.centre
        back = matmul(matmul(affine(0.0, c), affine(-np.degrees(copy * plan.symmetry.angle))),
                      affine(0.0, -c))
        out.append([replace(_strip(weave, *shape, names, cols), strand=int(image[shape[0]]),
                            frame=matmul(shape[-1], back)) for shape in shapes])
    return out


def flat_angle(outline) -> float:
    """Degrees to turn ``outline`` so that its smallest rectangle's long side lies along x."""
    rect = np.asarray(shapely.minimum_rotated_rectangle(outline).exterior.coords)[:4]
    edges = np.diff(np.vstack([rect, rect[:1]]), axis=0)
    long = edges[np.argmax(snap(np.hypot(edges[:, 0], edges[:, 1])))]
    return float(-np.degrees(np.arctan2(long[1], long[0])))


def widened(outline: shapely.Polygon, tiles: NDArray[np.object_], width: float | None = None
            ) -> tuple[shapely.Polygon, NDArray[np.object_]]:
    """(outline, tiles) of a strip whose necks narrower than ``width`` are filled out: the
    notches beside each :func:`thin_parts` are closed (a round closing of the outline, as small
    as does it; only the notches within ``width`` of a thin part), each filled notch printed
    as the tile it shares the longest edge with. Unchanged when the strip already
    :func:`holds` (and when no closing up to twice ``width`` helps: the caller refuses it).
    ``width`` defaults to ``MIN_PIECE``."""
    width = MIN_PIECE if width is None else width
    if holds([outline], width, slivers=False)[0]:
        return outline, tiles
    thin = shapely.buffer(shapely.union_all(thin_parts(outline, width)), width)
    for radius in (width, 1.5 * width, 2.0 * width):
        closed = shapely.buffer(shapely.buffer(outline, radius, quad_segs=8), -radius,
                                quad_segs=8)
        fills = [g for g in shapely.get_parts(shapely.difference(closed, outline))
                 if g.area > 0 and g.intersects(thin)]
        grown = outline_of(np.array([outline, *fills], dtype=object), 1e-6 * width)
        grown = shapely.simplify(grown, width / 20)  # the arcs in few segments: a knife's
        # corner check (``printcut.cut_report``) reads no chord as a narrow feature
        if holds([grown], width, slivers=False)[0]:
            break
    else:
        return outline, tiles
    added = [g for g in shapely.get_parts(shapely.difference(grown, outline)) if g.area > 0]
    return grown, given_to_tiles(tiles, added)


def _strip_shape(visits, tiles, centres, scale, tile_mm):
    """(outline, tiles, frame) of the strip of the tiles ``visits``: in mm, long axis along
    x, walking towards +x, and the map from model units to it."""
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
    outline, shapes = widened(shapely.transform(outline, place), shapely.transform(shapes, place))
    try:  # a V between two tiles opened as the ball's are (scissors and blades clear it)
        opened = widen_notches(outline)
    except NotchError:  # none opens within its tiles: narrowest_feature reports it
        opened = outline
    if opened is not outline:
        shapes = shapely.intersection(shapes, opened)
    return *thickened(opened, shapes, MIN_PIECE), frame


def _strip(weave, s, visits, over, outline, shapes, frame, labels, colours) -> Strip:
    over_strand = weave.tile_over[visits]
    fills = tuple(colours[s] if o else tint(colours[t]) for o, t in
                  zip(over.tolist(), over_strand.tolist()))
    names = tuple(labels[t] for t in over_strand.tolist())
    return Strip(int(s), labels[s], outline, shapes, fills, np.asarray(over, dtype=bool), names,
                 frame, arrow_ink=text_colour_on(colours[s]))
