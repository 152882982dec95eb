"""What a pair of scissors can cut (paper section 5.2): how thin a strip's cut outline is
(necks, slivers, notches) and how a strip too thin somewhere is mended. A strip whose tiles meet
at a corner, end in a needle or leave a slit between them is thickened there and its slits
filled, the added paper printed as the tile beside it: a maker never cuts a part narrower than
the kit's limit (``strips.MIN_PIECE``)."""

from __future__ import annotations

import numpy as np
import shapely
from numpy.typing import NDArray

from ..layout.labels import distinct_geoms
from ..numeric import snap
from .notches import narrowest_notch

SLIVER = 6.0  # mm: a part narrower than a width may stick out this far beyond the parts that
# are as wide (a sharp corner: 2.3 mm for the star's 35-degree tips at 3 mm), no farther (a
# sliver); a fixed length, so that a wider disc never passes what a narrower one fails


def outline_of(shapes, eps: float) -> shapely.Polygon:
    """The cut line round ``shapes`` (tiles of one strip): their union without holes; tiles
    that only touch at a corner are joined by growing them ``eps``."""
    outline = shapely.union_all(shapes)
    if outline.geom_type != "Polygon":  # tiles touching at a corner: keep one piece
        outline = shapely.union_all(shapely.buffer(shapes, eps, join_style="mitre"))
    if outline.geom_type != "Polygon":
        outline = max(shapely.get_parts(outline), key=lambda g: g.area)
    return shapely.Polygon(outline.exterior)


def opened(polygons, width: float) -> NDArray[np.object_]:
    """The parts of ``polygons`` a disc ``width`` across reaches inside them (a round opening)."""
    shrunk = shapely.buffer(np.asarray(polygons, dtype=object), -width / 2, quad_segs=8)
    return shapely.buffer(shrunk, width / 2, quad_segs=8)


def holds(polygons, width: float, slivers: bool = True) -> NDArray[np.bool_]:
    """(N,) True for every polygon that is no thinner than ``width`` anywhere it matters to a
    pair of scissors: what a disc ``width`` across reaches inside it is one piece (no neck),
    and no corner reaches farther than ``SLIVER`` beyond it (no sliver; with ``slivers``
    False, necks only: what widening mends and a larger size always cures). Equal polygons (a
    module's copies) are looked at once."""
    of, distinct = distinct_geoms(polygons)
    return _holds(distinct, width, slivers)[of]


def _holds(polygons, width, slivers: bool = True) -> NDArray[np.bool_]:
    """:func:`holds` of every polygon, ``width`` one for all or one each."""
    core = opened(polygons, width)
    one = (shapely.get_num_geometries(core) == 1) & ~shapely.is_empty(core)
    if not slivers:
        return one
    coords, owner = shapely.get_coordinates(polygons, return_index=True)
    far = shapely.distance(shapely.points(coords), core[owner])
    reach = np.zeros(len(polygons))
    np.maximum.at(reach, owner, np.nan_to_num(far, nan=np.inf))
    return one & (reach <= SLIVER)


def slimmest(polygons, step: float = 0.05, largest: float = 50.0) -> NDArray[np.float64]:
    """(N,) per polygon the largest multiple of ``step`` mm (at most ``largest``) it
    :func:`holds`: the narrowest neck or sliver a maker must cut round (a polygon that holds
    3 mm reads 3 mm, not the bisection's last point under it)."""
    of, polygons = distinct_geoms(polygons)
    low, high = np.zeros(len(polygons), int), np.full(len(polygons), int(largest / step))
    while (high - low > 1).any():  # bisection steps on the grid, all polygons at once
        mid = (low + high) // 2
        ok = _holds(polygons, mid * step)
        low, high = np.where(ok, mid, low), np.where(ok, high, mid)
    return (low * step)[of]


def narrowest_feature(polygons) -> NDArray[np.float64]:
    """(N,) per outline the narrowest part a blade must cut round or clear: its
    :func:`slimmest` neck or sliver of paper, or the mouth of its narrowest notch
    (:func:`.notches.narrowest_notch`), whichever is narrower."""
    return np.minimum(slimmest(polygons), narrowest_notch(polygons))


def thin_parts(outline: shapely.Polygon, width: float) -> list:
    """The parts of ``outline`` that make it fail :func:`holds`: of what a disc ``width``
    across does not reach, the bits that join two reached parts (necks) and those reaching
    farther than ``SLIVER`` out of them (slivers); not the corners' small chips."""
    core = opened([outline], width)[0]
    cores = list(shapely.get_parts(core))
    out = []
    for bit in shapely.get_parts(shapely.difference(outline, core)):  # a few bits
        if bit.area <= 0:
            continue
        touching = sum(shapely.distance(c, bit) < 1e-6 * width for c in cores)
        far = shapely.distance(shapely.points(shapely.get_coordinates(bit)), core).max()
        if touching > 1 or not far <= SLIVER:
            out.append(bit)
    return out


def areal(geometry):
    """The polygons of an overlay's result, as one (Multi)Polygon. GEOS can return the union of
    a tile and a filled notch that meet along a nearly straight edge as a GeometryCollection:
    the polygon, and that edge collapsed by its snap-rounding into a LineString of no area (a
    strip of the Voronoi example). A collection has no boundary (``shapely.boundary`` gives
    None, and its length NaN), and a tile is an area: its lines are dropped."""
    parts = shapely.get_parts(geometry)
    parts = parts[shapely.get_type_id(parts) == 3]
    return parts[0] if len(parts) == 1 else shapely.multipolygons(parts)


def cuts(polygons, width: float) -> NDArray[np.bool_]:
    """(N,) True for every polygon that :func:`holds` ``width`` (no neck, no sliver) and whose
    notches all have a mouth at least that wide: what scissors cut cleanly."""
    return holds(polygons, width) & (narrowest_notch(polygons) >= width * (1 - 1e-9))


MEND = 0.1  # share of a strip's paper thickening may add: a strip thin all along is mended by
# a larger size (the book refuses it with one), not by a blob
HAIR = 0.05  # mm: steps of a mended outline this small are rounding (GEOS's unions), not notches


def thickened(outline: shapely.Polygon, tiles: NDArray[np.object_], width: float
              ) -> tuple[shapely.Polygon, NDArray[np.object_]]:
    """(outline, tiles) of a strip that still fails :func:`cuts` once its necks are widened
    and its V notches opened (tiles of an irregular mesh: a tile hung on a corner, a needle
    tile, a slit between two tiles): every :func:`thin_parts` grown by a radius and every notch
    narrower than twice it filled (a mitred closing, which leaves the other corners as they
    are), with the smallest radius of ``width`` / 2, 3/4, 1 that makes it cut; the outline's
    steps under ``HAIR`` smoothed, each added bit printed as the tile beside it
    (:func:`given_to_tiles`). Unchanged when it already cuts, when no radius helps, or when
    it would add more than ``MEND`` of its paper (the caller reports it)."""
    if cuts([outline], width)[0]:
        return outline, tiles
    thin = shapely.union_all(thin_parts(outline, width))
    for radius in (0.5 * width, 0.75 * width, width):
        thick = shapely.union(outline, shapely.buffer(thin, radius, quad_segs=2))
        closed = shapely.buffer(shapely.buffer(thick, radius, join_style="mitre"), -radius,
                                join_style="mitre")
        grown = thick
        for fill in shapely.get_parts(shapely.difference(closed, thick)).tolist():  # a few
            more = shapely.union(grown, fill)  # a notch, not a gap between two arms of a
            # curled strip (a hole)
            if 0 < fill.area <= 4 * width ** 2 and not shapely.get_num_interior_rings(more):
                grown = more
        grown = _smooth(outline_of(np.array([grown]), 1e-6 * width))
        if grown.area > (1 + MEND) * outline.area:  # thin all along: a size question
            return outline, tiles
        if cuts([grown], width)[0]:
            break
    else:
        return outline, tiles
    kept = np.array([areal(g) for g in shapely.intersection(tiles, grown)], dtype=object)
    added = shapely.buffer(shapely.buffer(shapely.difference(grown, shapely.union_all(kept)),
                                          -HAIR, join_style="mitre"), HAIR, join_style="mitre")
    # (the smoothed outline's hairs along the tiles stay unprinted: under a cut line)
    return grown, given_to_tiles(kept, [g for g in shapely.get_parts(added) if g.area > 0])


def _smooth(outline: shapely.Polygon) -> shapely.Polygon:
    """``outline`` without steps under ``HAIR`` and without places where it comes within a
    tenth of that of itself (a mitred closing: turned to a strip's frame, such a place would
    cross itself)."""
    eps = HAIR / 10
    closed = shapely.buffer(shapely.buffer(outline, eps, join_style="mitre"), -eps,
                            join_style="mitre")
    return shapely.simplify(outline_of(np.array([closed, outline], dtype=object), eps), HAIR)


def printed_once(tiles: NDArray[np.object_], owner=None) -> NDArray[np.object_]:
    """``tiles`` (one strip's, or several strips': ``owner`` gives each tile's strip) with the
    paper two tiles of a strip share (more than a ``HAIR`` square) left to the later one: a
    tile of an irregular mesh twisted over its neighbour (the Voronoi example's strip A32: a
    0.9 mm² lobe) printed both tiles there, one outline showing through the other. The
    strip's tiles themselves keep the weave's paper (labels, crossings)."""
    first, second = shapely.STRtree(tiles).query(tiles, predicate="overlaps")
    pairs = first < second
    if owner is not None:
        pairs &= owner[first] == owner[second]
    first, second = first[pairs], second[pairs]
    shared = shapely.area(shapely.intersection(tiles[first], tiles[second])) > HAIR ** 2
    if not shared.any():
        return tiles
    tiles = tiles.copy()
    for i, j in sorted(zip(first[shared].tolist(), second[shared].tolist())):  # a few pairs
        tiles[i] = areal(shapely.difference(tiles[i], tiles[j]))
    return tiles


def given_to_tiles(tiles: NDArray[np.object_], added) -> NDArray[np.object_]:
    """``tiles`` with each bit of paper in ``added`` (outside them) printed as one of them: the
    one it shares the longest edge with (the nearest where it shares none)."""
    tiles = tiles.copy()
    for bit in added:  # a few bits per strip
        shared = shapely.length(shapely.intersection(shapely.boundary(tiles), bit.boundary))
        k = int(np.lexsort((np.arange(len(tiles)), snap(shapely.distance(tiles, bit)),
                            -snap(shared)))[0])
        tiles[k] = areal(shapely.union(tiles[k], bit))
    return tiles
