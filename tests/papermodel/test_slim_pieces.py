"""No paper piece is too thin to cut: every cut outline of every paper-model recipe, read from
the Drawings the recipe's commands write, holds ``MIN_PIECE`` (3 mm): what a disc that wide
reaches inside it is one piece (no neck) and no corner reaches more than twice that beyond it
(no sliver). The measure is checked on hand-made shapes whose narrowest part is known; the
star's neck (strip A8 hung on a 0.2 mm joint at 19 mm octagons) is widened by closing the
notches beside it, printed as its tile; what no widening saves is refused with the size that
works."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely
from shapely import affinity

from weavecut import presets
from weavecut.mesh_io import read_valid_mesh
from weavecut.papermodel import book as book_module
from weavecut.papermodel import label_tabs, strips
from weavecut.papermodel.pages import GAP
from weavecut.papermodel.printcut import WASTE
from weavecut.papermodel.book import SizeError, strand_book
from weavecut.subdivision import subdivide
from weavecut.units import to_mm
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

from tests.built_recipes import built
from tests.papermodel.cut_oracle import notch_mouths, problems

ROOT = Path(__file__).resolve().parents[2]
RECIPES = sorted(p for p in [*ROOT.glob("templates/recipes/*.toml"), *ROOT.glob("examples/*.toml")]
                 if any(j.get("command") == "strands"
                        for j in tomllib.loads(p.read_text()).get("job", [])))


def _dumbbell(neck: float) -> shapely.Polygon:
    """Two 20 mm squares joined by a bar ``neck`` mm wide and 6 mm long."""
    return shapely.union_all([shapely.box(0, 0, 20, 20), shapely.box(26, 0, 46, 20),
                              shapely.box(19, 10 - neck / 2, 27, 10 + neck / 2)])


def _needle(width: float, length: float = 15.0) -> shapely.Polygon:
    """A 20 mm square with a needle ``width`` wide sticking ``length`` out of one side."""
    return shapely.union(shapely.box(0, 0, 20, 20),
                         shapely.box(19, 10 - width / 2, 20 + length, 10 + width / 2))


def _wedge(degrees: float, length: float = 40.0) -> shapely.Polygon:
    """An isosceles triangle with a tip of ``degrees``."""
    half = np.radians(degrees) / 2
    return shapely.Polygon([(0, 0), (length, length * np.tan(half)),
                            (length, -length * np.tan(half))])


@pytest.mark.parametrize("neck", [0.5, 1.8, 2.9, 4.2])
def test_the_slimmest_part_of_a_dumbbell_is_its_neck(neck):
    """Worked by hand: the bar is the narrowest part, whichever way the shape lies."""
    for angle in (0.0, 37.0):
        shape = affinity.rotate(_dumbbell(neck), angle)
        assert neck - strips.slimmest([shape], step=0.02)[0] == pytest.approx(0.0, abs=0.03)
        assert strips.holds([shape], 3.0)[0] == (neck > 3.0)


def _waist(joint: float) -> shapely.Polygon:
    """Two 12 mm wide trapezoids meeting across a ``joint`` mm edge: a strip pinched to a
    joint and at once as wide again (the pentagon flower's octagon tiles at 23 cm, two
    pentagons meeting across their middle edge: 2.83 mm at the narrowest)."""
    h = joint / 2
    return shapely.Polygon([(0, -6), (10, -h), (20, -6), (20, 6), (10, h), (0, 6)])


@pytest.mark.parametrize("joint", [2.83, 2.99])
def test_a_waist_is_no_neck_and_a_bar_is(joint):
    """Whether a joint between two parts of a strip counts as a cut feature, decided: a waist
    (a joint no longer than it is wide) does not, a bar does. A 3 mm disc does not pass
    either, but at a waist the blade turns one wide corner on each side (over 120 degrees
    here; a V under 60 degrees is a notch, held apart) and leaves no strip of paper between
    two near-parallel cuts to drag or tear; the joint is the tile's own outline, which
    widening would push over the neighbouring strands' tiles in the finished weave. So what
    the measure holds to 3 mm is the discs' reach (what they reach is one piece), not their
    passage: the flower's 65 waists (15 octagons, 50 label-tab joints, 2.83-2.99 mm) are no
    necks. Planted: the strict reading (the shrunk outline in one piece) calls the waist a
    neck, and the same joint drawn 6 mm long is a neck in both readings."""
    waist = _waist(joint)
    assert len(shapely.get_parts(waist.buffer(-1.5, quad_segs=16))) == 2  # no disc passes
    assert not problems([waist], strips.MIN_PIECE, strips.SLIVER)
    assert strips.holds([waist], strips.MIN_PIECE)[0]
    assert strips.narrowest_feature([waist])[0] >= strips.MIN_PIECE
    bar = _dumbbell(joint)
    assert problems([bar], strips.MIN_PIECE, strips.SLIVER) == ["outline 0: a neck under 3 mm"]
    assert not strips.holds([bar], strips.MIN_PIECE)[0]


@pytest.mark.parametrize("width", [0.3, 1.5, 2.5])
def test_a_needle_is_a_sliver_and_a_sharp_corner_is_not(width):
    """A needle narrower than a disc, longer than twice it, fails; so does a hairline tip
    (15 degrees); a 35 degree tip (the star's) and a stub as long as it is wide do not."""
    assert strips.slimmest([_needle(width)], step=0.02)[0] == pytest.approx(width, abs=0.03)
    assert strips.holds([_needle(width, length=width)], 3.0)[0]
    assert not strips.holds([_wedge(15.0)], 3.0)[0]
    assert strips.holds([_wedge(35.0)], 3.0)[0]


def _star_book(tile: float):
    mesh = read_valid_mesh(str(ROOT / "examples" / "star.svg"), cell=10.0)
    weaves = snub_weaves(subdivide(mesh, 1))
    return weaves, strand_book(weaves, palette("maritime-12"), tile_size=tile)


def test_the_stars_neck_is_widened_and_printed():
    """At 19 mm octagons strip A8's tiles hang on a 0.2 mm joint: the strip as its tiles make
    it fails, the strip printed holds 3 mm, contains every tile it had, and its tiles cover it
    (the filled notches are printed, as the tile beside them)."""
    weaves, book = _star_book(19.0)
    tiles = strips.model_tiles(weaves[-1])
    widened = 0
    for _, piece in book.pieces:
        visits, _ = weaves[-1].strand(piece.strand)
        raw = shapely.transform(shapely.union_all(shapely.make_valid(tiles[visits])),
                                lambda xy: (piece.frame[:2, :2] @ xy.T).T + piece.frame[:2, 2])
        assert strips.holds([piece.cut], strips.MIN_PIECE)[0], piece.label
        # nothing cut away but the hairline wedges that open a V between two tiles
        assert shapely.difference(raw, piece.outline).area < 0.01 * raw.area, piece.label
        union = shapely.union_all(piece.tiles)
        assert union.symmetric_difference(piece.outline).area < 1e-6 * piece.outline.area
        if not strips.holds([raw], strips.MIN_PIECE)[0]:
            widened += 1
            assert piece.outline.area > raw.area
    assert widened >= 1  # A8 (and A7, 2.9 mm) needed it


@pytest.mark.slow
def test_a_strip_no_widening_saves_is_refused_with_the_size_that_works(monkeypatch):
    """Asked for 5 mm necks with no strip thickened (``slim.thickened`` mends what closing
    notches does not), the star at 21 mm is refused, naming a tile size at which the book is
    made (its necks then all 5 mm wide)."""
    for module in (book_module, strips):
        monkeypatch.setattr(module, "MIN_PIECE", 5.0)
    monkeypatch.setattr(strips, "thickened", lambda outline, tiles, width: (outline, tiles))
    with pytest.raises(SizeError, match=r"neck narrower than 5 mm, too thin to cut") as refused:
        _star_book(21.0)
    need = float(str(refused.value).split("use --tile-size ")[-1].split("mm")[0])
    assert need > 21.0
    _, book = _star_book(need)
    assert strips.holds([p.cut for _, p in book.pieces], 5.0, slivers=False).all()


def _kerf(recipe: Path) -> float:
    """The widest kerf of the card the recipe's laser jobs cut (0 without one): card outlines
    lie half a kerf outside their strips, so two of them are that much nearer than the packer's
    gap."""
    jobs = tomllib.loads(recipe.read_text()).get("job", [])
    return max((to_mm(presets.load("materials", j.get("material", "card-300gsm"))["kerf"])
                for j in jobs if j.get("laser-card")), default=0.0)


@pytest.mark.slow
@pytest.mark.parametrize("recipe", RECIPES, ids=lambda p: p.stem)
def test_every_cut_piece_of_a_paper_model_recipe_holds_the_minimum(recipe, tmp_path_factory):
    """Every outline on a cut layer of every Drawing the recipe's commands write (the printed
    books' strip pages, the cutters' cut files, the card sheets) holds ``MIN_PIECE``, by the
    product's measure and by ``cut_oracle`` (necks, slivers, notches: a label tab's shoulder
    beside its tile's edge read 1.26 mm); outlines on one sheet keep the packer's gap, and on
    the sheets of a print-and-cut job (the printed pages and the cut files beside them)
    ``printcut.WASTE`` (3 mm): the waste between two strips is paper a drag knife must cut
    past, not drag along. Planted: print-and-cut packed at the scissors' 2 mm gap fails. (The
    build is the session's: ``built_recipes``.)"""
    jobs = tomllib.loads(recipe.read_text()).get("job", [])
    machine = {Path(j["output"]).parent for j in jobs if j.get("cutter")}
    outlines, gaps = 0, []
    for name, sheets in built(tmp_path_factory, recipe)[1]:
        gap = WASTE if Path(name).parent in machine else GAP
        gaps.append(gap)
        cut = [g for sheet in sheets for g in sheet]
        if cut:
            slim = strips.narrowest_feature(cut)
            # a notch opened to MIN_PIECE by bisection may read a hair under it
            assert slim.min() >= strips.MIN_PIECE - 1e-9, (name, float(slim.min()))
            outlines += len(cut)
        for cut in sheets:
            assert not problems(cut, strips.MIN_PIECE, strips.SLIVER, gap - _kerf(recipe)), name
    assert outlines > 0
    assert (WASTE in gaps) == bool(machine)  # the rule is applied


def test_widened_tiles_of_the_voronoi_example_stay_areas():
    """The Voronoi example's irregular strips are widened where a notch is filled: GEOS gave a
    tile plus its filled notch back as the polygon beside a collapsed edge (a LineString), a
    collection without a boundary, whose shared length with the next notch was NaN: a sort key
    that depended on the CPU (now refused by ``snap``). Every printed tile is a (Multi)Polygon
    with a boundary, and the widened strips' tiles keep all their area."""
    from weavecut.papermodel.modules import plan_modules

    mesh = read_valid_mesh(str(ROOT / "examples" / "voronoi-patch.obj"))
    weave = snub_weaves(subdivide(mesh, 2))[-1]  # as `strands` and the books' tests make it
    plan = plan_modules(weave)
    original, grown = strips.widened, []

    def keep(outline, tiles, width=None):
        made = original(outline, tiles, width)
        if made[0] is not outline:
            grown.append((outline, tiles, *made))
        return made

    strips.widened = keep
    try:
        made = strips.build_strips(weave, plan, ["#336699"] * len(plan.labels),
                                   20.0 / strips.octagon_size(weave), range(len(plan.labels)))
    finally:
        strips.widened = original
    for strip in made:
        kinds = shapely.get_type_id(strip.tiles)
        assert set(kinds.tolist()) <= {3, 6}, (strip.label, kinds)  # Polygon, MultiPolygon
        assert not any(b is None for b in shapely.boundary(strip.tiles).tolist()), strip.label
    assert len(grown) >= 2  # the example has strips to widen
    for outline, before, _, after in grown:  # the filled notches are added, nothing is lost
        added = shapely.area(shapely.difference(shapely.union_all(after), outline))
        assert sum(shapely.area(after)) == pytest.approx(sum(shapely.area(before)) + added,
                                                         rel=1e-9)


@pytest.mark.parametrize("planted", ["neck", "notch", "sliver", "gap"])
def test_the_oracle_finds_a_planted_1_2_mm_feature(planted):
    """A strip-sized outline with a 1.2 mm neck, notch or sliver, or two outlines 1.2 mm apart,
    each fails the oracle; the outline without it passes."""
    plain = shapely.box(0, 0, 60, 12)
    shapes = {"neck": shapely.union(shapely.box(0, 0, 29, 12), shapely.box(31, 0, 60, 12))
              .union(shapely.box(28, 5.4, 32, 6.6)),
              "notch": shapely.Polygon([(0, 0), (60, 0), (60, 12), (31.2, 12), (30, 6),
                                        (30, 12), (0, 12)]),
              "sliver": shapely.union(plain, shapely.box(59, 5.4, 75, 6.6))}
    assert not problems([plain], strips.MIN_PIECE, strips.SLIVER, GAP)
    if planted == "gap":
        found = problems([plain, shapely.box(0, 13.2, 60, 25)], strips.MIN_PIECE,
                         strips.SLIVER, GAP)
    else:
        found = problems([shapes[planted]], strips.MIN_PIECE, strips.SLIVER, GAP)
    assert found and all(planted in f or ("apart" in f and planted == "gap") for f in found)
    if planted != "gap":  # the product's measure agrees
        assert strips.narrowest_feature([shapes[planted]])[0] < strips.MIN_PIECE


def _old_tab(a, b, normal, base, depth, before, after):
    """The label tab before chamfers: a rectangle overhanging its edge by ``FLAP_STEP`` or
    more (its shoulder left a 1.26 mm notch beside the tile's next edge)."""
    edge = float(np.hypot(*(b - a)))
    unit, mid = (b - a) / edge, (a + b) / 2
    base = (edge if base > edge - 2 * label_tabs.FLAP_STEP else base) if base <= edge else \
        max(base, edge + 2 * label_tabs.FLAP_STEP)
    p, q = mid - unit * base / 2, mid + unit * base / 2
    return (shapely.Polygon([p, q, q + normal * depth, p + normal * depth]), 0.0,
            shapely.LineString([p, q]))


@pytest.mark.slow
def test_a_label_tab_leaves_no_notch_beside_its_tile(monkeypatch):
    """The pentagon flower's 70 label tabs at 23 cm: each tab wider than its edge is lifted on
    chamfers, so no corner of a tabbed strip is a notch under ``MIN_PIECE``; the old
    rectangular tab (planted) leaves notches 1.26 mm wide, and the oracle finds them."""
    from weavecut.papermodel.book import tile_size_for

    from weavecut.inputs import pentagon_flower

    ws = snub_weaves(subdivide(pentagon_flower(), 3))

    def narrowest(ws):
        book = strand_book(ws, palette("okabe-ito"), tile_size=tile_size_for(ws[-1], 230.0))
        tabbed = [p.cut for _, p in book.pieces if p.flap is not None]
        assert len(tabbed) == 70
        return min((m for o in tabbed for m in notch_mouths(o)), default=np.inf)

    assert narrowest(ws) >= strips.MIN_PIECE
    monkeypatch.setattr(label_tabs, "_tab", _old_tab)
    assert narrowest(ws) == pytest.approx(1.26, abs=0.01)
