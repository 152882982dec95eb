"""The frame split into dovetailed parts, checked from the parts' geometry: they tile the frame,
are numbered counter-clockwise so that F1 joins F2 and the last joins F1, each join is a
dovetail (longer than the straight cut across the band, with a tab that widens into the next
part), and a frame that fits stays whole. ``fits`` against rectangles whose size is known."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely import affinity

from weavecut.errors import WeaveCutError
from weavecut.puzzle.frame import MAX_PARTS, _parts, _ray, fits, split_frame

from tests.built_puzzles import pentagon_puzzle


def _puzzle():
    return pentagon_puzzle(2, 400.0)


def _shared(a, b):
    """The border two parts share (lines only)."""
    return shapely.intersection(shapely.buffer(a.boundary, 1e-6), b.boundary)


@pytest.mark.parametrize("sheet", [(380.0, 280.0), (300.0, 200.0), (220.0, 160.0)])
def test_parts_tile_the_frame_counter_clockwise_joined_by_dovetails(sheet):
    puzzle = _puzzle()
    frame = puzzle.frame
    parts = split_frame(frame, puzzle.outer, sheet, 5.0, 0.2)
    n = len(parts)
    assert 2 <= n <= MAX_PARTS
    assert all(p.geom_type == "Polygon" and p.is_valid and not p.interiors for p in parts)
    assert shapely.area(parts).sum() == pytest.approx(frame.area, rel=1e-9)
    assert shapely.symmetric_difference(shapely.union_all(parts), frame).area < 1e-6
    assert fits(shapely.buffer(parts, 0.1, join_style="mitre"), sheet, 5.0).all()
    # numbered counter-clockwise round the outline's centroid
    centre = np.asarray(puzzle.outer.centroid.coords[0])
    angle = np.unwrap([np.arctan2(*(np.asarray(p.centroid.coords[0]) - centre)[::-1])
                       for p in parts])
    assert (np.diff(angle) > 0).all() and angle[-1] - angle[0] < 2 * np.pi
    for k in range(n):
        a, b = parts[k], parts[(k + 1) % n]
        border = shapely.line_merge(_shared(a, b))
        assert border.length > 0, f"F{k + 1} does not join F{(k + 1) % n + 1}"
        ends = shapely.get_coordinates(shapely.boundary(border)) if border.geom_type == \
            "LineString" else shapely.get_coordinates(border)[[0, -1]]
        straight = float(np.hypot(*(ends[0] - ends[-1])))
        assert border.length > 1.5 * straight  # a tab, not a straight cut across the band
        # parts that are not neighbours do not touch along a line
        for m in range(n):
            if m not in (k, (k + 1) % n) and n > 3:
                assert _shared(a, parts[m]).length < 1e-6 or _shared(b, parts[m]).length < 1e-6


def test_a_frame_that_fits_stays_whole_and_one_that_never_fits_is_refused():
    puzzle = _puzzle()
    whole = split_frame(puzzle.frame, puzzle.outer, (800.0, 800.0), 5.0, 0.2)
    assert len(whole) == 1 and whole[0] is puzzle.frame
    # as cut, grown by kerf / 2: a sheet that holds the frame but not the frame grown by a
    # kerf of 2 mm splits it
    x0, y0, x1, y1 = puzzle.frame.bounds
    snug = (x1 - x0 + 10.5, y1 - y0 + 10.5)
    assert fits(np.array([puzzle.frame], dtype=object), snug, 5.0).all()
    assert len(split_frame(puzzle.frame, puzzle.outer, snug, 5.0, 0.0)) == 1
    assert len(split_frame(puzzle.frame, puzzle.outer, snug, 5.0)) == 1  # no kerf unless given
    assert len(split_frame(puzzle.frame, puzzle.outer, snug, 5.0, 2.0)) > 1
    with pytest.raises(WeaveCutError, match=r"^even in 12 parts the frame does not fit a 40 x "
                                            r"30 mm sheet; use a larger --sheet or a smaller "
                                            r"--size$"):
        split_frame(puzzle.frame, puzzle.outer, (40.0, 30.0), 5.0, 0.2)


@pytest.mark.parametrize("angle", [0.0, 30.0, 90.0, 137.0])
def test_fits_lays_a_part_flat_on_its_minimum_rectangle(angle):
    """A 100 x 20 mm bar at any angle fits a sheet whose room (less the margin on both sides)
    is at least 100 x 20, and not one that is short of it by a tenth in either direction."""
    bar = affinity.rotate(shapely.box(0.0, 0.0, 100.0, 20.0), angle, origin=(37.0, -5.0))
    part = np.array([bar], dtype=object)
    assert fits(part, (110.0, 30.0), 5.0).all()
    assert fits(part, (100.0 + 10.0, 20.0 + 10.0), 5.0).all()
    assert not fits(part, (109.9, 30.0), 5.0).any()
    assert not fits(part, (110.0, 29.9), 5.0).any()
    assert not fits(part, (110.0, 30.0), 5.1).any()
    several = np.array([bar, shapely.box(0, 0, 10, 10), shapely.box(0, 0, 200, 5)], dtype=object)
    assert fits(several, (110.0, 30.0), 5.0).tolist() == [True, True, False]


@pytest.mark.parametrize("angle", [0.3, 1.9, 4.0])
def test_each_cut_carries_a_symmetric_dovetail_that_widens(angle):
    """The cut along a ray: from the centre out, a tab of four corners, then on: the neck's
    two corners on the ray, the head's two off it by the same depth, the head wider than the
    neck and centred on the neck's middle (a dovetail locks only if it widens both ways)."""
    puzzle = _puzzle()
    centre = np.asarray(puzzle.outer.centroid.coords[0])
    cut = _ray(puzzle.frame, centre, angle, 1000.0)
    assert cut is not None and len(cut) == 6
    u = np.array([np.cos(angle), np.sin(angle)])
    n = np.array([-u[1], u[0]])
    along, off = (cut - centre) @ u, (cut - centre) @ n
    np.testing.assert_allclose(off[[0, 1, 4, 5]], 0.0, atol=1e-9)
    assert abs(off[2]) > 0 and off[2] == pytest.approx(off[3], abs=1e-9)
    neck, head = along[4] - along[1], along[3] - along[2]
    assert 0 < neck < head
    assert (along[2] + along[3]) / 2 == pytest.approx((along[1] + along[4]) / 2, abs=1e-9)


def _no_fewer_parts_fit(puzzle, sheet, kerf, n):
    """No split into fewer than ``n`` parts fits ``sheet``: not the whole frame, and no ray
    count below ``n`` from any start split_frame offers (each side's midpoint, each corner)."""
    grown = shapely.buffer(np.array([puzzle.frame], dtype=object), kerf / 2, join_style="mitre")
    assert not fits(grown, sheet, 5.0).any()
    centre = np.asarray(puzzle.outer.centroid.coords[0])
    corners = np.asarray(puzzle.outer.exterior.coords)[:-1]
    through = np.concatenate([(corners + np.roll(corners, -1, axis=0)) / 2, corners]) - centre
    for k in range(2, n):
        for start in np.arctan2(through[:, 1], through[:, 0]):
            fewer = _parts(puzzle.frame, centre, start + 2 * np.pi * np.arange(k) / k)
            assert fewer is None or not fits(shapely.buffer(fewer, kerf / 2, join_style="mitre"),
                                             sheet, 5.0).all(), (k, start)


@pytest.mark.slow
def test_a_frame_that_needs_the_most_parts_is_split_into_them():
    """On a 156 x 117 mm sheet the 400 mm pentagon's frame fits in no fewer than MAX_PARTS
    parts; split_frame still finds the split, and every part fits the sheet as cut (grown by
    kerf / 2)."""
    puzzle = _puzzle()
    sheet, kerf = (156.0, 117.0), 0.2
    parts = split_frame(puzzle.frame, puzzle.outer, sheet, 5.0, kerf)
    assert len(parts) == MAX_PARTS
    assert fits(shapely.buffer(parts, kerf / 2, join_style="mitre"), sheet, 5.0).all()
    assert shapely.symmetric_difference(shapely.union_all(parts), puzzle.frame).area < 1e-6
    _no_fewer_parts_fit(puzzle, sheet, kerf, MAX_PARTS)
    # a sheet a little smaller needs more: MAX_PARTS + 1 parts would fit it, but the split
    # stops at MAX_PARTS and refuses
    small = (150.0, 112.5)
    centre = np.asarray(puzzle.outer.centroid.coords[0])
    k = MAX_PARTS + 1
    more = _parts(puzzle.frame, centre, 0.0 + 2 * np.pi * np.arange(k) / k)
    assert fits(shapely.buffer(more, kerf / 2, join_style="mitre"), small, 5.0).all()
    with pytest.raises(WeaveCutError, match=rf"^even in {MAX_PARTS} parts the frame"):
        split_frame(puzzle.frame, puzzle.outer, small, 5.0, kerf)


def test_fits_allows_a_nanometre_over_the_room_and_no_more():
    """The room is the sheet less the margin on both sides, plus 1e-9 mm for rounding: a part
    exactly that wide (or high) fits, one a float step over it does not."""
    wide, high = 110.0 - 2 * 5.0 + 1e-9, 30.0 - 2 * 5.0 + 1e-9
    exact = np.array([shapely.box(0.0, 0.0, wide, 20.0), shapely.box(0.0, 0.0, 100.0, high)],
                     dtype=object)
    assert fits(exact, (110.0, 30.0), 5.0).tolist() == [True, True]
    over = np.array([shapely.box(0.0, 0.0, np.nextafter(wide, np.inf), 20.0),
                     shapely.box(0.0, 0.0, 100.0, np.nextafter(high, np.inf))], dtype=object)
    assert fits(over, (110.0, 30.0), 5.0).tolist() == [False, False]


def _crossings(parts, outer):
    """Where the cuts between neighbouring parts meet the outer outline, counter-clockwise."""
    rim = shapely.buffer(outer.exterior, 1e-6)
    ends = [shapely.centroid(g) for a, b in zip(parts, np.roll(parts, -1))
            for g in shapely.get_parts(shapely.intersection(_shared(a, b), rim))]
    xy = np.unique(np.round(shapely.get_coordinates(ends), 5), axis=0)
    centre = np.asarray(outer.centroid.coords[0])
    return xy[np.argsort(np.arctan2(*(xy - centre).T[::-1]))]


@pytest.mark.parametrize("sheet, n", [((420.0, 300.0), 2), ((380.0, 280.0), 3), ((300.0, 200.0), 4)])
def test_cuts_are_equally_spaced_rays_one_through_a_side_midpoint(sheet, n):
    """The fewest parts that fit (two on a sheet that holds half the frame), cut along rays
    that leave the frame at points of its outline at equal angles round the centre, one of
    them a side's midpoint."""
    puzzle = _puzzle()
    outer = puzzle.outer
    parts = split_frame(puzzle.frame, outer, sheet, 5.0, 0.2)
    assert len(parts) == n
    _no_fewer_parts_fit(puzzle, sheet, 0.2, n)
    centre = np.asarray(outer.centroid.coords[0])
    ends = _crossings(parts, outer)
    angle = np.arctan2(*(ends - centre).T[::-1])  # ascending: _crossings sorts them
    np.testing.assert_allclose(np.diff(np.r_[angle, angle[0] + 2 * np.pi]),
                               2 * np.pi / len(parts), atol=1e-6)
    # the cuts through a side's midpoint (the shortest across the band) come first: the
    # pentagon's frame splits that way on these sheets
    corners = np.asarray(outer.exterior.coords)[:-1]
    mids = (corners + np.roll(corners, -1, axis=0)) / 2
    assert len(ends) == len(parts)
    assert np.hypot(*(ends[:, None] - mids[None]).transpose(2, 0, 1)).min() < 1e-4


def test_a_moved_frame_splits_into_the_moved_parts():
    """The split depends on the frame's shape, not on where it lies: moved 5 m away, the same
    parts, moved."""
    puzzle = _puzzle()
    parts = split_frame(puzzle.frame, puzzle.outer, (300.0, 200.0), 5.0, 0.2)
    far = [affinity.translate(g, 5000.0, -3000.0) for g in (puzzle.frame, puzzle.outer)]
    moved = split_frame(*far, (300.0, 200.0), 5.0, 0.2)
    assert len(moved) == len(parts)
    for a, b in zip(parts, moved):
        assert shapely.hausdorff_distance(affinity.translate(a, 5000.0, -3000.0), b) < 1e-6


@pytest.mark.parametrize("angle", [0.3, 1.9, 4.0])
def test_a_dovetail_sticks_out_towards_the_next_part_where_it_fits(angle):
    """A tab leaves the part before the ray for the next one (counter-clockwise, to the left of
    the ray) where one fits there, as it does at these angles: inside the frame with a wall
    of frame around it."""
    puzzle = _puzzle()
    centre = np.asarray(puzzle.outer.centroid.coords[0])
    cut = _ray(puzzle.frame, centre, angle, 1000.0)
    u = np.array([np.cos(angle), np.sin(angle)])
    left = (cut[2:4] - centre) @ np.array([-u[1], u[0]])
    assert (left > 0).all()
    assert puzzle.frame.contains(shapely.Polygon(cut[1:5]))


@pytest.mark.parametrize("angle", [0.0, 1.0, 2.0, 4.5])
def test_a_ray_across_two_bands_of_frame_carries_its_tab_in_the_outer_one(angle):
    """Two rings (10-20 and 30-40 mm round a centre far from the origin) joined by a bridge
    on the far side: a ray from the centre crosses both, and its dovetail sits in the outer
    band, whole (from the centre out: the neck's corners on the ray at 30-40 mm)."""
    centre = np.array([-300.0, 800.0])

    def ring(r0, r1):
        disc = shapely.Point(centre)
        return shapely.difference(disc.buffer(r1, 256), disc.buffer(r0, 256))

    bridge = shapely.box(centre[0] - 45, centre[1] - 2, centre[0] - 5, centre[1] + 2)
    frame = shapely.union_all([ring(10, 20), ring(30, 40), bridge])
    cut = _ray(frame, centre, angle, 1000.0)
    u = np.array([np.cos(angle), np.sin(angle)])
    along = (cut[1:5] - centre) @ u
    assert 30 < along.min() and along.max() < 40
    assert frame.contains(shapely.Polygon(cut[1:5]))


def test_a_frame_that_falls_apart_in_every_split_is_refused():
    """Every part is one piece. Two rings joined by one bridge fall apart under any split (a
    wedge without the bridge holds an arc of each ring, apart), so on a sheet too small for
    the whole frame it is refused rather than cut into loose pieces."""
    def ring(r0, r1):
        return shapely.difference(shapely.Point(0, 0).buffer(r1, 16),
                                  shapely.Point(0, 0).buffer(r0, 16))

    frame = shapely.union_all([ring(10, 20), ring(30, 40), shapely.box(-45, -2, -5, 2)])
    assert frame.geom_type == "Polygon"
    with pytest.raises(WeaveCutError, match=r"^even in 12 parts the frame does not fit"):
        split_frame(frame, shapely.box(-40, -40, 40, 40), (70.0, 50.0), 1.0)
