"""The raster polygon packer: pieces never overlap, stay inside, turn by 15 degree steps and are
never mirrored; congruent pieces nest."""

from __future__ import annotations

import math

import numpy as np
import shapely
import pytest
import shapely.affinity
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.papermodel.packing import nest_offset, pack


def wavy(length: float, width: float = 6.0, amplitude: float = 4.0) -> shapely.Polygon:
    """A zig-zag band along x, like a strip of octagons."""
    x = np.linspace(0.0, length, 9)
    y = amplitude * (np.arange(9) % 2)
    line = shapely.LineString(np.column_stack([x, y]))
    return shapely.buffer(line, width / 2, cap_style="flat", join_style="mitre")


pieces = st.lists(st.tuples(st.floats(10, 120), st.floats(3, 12), st.floats(0, 8)),
                  min_size=1, max_size=12)


@settings(max_examples=15, deadline=None)
@given(pieces)
def test_packed_pieces_are_apart_inside_and_turned_not_mirrored(spec):
    shapes = [wavy(a, b, c) for a, b, c in spec]
    width, height, gap = 150.0, 130.0, 2.0
    places = pack(shapes, width, height, gap)
    moved = []
    for s, p in zip(shapes, places):
        m = p.matrix()
        assert np.linalg.det(m[:2, :2]) > 0.999  # a turn, never a mirror
        assert math.isclose(p.angle % 15.0, 0.0, abs_tol=1e-9)
        g = shapely.transform(s, lambda xy: xy @ m[:2, :2].T + m[:2, 2])
        assert shapely.box(-1e-6, -1e-6, width + 1e-6, height + 1e-6).contains(g)
        assert abs(g.area - s.area) < 1e-6 * s.area
        moved.append((p.page, g))
    for i, (pi, gi) in enumerate(moved):
        for pj, gj in moved[i + 1:]:
            if pi == pj:
                assert gi.distance(gj) >= gap - 1e-9


def test_congruent_strips_nest_and_share_a_page_densely():
    strip = wavy(100.0)
    dx, dy = nest_offset(strip, 2.0)
    assert strip.distance(shapely.transform(strip, lambda xy: xy + (dx, dy))) >= 2.0 - 1e-9
    # nested copies are closer than stacked bounding boxes would be
    assert dy < strip.bounds[3] - strip.bounds[1]
    places = pack([strip] * 8, 190.0, 240.0, 2.0, kinds=[0] * 8)
    assert {p.page for p in places} == {0}
    hull = shapely.convex_hull(shapely.union_all([
        shapely.transform(strip, lambda xy, m=p.matrix(): xy @ m[:2, :2].T + m[:2, 2])
        for p in places]))
    assert 8 * strip.area / hull.area > 0.6


@pytest.mark.parametrize("turn", [0.0, 30.0])
def test_a_piece_goes_into_the_hole_it_fits(turn):
    """A frame filling most of the page holds a hole a little larger than a strip (turned by
    ``turn``): the strip goes into the hole, so one page holds both (a page must not be passed
    over as full while it still has room; the quick page tests only skip pages that cannot hold
    the piece)."""
    strip = shapely.affinity.rotate(shapely.box(0.0, 0.0, 40.0, 8.0), turn, origin="centroid")
    hole = shapely.buffer(strip, 4.5, join_style="mitre")
    frame = shapely.box(*shapely.buffer(hole, 12.0).bounds).difference(hole)
    x0, y0, x1, y1 = frame.bounds
    places = pack([frame, strip], x1 - x0 + 3.0, y1 - y0 + 3.0, 2.0)
    assert [p.page for p in places] == [0, 0]


@settings(max_examples=80, deadline=None)
@given(st.integers(1, 20), st.integers(1, 20), st.integers(0, 12), st.integers(0, 12),
       st.integers(0, 3), st.integers(0, 3), st.sampled_from([1, 2, 3, 4, 8]),
       st.integers(0, 999))
def test_the_block_tests_never_refuse_a_place_that_fits(h, w, y, x, dh, dw, k, seed):
    """A page taken everywhere but a free window (``dh``, ``dw`` cells larger than a mask with
    holes, at any offset): wherever the mask, or the mask turned by half a turn, fits cell by
    cell (checked by brute force), the quick test on k x k blocks leaves the block place of its
    core there; the half-turned mask's core is the one its own mask has."""
    from scipy.signal import correlate2d
    from weavecut.papermodel.packing_grid import Page, block_cores
    page = Page(40, 40, {})
    page.taken[:] = True
    page.taken[y:y + h + dh, x:x + w + dw] = False
    mask = np.random.default_rng(seed).random((h, w)) < 0.8
    mask[0, 0] = mask[-1, -1] = True  # the mask's own size
    cores = block_cores(mask, k)
    own = block_cores(mask[::-1, ::-1], k)[0]
    assert own[1] == cores[1][1] and (own[0] is None) == (cores[1][0] is None)
    assert own[0] is None or np.array_equal(own[0], cores[1][0])
    for m, (core, offset) in zip((mask, mask[::-1, ::-1]), cores):
        at = np.argwhere(correlate2d(page.taken.astype(int), m.astype(int), mode="valid") == 0)
        assert len(at)  # the window holds it
        if core is not None:
            fits = page.fits(k, [core])[0]
            assert all(fits[iy // k + offset[0], ix // k + offset[1]] for iy, ix in at.tolist())


@settings(max_examples=10, deadline=None)
@given(pieces)
def test_the_finer_block_tests_find_the_same_places(spec):
    """Giving up on cell by cell tries at once (the 2 x 2 block test, then the exact
    correlation, take over every time) packs every piece in the same place."""
    import weavecut.papermodel.packing as packing
    shapes = [wavy(a, b, c) for a, b, c in spec]
    quick = pack(shapes, 150.0, 130.0, 2.0)
    tries, packing.TRIES = packing.TRIES, 0
    try:
        assert pack(shapes, 150.0, 130.0, 2.0) == quick
    finally:
        packing.TRIES = tries


def test_fast_fft_sizes_are_scipys():
    from scipy.fft import next_fast_len

    from weavecut.papermodel.packing_grid import fast_len

    assert [fast_len(n) for n in range(1, 3000)] == [next_fast_len(n) for n in range(1, 3000)]


@settings(max_examples=25, deadline=None)
@given(st.floats(5, 60), st.floats(2, 12), st.floats(0, 8), st.floats(0, 2.5),
       st.sampled_from([0.5, 0.75, 1.25]))
def test_a_mask_is_the_cells_whose_centre_lies_in_the_grown_piece(length, width, amplitude,
                                                                  hole, cell):
    """The raster (crossings counted along every row of centres of every turn at once) against
    shapely's own point test: a cell of a turn's mask is taken exactly where its centre lies in
    the piece grown by the mask's reach, turned (a hole in the piece stays a hole where the
    growth leaves one); centres within a micron of an edge are not asked."""
    from weavecut.numeric import affine
    from weavecut.papermodel.packing_grid import turned_masks
    piece = wavy(length, width, amplitude)
    piece = piece.difference(shapely.Point(length / 2, amplitude / 2).buffer(hole, quad_segs=2))
    gap = 2.0
    reach = gap / 2 + cell * math.sqrt(0.5)
    grown = shapely.buffer(piece, reach / math.cos(math.pi / 16), quad_segs=4)
    turns = turned_masks(piece, np.arange(0.0, 360.0, 15.0).tolist(), gap, cell, 500.0, 500.0)
    assert len(turns) == 24
    for angle, mask, origin in turns:
        m = affine(angle)[:2, :2]
        turned = shapely.transform(grown, lambda xy, m=m: xy @ m.T)
        rows, columns = np.indices(mask.shape)
        x, y = origin[0] + (columns + 0.5) * cell, origin[1] + (rows + 0.5) * cell
        inside = shapely.contains_xy(turned, x, y)
        edge = shapely.dwithin(shapely.boundary(turned), shapely.points(x, y), 1e-6)
        assert inside.any()
        np.testing.assert_array_equal(mask[~edge], inside[~edge], err_msg=f"turn {angle}")
