"""Work shared or skipped for speed gives what the plain way gives: congruent strips labelled
together as each alone, fits in one batch as one by one, strips moved together as one by one,
a spot skipped only where the text cannot fit, obstacles indexed as tested one by one, a plate's
search skipped only where it finds nothing, a best spot remembered as found again."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.papermodel.test_strip_paint import weaves
from weavecut.layout.labels import MIN_CAP, largest_fit, unit_boxes
from weavecut.numeric import affine
from weavecut.papermodel import book
from weavecut.papermodel.assembly import Obstacles
from weavecut.papermodel.modules import book_colours, plan_modules
from weavecut.papermodel.pages import PageArea
from weavecut.papermodel.plates import free_spot, search_spot
from weavecut.papermodel.strip_labels import _fit_text, _may_reach, label_strips
from weavecut.papermodel.strips import GEOMETRY, moved_strips
from weavecut.weave.colour import palette


@lru_cache(maxsize=None)
def unlabelled():
    """(strips, tile size): the square grid 2 x 2's strips at the size where four end strips
    carry their IDs on tabs, before labelling."""
    w = weaves("square-grid:2x2", 2)
    plan = plan_modules(w[-1])
    colours = book_colours(list(w), plan, palette("maritime-12"), "mixed")
    size = book.strip_need(w[-1])
    keep = book.label_strips
    book.label_strips = lambda strips, tile_mm: strips
    try:
        strips, _ = book.labelled_pieces(w[-1], plan, colours, size, "mixed",
                                         PageArea(210.0, 297.0, 10.0, None))
    finally:
        book.label_strips = keep
    return tuple(strips), size


def same(a, b) -> bool:
    """Two strips alike field by field (shapes coordinate for coordinate)."""
    for name, x in vars(a).items():
        y = getattr(b, name)
        if name in GEOMETRY:
            x, y = (None if v is None else shapely.to_wkb(np.atleast_1d(v)).tolist()
                    for v in (x, y))
        elif isinstance(x, np.ndarray):
            x, y = x.tolist(), y.tolist()
        if x != y:
            return False
    return True


def test_congruent_strips_are_labelled_as_each_alone():
    """Copies of a module strip share their label regions, neighbourhoods and tabs: labelled
    together, every strip gets what it gets labelled alone (where nothing is shared)."""
    strips, size = unlabelled()
    together = label_strips(list(strips), size)
    alone = [label_strips([s], size)[0] for s in strips]
    shapes = [shapely.to_wkb(s.outline) for s in strips]
    assert len(set(shapes)) < len(shapes)  # congruent strips are there
    tabbed = [s for s in together if s.flap is not None]
    assert len({t.texts[0].text for t in tabbed}) > 1  # tabs, for different IDs
    assert all(same(a, b) for a, b in zip(together, alone))


def test_strips_moved_together_as_one_by_one():
    """Every strip through its own turn and shift in one transform: the same shapes, frames
    and texts (upright, half-turned ones too) as moving each alone."""
    strips, size = unlabelled()
    strips = label_strips(list(strips), size)
    rng = np.random.default_rng(3)
    turns = rng.choice([0.0, 15.0, 90.0, 180.0, 225.0, 270.0], len(strips))
    matrices = [affine(a, rng.uniform(-50, 150, 2)) for a in turns]
    together = moved_strips(strips, matrices, turns)
    assert all(same(a, moved_strips([s], [m], [t])[0])
               for a, s, m, t in zip(together, strips, matrices, turns))
    assert any(t.angle != u.angle for s, m in zip(together, strips) for t, u in
               zip(s.texts, m.texts))


def band(points):
    """A wavy band 4 mm wide along ``points`` (a repeated point is dropped)."""
    points = [p for i, p in enumerate(points) if i == 0 or p != points[i - 1]]
    if len(points) < 2:
        return shapely.Point(points[0]).buffer(2.0, quad_segs=2)
    return shapely.buffer(shapely.LineString(points), 2.0, quad_segs=2)


polygons = st.lists(st.tuples(st.floats(-8, 8), st.floats(-8, 8)), min_size=2, max_size=6).map(
    band)


@settings(max_examples=40, deadline=None)
@given(st.lists(polygons, min_size=1, max_size=3), st.data())
def test_fits_in_one_batch_as_one_by_one(regions, data):
    """Fits sharing a region and a centre (a text's turns) share the edges' nearest points:
    the batch answers each fit as it is answered alone."""
    n = data.draw(st.integers(1, 12))
    which = data.draw(st.lists(st.integers(0, len(regions) - 1), min_size=n, max_size=n))
    centres = np.array(data.draw(st.lists(st.sampled_from([(0.0, 0.0), (1.5, -0.5), (-3, 2)]),
                                          min_size=n, max_size=n)))
    texts = data.draw(st.lists(st.sampled_from(["A1", "B27", "2/3", "glue"]), min_size=n,
                               max_size=n))
    angles = data.draw(st.lists(st.sampled_from([0.0, 15.0, 45.0, 90.0, 165.0]), min_size=n,
                                max_size=n))
    regs = np.array([regions[i] for i in which], dtype=object)
    shapes = unit_boxes(texts, angles)
    batch = largest_fit(regs, shapes, centres, 0.2, 4.0)
    each = [largest_fit(regs[i:i + 1], shapes[i:i + 1], centres[i:i + 1], 0.2, 4.0)[0]
            for i in range(n)]
    np.testing.assert_array_equal(batch, each)


@settings(max_examples=60, deadline=None)
@given(polygons, st.lists(st.tuples(st.floats(-10, 10), st.floats(-10, 10)), min_size=1,
                          max_size=8), st.sampled_from(["1", "A1", "B27", "X12 2/3"]))
def test_a_spot_is_skipped_only_where_the_text_cannot_fit(region, spots, text):
    """The quick test that skips a cramped label's spot never skips one where the text
    reaches ``MIN_CAP`` (at any of its turns)."""
    spots = np.array(spots)
    of = np.zeros(len(spots), dtype=np.int64)
    hope = _may_reach(np.array([region], dtype=object), of, spots, [text] * len(spots), MIN_CAP)
    size, _ = _fit_text(np.full(len(spots), region, dtype=object), spots, [text] * len(spots),
                        MIN_CAP)
    assert (size[~hope] < MIN_CAP - 1e-9).all()


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(0, 50), st.floats(0, 50), st.floats(0.5, 6)), min_size=1,
                max_size=40), st.integers(0, 99))
def test_obstacles_answer_as_tested_one_by_one(boxes, seed):
    """Obstacles added one at a time, asked in between (an index made now and then, the newest
    tested one by one): each answer is whether the shape touches any obstacle so far."""
    rng = np.random.default_rng(seed)
    obstacles = Obstacles()
    for x, y, r in boxes:
        obstacles += [shapely.box(x, y, x + r, y + r)]
        probe = shapely.box(*(rng.uniform(0, 50, (5, 2)).T),
                            *(rng.uniform(0, 50, (5, 2)) + 2.0).T)
        brute = shapely.intersects(probe[:, None], np.array(obstacles)[None, :]).any(axis=1)
        np.testing.assert_array_equal(obstacles.hits(probe), brute)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(-30, 30), st.floats(-30, 30), st.floats(0.5, 12),
                          st.floats(0.5, 12), st.booleans()), max_size=30),
       st.tuples(st.floats(-5, 5), st.floats(-5, 5)), st.sampled_from([0, 1, 2, 3]))
def test_a_plate_search_is_skipped_only_where_it_finds_nothing(boxes, at, touch):
    """A plate's spot round ``at`` is what trying every spot gives, also where ``at`` lies on
    an obstacle's corner or edge (touch 1, 2) or 0.2 mm off one (3), inside one or clear of all
    (boxes and the thick lines leaders leave)."""
    obstacles = [shapely.box(x, y, x + w, y + h) if box else
                 shapely.buffer(shapely.LineString([(x, y), (x + w, y - h)]), 0.3)
                 for x, y, w, h, box in boxes]
    if touch:
        off = 0.2 if touch == 3 else 0.0
        obstacles.append(shapely.box(at[0] - 3.0 * (touch == 2), at[1] + off, at[0] + 3.0,
                                     at[1] + off + 2.0))
    frame = shapely.box(-50, -50, 50, 50)
    quick = free_spot(at, "A1", obstacles, frame, 5.0)
    full = search_spot(at, "A1", obstacles, frame, 5.0)
    assert (quick is None) == (full is None)
    if full is not None:
        assert shapely.equals_exact(quick[1], full[1], 0.0)
        assert shapely.equals_exact(quick[2], full[2], 0.0)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.lists(st.tuples(st.integers(0, 2), st.integers(0, 1),
                                                     st.booleans()), min_size=1, max_size=8))
def test_a_remembered_best_spot_is_the_one_found_again(seed, asks):
    """Stacks (one of three) asked for along an axis (each way to a spot of its own) on a page
    that fills up, some asked again on the same cells: the spot remembered is the one a fresh
    search finds."""
    from weavecut.papermodel.packing import _best_spot, _spot
    from weavecut.papermodel.packing_grid import Options, Page, turned_masks
    rng = np.random.default_rng(seed)
    pieces = [shapely.box(0, 0, 30, 6), shapely.box(0, 0, 12, 12),
              shapely.Polygon([(0, 0), (25, 0), (0, 9)])]
    options = [Options(turned_masks(p, [0.0, 45.0, 90.0, 135.0], 2.0, 1.0, 80.0, 60.0))
               for p in pieces]
    page, spots = Page(60, 80, {}), {}
    page.taken[:] = rng.random(page.taken.shape) < 0.002
    page.taken[:30, :40] = True  # the least right edge is up the left, the least top right
    for kind, axis, lay in asks:
        got = _spot(page, options[kind], (kind, 1), axis, spots)
        twin = Page(60, 80, {})
        twin.taken[:] = page.taken  # the same cells, asked afresh
        want = _best_spot(twin, options[kind], axis)
        assert (got is None) == (want is None)
        if want is not None:
            assert got[:2] == want[:2] and (got[2] == want[2]).all()
            if lay:
                page.add(got[2], *got[0])


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from([2, 4, 8]), st.floats(0.2, 0.8))
def test_a_finer_test_read_directly_agrees_with_the_fft(seed, k, share):
    """The blocks under a core read at given places say what the FFT correlation says there
    (and nothing elsewhere), on a page with odd edges."""
    from weavecut.papermodel.packing_grid import Page, block_cores
    rng = np.random.default_rng(seed)
    page = Page(int(rng.integers(20, 60)), int(rng.integers(20, 60)), {})
    page.taken[:] = rng.random(page.taken.shape) < share
    mask = rng.random((int(rng.integers(3, 19)), int(rng.integers(3, 19)))) < 0.9
    for core, _ in block_cores(mask, k):
        if core is None:
            continue
        fft = page.fits(k, [core])[0]
        rows = rng.integers(-2, fft.shape[0] + 2, 50)
        columns = rng.integers(-2, fft.shape[1] + 2, 50)
        direct = page.fits_at(k, core, rows, columns)
        inside = (rows >= 0) & (columns >= 0) & (rows < fft.shape[0]) & (columns < fft.shape[1])
        expect = np.zeros_like(fft)
        expect[rows[inside], columns[inside]] = fft[rows[inside], columns[inside]]
        np.testing.assert_array_equal(direct, expect)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(st.floats(-50, 50), st.floats(-50, 50), st.floats(1, 9),
                          st.booleans()), min_size=1, max_size=12))
def test_polygons_from_shapely_read_ring_by_ring(specs):
    """Every ring of every polygon, read at once, is the ring read one by one: exterior
    counter-clockwise then holes clockwise, the closing corner dropped, in order."""
    from weavecut.layout.drawing import polygons_from_shapely
    shapes = [shapely.Point(x, y).buffer(r, quad_segs=3).difference(
        shapely.Point(x, y).buffer(r / 2, quad_segs=2)) if hole
        else shapely.box(x, y, x + r, y + r / 3) for x, y, r, hole in specs]
    got = polygons_from_shapely(shapes, fills=["#ffffff"] * len(shapes))
    rings, counts = [], []
    for g in shapes:
        g = shapely.orient_polygons(g)
        parts = [g.exterior, *g.interiors]
        rings += [np.asarray(p.coords)[:-1] for p in parts]
        counts.append(len(parts))
    np.testing.assert_array_equal(got.coords, np.concatenate(rings))
    np.testing.assert_array_equal(got.ring_offsets, np.cumsum([0] + [len(r) for r in rings]))
    np.testing.assert_array_equal(got.polygon_offsets, np.cumsum([0] + counts))
