"""The packer's promises, checked on shapes whose best packing is known: never more pages than
the pieces need, a piece turned only when it must be, and a clear refusal for a piece that fits
at no angle. Every placement is checked with shapely: inside the area, ``gap`` apart, a turn
(determinant 1), by a multiple of the angle step."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from weavecut.papermodel.packing import Place, pack


def placed(shapes, places):
    """Every shape moved by its Place, with its page."""
    out = []
    for s, p in zip(shapes, places):
        m = p.matrix()
        out.append((p.page, shapely.transform(s, lambda xy, m=m: xy @ m[:2, :2].T + m[:2, 2])))
    return out


def assert_valid(shapes, places, width, height, gap, step=15.0):
    moved = placed(shapes, places)
    area = shapely.box(-1e-6, -1e-6, width + 1e-6, height + 1e-6)
    for (page, g), s, p in zip(moved, shapes, places):
        assert area.contains(g), (p, g.bounds)
        assert np.linalg.det(p.matrix()[:2, :2]) == pytest.approx(1.0)
        assert abs(g.area - s.area) < 1e-6 * s.area
        assert p.angle % step == pytest.approx(0.0, abs=1e-9) or \
            p.angle % step == pytest.approx(step, abs=1e-9)
    for i, (pi, gi) in enumerate(moved):
        for pj, gj in moved[i + 1:]:
            if pi == pj:
                assert gi.distance(gj) >= gap - 1e-6
    return moved


def test_place_matrix_turns_counter_clockwise_then_shifts():
    m = Place(0, 90.0, (5.0, 7.0)).matrix()
    assert np.allclose(m @ [1.0, 0.0, 1.0], [5.0, 8.0, 1.0])
    assert np.allclose(m @ [0.0, 2.0, 1.0], [3.0, 7.0, 1.0])
    assert np.allclose(Place(1, 0.0, (0.0, 0.0)).matrix(), np.eye(3))


@pytest.mark.parametrize("n", [1, 2, 3, 5])
def test_pieces_that_fill_half_a_page_take_half_as_many_pages(n):
    """Bars a little under half the area's height: two fit a page, three never do, so n bars
    need exactly ceil(n / 2) pages, and each page's bars lie one above the other."""
    width, height, gap = 100.0, 50.0, 2.0
    bar = shapely.box(0.0, 0.0, 90.0, 20.0)
    places = pack([bar] * n, width, height, gap)
    moved = assert_valid([bar] * n, places, width, height, gap)
    assert max(p.page for p in places) + 1 == -(-n // 2)
    assert sorted({p.page for p in places}) == list(range(-(-n // 2)))
    for page, g in moved:  # long side along x: a bar turned upright would not fit
        x0, y0, x1, y1 = g.bounds
        assert x1 - x0 == pytest.approx(90.0, abs=1e-6)


def test_a_piece_too_long_for_the_width_is_turned_to_fit():
    """A 14 x 95 bar on an area 100 wide and 40 high fits only lying along x: upright it is taller
    than the area; the packer must find the turn (90 or 270 degrees)."""
    bar = shapely.box(0.0, 0.0, 14.0, 95.0)
    places = pack([bar], 100.0, 40.0, 2.0)
    assert_valid([bar], places, 100.0, 40.0, 2.0)
    assert places[0].angle % 180.0 == pytest.approx(90.0)


def test_a_piece_that_fits_at_no_angle_is_refused_with_its_size():
    with pytest.raises(ValueError, match=r"a strip of 130 x 60 mm fits the printable area at "
                                         r"no angle"):
        pack([shapely.box(0.0, 0.0, 130.0, 60.0)], 100.0, 50.0, 2.0)


def test_pieces_keep_their_order_and_small_ones_fill_the_gaps():
    """Places come back in input order (each is the piece's own: its moved shape has the piece's
    area), and small squares go beside a large block on its page rather than onto a new one."""
    width, height, gap = 120.0, 60.0, 2.0
    shapes = [shapely.box(0.0, 0.0, 10.0, 10.0), shapely.box(0.0, 0.0, 80.0, 56.0),
              shapely.box(0.0, 0.0, 12.0, 12.0), shapely.box(0.0, 0.0, 14.0, 14.0)]
    places = pack(shapes, width, height, gap)
    moved = assert_valid(shapes, places, width, height, gap)
    assert [g.area for _, g in moved] == pytest.approx([s.area for s in shapes])
    assert {p.page for p in places} == {0}


@pytest.mark.parametrize("step", [30.0, 45.0])
def test_turns_are_multiples_of_the_angle_step(step):
    """With coarser steps every piece is still placed at a multiple of the step, never between."""
    bar = shapely.box(0.0, 0.0, 60.0, 6.0)
    places = pack([bar, bar], 70.0, 70.0, 2.0, angle_step=step)
    assert_valid([bar, bar], places, 70.0, 70.0, 2.0, step)


@pytest.mark.parametrize("dims, need", [
    ([(32.0, 24.0), (54.0, 48.0), (28.0, 36.0)], 1),
    ([(52.0, 54.0), (8.0, 44.0), (20.0, 42.0), (48.0, 44.0), (52.0, 36.0), (30.0, 48.0)], 2),
])
def test_blocks_take_the_pages_their_area_needs(dims, need):
    """Blocks on a 100 x 60 area whose area (each grown by the gap) needs ``need`` pages, and
    that fit on that many: in the first set the 54 x 48 block stands upright (48 wide) and the
    others lie one above the other beside it (24 + 2 + 28 <= 60 high, at most 36 <= 50 wide).
    Filling columns from the left (least right edge first) lays the big block flat and needs a
    page more; the packer must find the packing with fewer pages."""
    width, height, gap = 100.0, 60.0, 2.0
    shapes = [shapely.box(0.0, 0.0, max(d), min(d)) for d in dims]
    grown = sum((max(d) + gap) * (min(d) + gap) for d in dims)
    assert -(-grown // ((width + gap) * (height + gap))) == need  # the area bound
    places = pack(shapes, width, height, gap)
    assert_valid(shapes, places, width, height, gap)
    assert max(p.page for p in places) + 1 == need


def test_a_block_larger_than_a_c_shape_goes_into_its_mouth():
    """A C shape 96 x 56 (back 16 wide, arms 6, mouth 80 x 44) all but fills a 100 x 60 area, and a 70 x
    36 block, larger in area than the C, fits its mouth with more than 2 mm to spare: one page. Packed by
    area the block goes first and leaves no room for the C (two pages); the C takes up its hull."""
    width, height, gap = 100.0, 60.0, 2.0
    c_shape = shapely.box(0.0, 0.0, 96.0, 56.0) - shapely.box(16.0, 6.0, 96.0, 50.0)
    block = shapely.box(0.0, 0.0, 70.0, 36.0)
    assert block.area > c_shape.area
    places = pack([block, c_shape], width, height, gap)
    assert_valid([block, c_shape], places, width, height, gap)
    assert {p.page for p in places} == {0}


def test_two_congruent_strips_go_one_by_one_where_their_stack_does_not_fit():
    """A 96 x 76 block stands upright on a 100 x 100 area and leaves a column 22 mm wide; two
    congruent 45 x 12 strips nest into a stack 26 deep, too deep for it, but upright one above
    the other (45 + 2 + 45 <= 100, 76 + 2 + 12 <= 100) they fit: the stack must be halved
    before a page is opened, so one page holds all three."""
    width, height, gap = 100.0, 100.0, 2.0
    block, strip = shapely.box(0.0, 0.0, 96.0, 76.0), shapely.box(0.0, 0.0, 45.0, 12.0)
    shapes = [block, strip, strip]
    places = pack(shapes, width, height, gap, kinds=[0, 1, 1])
    assert_valid(shapes, places, width, height, gap)
    assert {p.page for p in places} == {0}


def test_the_last_pages_piece_packed_first_saves_a_page():
    """Four blocks with a one-page packing, built here by hand: 24 x 54, 37 x 49 and 52 x 31
    (upright) side by side along the bottom (24 + 37 + 31 + 2 x 2 <= 100), 52 x 39 above them
    (54 + 2 + 39 <= 100). Largest first, filling columns from the left or rows from the bottom,
    leaves the 24 x 54 block over for a second page; packed again with that page's piece first
    (as the packer does when its last page is nearly empty), all fit on one."""
    width, height, gap = 100.0, 100.0, 2.0
    dims = [(52.0, 31.0), (37.0, 49.0), (24.0, 54.0), (52.0, 39.0)]
    shapes = [shapely.box(0.0, 0.0, w, h) for w, h in dims]
    by_hand = [Place(0, 90.0, (96.0, 0.0)), Place(0, 0.0, (26.0, 0.0)),
               Place(0, 0.0, (0.0, 0.0)), Place(0, 0.0, (0.0, 56.0))]
    assert_valid(shapes, by_hand, width, height, gap)
    places = pack(shapes, width, height, gap)
    assert_valid(shapes, places, width, height, gap)
    assert {p.page for p in places} == {0}


@pytest.mark.parametrize("cell", [0.75, 1.25])
def test_the_quick_page_test_never_refuses_a_page_a_turn_fits(cell):
    """A page taken everywhere but the mask of a diamond turned by 45 degrees (a square, of fewer
    cells than the diamond's own mask): the piece fits there, so the quick tests (free cells,
    blocks) must not say the page cannot hold it, whichever turn comes first, on a grid of
    cells smaller or larger than a millimetre."""
    from weavecut.papermodel.packing import _best_spot
    from weavecut.papermodel.packing_grid import Options, Page, turned_masks
    gap = 2.0
    diamond = shapely.Polygon([(0.0, -10.0), (10.0, 0.0), (0.0, 10.0), (-10.0, 0.0)])
    turns = turned_masks(diamond, [0.0, 45.0], gap, cell, 100.0, 100.0)  # and 180, 225
    assert [a for a, _, _ in turns] == [0.0, 45.0, 180.0, 225.0]
    assert turns[1][1].sum() < turns[0][1].sum()
    page = Page(60, 60, {})
    page.taken[:] = True
    m = turns[1][1]
    page.taken[5:5 + m.shape[0], 7:7 + m.shape[1]] &= ~m
    page.free = int((~page.taken).sum())
    options = Options(turns)
    (iy, ix), angle, mask, _ = _best_spot(page, options)
    assert angle in (45.0, 225.0)  # the square turns, the diamond's own do not fit
    assert not page.taken[iy:iy + mask.shape[0], ix:ix + mask.shape[1]][mask].any()
    assert page.may_hold(options)
