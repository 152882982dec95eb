"""A virtual assembly of a printed strand book: every piece read from the printed pages (the
Drawing's layers, not the strips that made them) is put back on the weave, and what the maker
reads on it is compared with the weave itself (``weavecut.weave``: which tiles a strand visits,
in which order).

- The direction arrows: every arrow printed on a strip, put back on the weave, points along its
  strand where it lies, and the same way as the arrows of that strand on page 1 (the maker lays
  each strip "arrows as on page 1").
- The glue band of a split strip: it is printed on piece j and lies, put back, on the one tile
  piece j shares with piece j + 1 (the tile it is glued under); the pieces together cover their
  strand's tiles, overlapping only there.
- The weaving steps (page 2): the weft pairs "from the top" are in the order of the strands'
  height on page 1, and each of them runs left-right there; the groups "centre outwards" are in
  the order of the strands' distance from the pattern's centre on page 1.

Page 1's pattern is registered to the weave by a least-squares similarity fit of its tiles'
centroids (asserted exact); a strip piece by the book's frame of that piece, which is checked
first to put the weave's tiles exactly onto the tiles printed on the page.
"""

from __future__ import annotations

import re
from functools import lru_cache

import numpy as np
import pytest
import shapely

from weavecut import inputs
from weavecut.layout.drawing import Polygons, Text
from weavecut.papermodel.book import strand_book
from weavecut.papermodel.strips import model_tiles
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

CASES = {  # name: (input, levels, page, tile size)
    "grid": ("square-grid:2x2", 2, (210.0, 297.0), 20.0),
    "grid-split": ("square-grid:2x2", 2, (148.0, 210.0), 45.0),  # strips in two pieces
    "flower": ("pentagon-flower", 2, (210.0, 297.0), 20.0),      # k = 5: groups
}


@lru_cache(maxsize=None)
def case(name: str):
    spec, levels, page, tile_size = CASES[name]
    weaves = snub_weaves(subdivide(inputs.get(spec), levels))
    return weaves[-1], strand_book(weaves, palette("maritime-12"), page, tile_size)


def layer_polygons(sheet, name: str, keep=lambda shape: True) -> list:
    return [g for layer in sheet.layers if layer.name == name for s in layer.shapes
            if isinstance(s, Polygons) and keep(s) for g in s.to_shapely().tolist()]


def apply(m: np.ndarray, xy: np.ndarray) -> np.ndarray:
    return np.asarray(xy, dtype=float) @ m[:2, :2].T + m[:2, 2]


def moved(m: np.ndarray, geoms):
    return shapely.transform(geoms, lambda xy: apply(m, xy))


def arrow_direction(arrow: shapely.Polygon) -> np.ndarray:
    """The unit vector an arrow polygon points along, from its shape alone: its two reflex
    corners are where the shaft meets the head; the tip is the one corner whose neighbours
    are both convex (the barbs), and the arrow points from the tail's middle (the corners
    three and four along from the tip) to the tip."""
    xy = np.asarray(shapely.geometry.polygon.orient(arrow).exterior.coords)[:-1]
    assert len(xy) == 7, "not an arrow"
    before, after = xy - np.roll(xy, 1, axis=0), np.roll(xy, -1, axis=0) - xy
    convex = before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0] > 0
    tips = [i for i in range(7) if convex[i] and convex[i - 1] and convex[(i + 1) % 7]]
    assert len(tips) == 1 and (~convex).sum() == 2, "not an arrow"
    i = tips[0]
    d = xy[i] - (xy[(i + 3) % 7] + xy[(i + 4) % 7]) / 2
    return d / np.hypot(*d)


def similarity_fit(src: np.ndarray, dst: np.ndarray) -> np.ndarray:
    """The turn, uniform scale and shift (3, 3) taking ``src`` points nearest to ``dst`` in
    least squares (no mirror), as complex numbers: dst = a * src + b."""
    z, w = src @ [1, 1j], dst @ [1, 1j]
    zc, wc = z - z.mean(), w - w.mean()
    a = (np.conj(zc) @ wc) / (np.conj(zc) @ zc)
    b = w.mean() - a * z.mean()
    return np.array([[a.real, -a.imag, b.real], [a.imag, a.real, b.imag], [0.0, 0.0, 1.0]])


class Assembly:
    """The weave and what the printed pages say about it, put back in model coordinates."""

    def __init__(self, weave, book):
        self.weave, self.book = weave, book
        self.tiles = model_tiles(weave)
        self.centres = shapely.get_coordinates(shapely.centroid(self.tiles))
        page1 = book.drawing.sheets[0]
        # page 1's tile outlines (one polygon per tile, stroked, not filled)
        printed = layer_polygons(page1, "pattern", lambda s: s.style.stroke == "#333333"
                                 and s.style.fill is None)
        assert len(printed) == len(self.tiles)
        on_page = shapely.get_coordinates(shapely.centroid(printed))
        self.page1 = similarity_fit(self.centres, on_page)
        size = np.sqrt(np.median(shapely.area(printed)))
        assert np.abs(apply(self.page1, self.centres) - on_page).max() < 1e-6 * size
        self.page1_centres = on_page

    def strand_of_tile(self, point) -> int:
        """The tile (model) whose polygon holds ``point`` (model units)."""
        hit = np.flatnonzero(shapely.contains_xy(self.tiles, *point))
        assert len(hit) == 1, point
        return int(hit[0])

    def local_direction(self, strand: int, tile: int) -> np.ndarray:
        """The strand's direction at ``tile`` in the weave's own walking order."""
        visits, _ = self.weave.strand(strand)
        i = int(np.flatnonzero(visits == tile)[0])
        return self.centres[visits[min(i + 1, len(visits) - 1)]] - \
            self.centres[visits[max(i - 1, 0)]]

    def page1_arrows(self) -> list[tuple[int, int]]:
        """(strand, +1 or -1 against the weave's order) of every arrow on page 1."""
        back = np.linalg.inv(self.page1)
        arrows = layer_polygons(self.book.drawing.sheets[0], "pattern",
                                lambda s: s.style.stroke is None and s.style.fill is not None
                                and len(s.coords) == 7 * s.n_polygons)
        return [self._sense(back, a, owner=None) for a in arrows]

    def _sense(self, back: np.ndarray, arrow, owner) -> tuple[int, int]:
        tip = arrow_direction(arrow)
        model_dir = back[:2, :2] @ tip
        tile = self.strand_of_tile(apply(back, shapely.get_coordinates(
            shapely.centroid(arrow)))[0])
        strand = int(self.weave.tile_over[tile])  # arrows lie in the strand's own tiles
        if owner is not None:
            assert strand == owner, "an arrow in a tile of another strand"
        d = self.local_direction(strand, tile)
        cos = model_dir @ d / np.hypot(*model_dir) / np.hypot(*d)
        assert abs(cos) > 0.7, f"arrow across its strand (cos {cos:.2f})"
        return strand, int(np.sign(cos))

    def pieces(self):
        """Per strip piece: (page, piece, its printed cut outline on the page, the model tiles
        its printed tiles lie on)."""
        for n, piece in self.book.pieces:
            sheet = self.book.drawing.sheets[n - 1]
            m = piece.frame
            visits, _ = self.weave.strand(piece.strand)
            mapped = moved(m, self.tiles[visits])
            printed = np.array(layer_polygons(sheet, "strips"), dtype=object)
            cuts = np.array(layer_polygons(sheet, "cut"), dtype=object)
            # the piece's tiles: the strand's tiles that the frame puts onto a printed tile
            near = shapely.hausdorff_distance(mapped[:, None], printed[None, :]) < 1e-6
            on = near.any(axis=1)
            assert on.any() and (near.sum(axis=1) <= 1).all(), piece.label
            inside = shapely.covers(shapely.buffer(cuts, 1e-6)[None, :],
                                    mapped[on][:, None]).all(axis=0)
            assert inside.sum() == 1, piece.label  # one cut outline holds them all
            yield n, piece, cuts[np.flatnonzero(inside)[0]], visits[on]


@pytest.mark.parametrize("name", ["grid", "grid-split", "flower"])
def test_strip_arrows_put_back_point_as_page_1s(name):
    """Every strip's arrows, put back on the weave, lie in its own tiles along its strand, and
    each strand's arrows (on its strips and on page 1) all point the same way."""
    a = Assembly(*case(name))
    sense: dict[int, set] = {}
    for s, d in a.page1_arrows():
        sense.setdefault(s, set()).add(("page 1", d))
    compared = 0
    for n, piece, cut, _ in a.pieces():
        arrows = [g for g in layer_polygons(a.book.drawing.sheets[n - 1], "arrows")
                  if cut.contains(g)]
        back = np.linalg.inv(piece.frame)
        for arrow in arrows:
            s, d = a._sense(back, arrow, owner=piece.strand)
            compared += s in sense
            sense.setdefault(s, set()).add((piece.label, d))
    mixed = {a.book.plan.labels[s]: sorted(v) for s, v in sense.items()
             if len({d for _, d in v}) > 1}
    assert not mixed, mixed
    assert compared >= 3  # strands with arrows on a strip and on page 1


def test_a_glue_band_lies_on_the_tile_the_next_piece_shares():
    """The split strips' pieces, put back, cover their strand's tiles; pieces j and j + 1 share
    one tile, and that is the tile under piece j's printed glue band (piece j + 1's first
    printed tile there, the band glued under it); the last piece has no band."""
    a = Assembly(*case("grid-split"))
    by_strand: dict[int, list] = {}
    for n, piece, cut, tiles in a.pieces():
        bands = [g for g in layer_polygons(a.book.drawing.sheets[n - 1], "glue")
                 if shapely.covers(shapely.buffer(cut, 1e-6), g)]
        back = np.linalg.inv(piece.frame)
        under = []
        for band in bands:  # the model tile each band covers exactly
            put = moved(back, band)
            near = np.flatnonzero(shapely.hausdorff_distance(a.tiles, put) < 1e-6)
            assert len(near) == 1, piece.label
            under.append(int(near[0]))
        number = re.fullmatch(r"\S+ (\d+)/(\d+)", piece.label)
        j, of = (int(number[1]), int(number[2])) if number else (1, 1)
        by_strand.setdefault(piece.strand, []).append((j, of, set(tiles.tolist()), under))
    split = 0
    for s, pieces in by_strand.items():
        pieces.sort()
        visits, _ = a.weave.strand(s)
        assert set().union(*(t for _, _, t, _ in pieces)) == set(visits.tolist())
        of = pieces[0][1]
        assert [j for j, *_ in pieces] == list(range(1, of + 1))
        for (j, _, mine, band), (_, _, theirs, nxt) in zip(pieces, pieces[1:]):
            shared = mine & theirs
            assert len(shared) == 1 and band == sorted(shared), (a.book.plan.labels[s], j)
        assert pieces[-1][3] == []  # the last piece is glued under, carries no band
        split += of > 1
    assert split >= 4


def steps_text(book) -> str:
    sheet = book.drawing.sheets[1]
    return " ".join(t.text for layer in sheet.layers if layer.name == "steps"
                    for t in layer.shapes if isinstance(t, Text))


def strand_ids(book, names: str) -> list[int]:
    index = {label: s for s, label in enumerate(book.plan.labels)}
    return [index[n] for n in re.findall(r"[A-Z]\d+", names)]


@pytest.mark.parametrize("name", ["grid", "grid-split"])
def test_weft_pairs_are_listed_from_the_top_of_page_1(name):
    """k = 4: the steps list the weft pairs "from the top"; on page 1 those strands run
    left-right, the others up-down, and the list goes down page 1 strand by strand."""
    a = Assembly(*case(name))
    listed = re.search(r"Weft pairs from the top: ([^.]*)\.", steps_text(a.book))
    assert listed, steps_text(a.book)
    weft = strand_ids(a.book, listed[1])
    assert len(weft) == len(set(weft))
    height, across = [], []
    for s in range(a.weave.n_strands):
        visits, _ = a.weave.strand(s)
        xy = a.page1_centres[visits]
        height.append(xy[:, 1].mean())
        dx, dy = np.abs(xy[-1] - xy[0])
        across.append(dx > dy)
    assert sorted(weft) == [s for s in range(a.weave.n_strands) if across[s]]
    tops = [height[s] for s in weft]
    assert tops == sorted(tops, reverse=True), [a.book.plan.labels[s] for s in weft]


def test_groups_are_listed_from_the_centre_of_page_1_outwards():
    """k = 5: the steps list the groups "centre outwards": each strand's nearest tile to the
    pattern's centre on page 1 is no farther in a group than in any later group, and every
    strand is listed once."""
    a = Assembly(*case("flower"))
    listed = re.search(r"Groups, centre outwards: (.*?)\.(?: |$)", steps_text(a.book))
    assert listed
    groups = [strand_ids(a.book, g) for g in re.split(r"\d+: ", listed[1])[1:]]
    assert sorted(s for g in groups for s in g) == list(range(a.weave.n_strands))
    areas = shapely.area(moved(a.page1, a.tiles))
    centre = (a.page1_centres * areas[:, None]).sum(axis=0) / areas.sum()
    reach = [np.hypot(*(a.page1_centres[a.weave.strand(s)[0]] - centre).T).min()
             for s in range(a.weave.n_strands)]
    near = [[reach[s] for s in g] for g in groups]
    size = np.sqrt(np.median(areas))
    for inner, outer in zip(near, near[1:]):
        assert max(inner) <= min(outer) + 1e-6 * size, (inner, outer)
    assert len(groups) > 2
