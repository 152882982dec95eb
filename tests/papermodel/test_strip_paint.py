"""What a printed strip shows, recounted tile by tile: its own tiles in its colour, the tiles it
passes under in a tint of the colour on top with that strand's ID, laid flat and walking to
+x; how copies and extras are coloured and named; the small geometric helpers (tint, affine,
arrows, outlines) against hand-computed values."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
import shapely

from tests.meshes import hexagon
from weavecut import inputs
from weavecut.numeric import affine
from weavecut.papermodel.modules import (
    copy_colours,
    copy_family_colours,
    copy_letter,
    orbit_colours,
    plan_modules,
)
from weavecut.papermodel.strip_labels import arrow_polygon
from weavecut.papermodel.strips import (
    Strip,
    build_strips,
    flat_angle,
    model_tiles,
    octagon_size,
    outline_of,
    strip_width,
    tint,
)
from weavecut.papermodel.symmetry import tile_centres
from weavecut.subdivision import subdivide
from weavecut.weave.colour import crossing_pairs, palette
from weavecut.weave.snub_weave import snub_weaves


@lru_cache(maxsize=None)
def weaves(spec: str, levels: int):
    return tuple(snub_weaves(subdivide(hexagon() if spec == "hexagon" else inputs.get(spec),
                                       levels)))


SPECS = [("square-grid:2x2", 2), ("hexagon", 2), ("square-grid:3x2", 2)]


def test_tint_keeps_a_share_of_the_colour_and_fills_the_rest_with_white():
    assert tint("#000000") == "#c7c7c7"  # 255 - 0.22 * 255 = 198.9
    assert tint("#204080", 1.0) == "#204080" and tint("#204080", 0.0) == "#ffffff"
    assert tint("#ff0000", 0.5) == "#ff8080"  # 255 - 0.5 * 255 = 127.5 -> 128


def test_affine_turns_scales_then_shifts():
    m = affine(90.0, (3.0, -2.0), 2.0)
    pts = np.array([[1.0, 0.0], [0.0, 1.0]])
    np.testing.assert_allclose(pts @ m[:2, :2].T + m[:2, 2], [[3.0, 0.0], [1.0, -2.0]],
                               atol=1e-12)
    assert m[2].tolist() == [0.0, 0.0, 1.0]
    np.testing.assert_allclose(affine(), np.eye(3), atol=0)


def test_copy_letters_run_a_to_z_then_aa():
    assert [copy_letter(j) for j in (0, 1, 25, 26, 27, 52)] == ["A", "B", "Z", "AA", "AB", "BA"]


def test_arrow_points_along_its_direction_and_ends_at_its_tip():
    tip, d = np.array([5.0, 2.0]), np.array([0.0, 3.0])  # up, not a unit vector
    arrow = arrow_polygon(tip, d, 4.0)
    coords = np.asarray(arrow.exterior.coords)
    assert arrow.is_valid and arrow.area > 0
    assert coords[:, 1].max() == pytest.approx(2.0) and coords[:, 1].min() == pytest.approx(-2.0)
    np.testing.assert_allclose(coords[np.argmax(coords[:, 1])], tip)
    # symmetric about its shaft; head 0.6 x length wide, shaft 0.24 x length
    assert (coords[:, 0] - 5.0).max() == pytest.approx(1.2)
    assert (coords[:, 0] - 5.0).min() == pytest.approx(-1.2)
    shaft = coords[coords[:, 1] < -1.0]
    assert np.abs(shaft[:, 0] - 5.0).max() == pytest.approx(0.48)
    head, shaft_area = 0.5 * 2.4 * 1.6, 0.96 * 2.4
    assert arrow.area == pytest.approx(head + shaft_area)


def test_outline_joins_tiles_and_drops_holes():
    ring = [shapely.box(0, 0, 3, 1), shapely.box(0, 2, 3, 3), shapely.box(0, 1, 1, 2),
            shapely.box(2, 1, 3, 2)]
    outline = outline_of(np.array(ring, dtype=object), 1e-6)
    assert outline.equals(shapely.box(0, 0, 3, 3)) and not outline.interiors
    corner = np.array([shapely.box(0, 0, 1, 1), shapely.box(1, 1, 2, 2)], dtype=object)
    joined = outline_of(corner, 1e-3)
    assert joined.geom_type == "Polygon" and joined.covers(shapely.Point(0.5, 0.5))
    assert joined.covers(shapely.Point(1.5, 1.5)) and joined.area < 2.01
    apart = np.array([shapely.box(0, 0, 1, 1), shapely.box(3, 0, 5, 1)], dtype=object)
    larger = outline_of(apart, 1e-3)  # the larger piece (grown to join corners)
    assert larger.covers(shapely.box(3, 0, 5, 1)) and larger.area < 2.01


@pytest.mark.parametrize("angle", [0.0, 30.0, 90.0, 135.0, -60.0])
def test_flat_angle_lays_the_long_side_along_x(angle):
    box = shapely.affinity.rotate(shapely.box(0, 0, 10, 2), angle, origin=(0, 0))
    turned = shapely.affinity.rotate(box, flat_angle(box), origin=(0, 0))
    x0, y0, x1, y1 = turned.bounds
    assert x1 - x0 == pytest.approx(10.0) and y1 - y0 == pytest.approx(2.0)


@pytest.mark.parametrize("spec, levels", SPECS)
def test_octagon_size_and_strip_width_measured_per_octagon(spec, levels):
    w = weaves(spec, levels)[-1]
    tiles = model_tiles(w)
    octagons = [t for t in tiles if len(t.exterior.coords) == 9]
    assert octagons
    across = [max(np.hypot(*(a - b)) for a in np.asarray(t.exterior.coords)
                  for b in np.asarray(t.exterior.coords)) for t in octagons]
    assert octagon_size(w) == pytest.approx(float(np.median(across)), rel=1e-12)
    short = []
    for t in octagons:
        rect = np.asarray(t.minimum_rotated_rectangle.exterior.coords)
        short.append(min(np.hypot(*(rect[1] - rect[0])), np.hypot(*(rect[2] - rect[1]))))
    assert strip_width(w) == pytest.approx(float(np.median(short)), rel=1e-9)
    assert 0 < strip_width(w) < octagon_size(w)


@pytest.mark.parametrize("spec, levels", SPECS)
def test_every_strip_tile_shows_its_own_colour_or_a_tint_of_the_strand_on_top(spec, levels):
    w = weaves(spec, levels)[-1]
    plan = plan_modules(w)
    colours = copy_colours(plan, palette("maritime-12"))
    strips = build_strips(w, plan, colours, 25.0, np.arange(w.n_strands))
    tiles = model_tiles(w)
    centres = tile_centres(w)
    for strip in strips:
        s = strip.strand
        assert strip.label == plan.labels[s]
        visits, over = w.strand(s)
        if plan.reversed[s]:
            visits, over = visits[::-1], over[::-1]
        assert strip.over.tolist() == over.tolist()
        for i, (t, o) in enumerate(zip(visits.tolist(), over.tolist())):
            top = int(w.tile_over[t])
            assert strip.names[i] == plan.labels[top]
            assert strip.fills[i] == (colours[s] if o else tint(colours[top]))
            assert top == s if o else top != s
            # the frame puts the model tile onto the printed one, at 25 mm per unit
            placed = shapely.transform(tiles[t], lambda xy: xy @ strip.frame[:2, :2].T
                                       + strip.frame[:2, 2])
            assert shapely.symmetric_difference(placed, strip.tiles[i]).area < 1e-6
        assert np.linalg.det(strip.frame[:2, :2]) == pytest.approx(25.0 ** 2)  # turned, not
        # mirrored; laid flat from the origin, walking to +x
        x0, y0, x1, y1 = strip.outline.bounds
        assert abs(x0) < 1e-9 and abs(y0) < 1e-9 and x1 - x0 >= y1 - y0 - 1e-9
        if len(visits) > 1:
            walk = centres[visits[-1]] - centres[visits[0]]
            assert (walk @ strip.frame[:2, :2].T)[0] >= 0
        assert strip.length == pytest.approx(x1) and strip.width == pytest.approx(y1)
        assert strip.arrow_ink in ("#000000", "#ffffff")


def test_a_copy_keeps_the_shape_and_takes_its_images_colour_and_name():
    w = weaves("square-grid:2x2", 2)[-1]
    plan = plan_modules(w)
    colours = copy_family_colours(w, plan, palette("maritime-12"))
    module = plan.copies[0]
    first = build_strips(w, plan, colours, 20.0, module)
    for j in range(1, plan.k):
        copy = build_strips(w, plan, colours, 20.0, module, j)
        for a, b, s in zip(first, copy, plan.copies[j].tolist()):
            assert b.strand == s and b.label == plan.labels[s]
            assert shapely.symmetric_difference(a.outline, b.outline).area < 1e-6
            assert b.fills[0] == colours[s] if b.over[0] else True
            # the copy's frame puts strand s's own tiles in place
            visits, _ = w.strand(s)
            tiles = model_tiles(w)[visits]
            placed = shapely.transform(b.outline, lambda xy: (xy - b.frame[:2, 2])
                                       @ np.linalg.inv(b.frame[:2, :2]).T)
            assert shapely.difference(placed, shapely.buffer(shapely.union_all(tiles),
                                                             1e-6)).area < 1e-6
    names = build_strips(w, plan, colours, 20.0, module, 1, tuple("n%d" % s for s in
                                                                  range(w.n_strands)))
    assert [s.label for s in names] == ["n%d" % s for s in plan.copies[1].tolist()]


def test_strip_moved_turns_everything_with_it():
    w = weaves("square-grid:2x2", 2)[-1]
    plan = plan_modules(w)
    strip = build_strips(w, plan, copy_colours(plan, palette("maritime-12")), 20.0,
                         plan.copies[0][:1])[0]
    m = affine(90.0, (100.0, 5.0))
    moved = strip.moved(m, 90.0)
    np.testing.assert_allclose(moved.frame, m @ strip.frame)
    x0, y0, x1, y1 = moved.outline.bounds
    assert (x1 - x0, y1 - y0) == pytest.approx((strip.width, strip.length))
    assert x1 == pytest.approx(100.0) and y0 == pytest.approx(5.0)
    assert isinstance(moved, Strip) and moved.glue is None
    assert all(shapely.symmetric_difference(a, shapely.affinity.affine_transform(
        b, [0, -1, 1, 0, 100, 5])).area < 1e-9 for a, b in zip(moved.tiles, strip.tiles))


@pytest.mark.parametrize("spec, levels", SPECS)
def test_copy_colours_one_per_copy_extras_last(spec, levels):
    w = weaves(spec, levels)[-1]
    plan = plan_modules(w)
    flat = palette("maritime-4").flat
    colours = copy_colours(plan, palette("maritime-4"))
    for j in range(plan.k):
        assert {colours[s] for s in plan.copies[j].tolist()} == {flat[j % len(flat)]}
    assert {colours[s] for s in plan.extras.tolist()} <= {flat[-1]}


@pytest.mark.parametrize("spec, levels", SPECS)
def test_copy_family_colours_tell_copies_apart_or_crossings(spec, levels):
    w = weaves(spec, levels)[-1]
    plan = plan_modules(w)
    pal = palette("maritime-12")
    colours = copy_family_colours(w, plan, pal)
    fams = pal.families
    if plan.k >= 3:
        for j, row in enumerate(plan.copies.tolist()):
            assert [colours[s] for s in row] == [fams[j % len(fams)][i % len(fams[j % len(fams)])]
                                                 for i in range(len(row))]
        fam = fams[plan.k % len(fams)]
        assert [colours[s] for s in plan.extras.tolist()] == [fam[i % len(fam)] for i in
                                                               range(len(plan.extras))]
    else:
        assert len(plan.extras) and all(c in pal.flat for c in colours)
        for a, b in crossing_pairs(w).tolist():
            assert colours[a] != colours[b]


@pytest.mark.parametrize("spec, levels", SPECS)
def test_orbit_colours_are_the_same_for_every_copy_and_differ_where_strands_cross(spec, levels):
    ws = list(weaves(spec, levels))
    plan = plan_modules(ws[-1])
    for name in ("maritime-12", "maritime-4"):
        pal = palette(name)
        colours = orbit_colours(ws, plan, pal)
        cols = np.array(colours)
        assert (cols[plan.copies] == cols[plan.copies[:1]]).all()
        assert set(colours) <= set(pal.flat)
        if not pal.shaded:  # flat: a greedy colouring over module columns and extras
            node = {}
            for j in range(plan.k):
                for i, s in enumerate(plan.copies[j].tolist()):
                    node[s] = i
            for i, s in enumerate(plan.extras.tolist()):
                node[s] = 1000 + i
            for a, b in crossing_pairs(ws[-1]).tolist():
                if node[a] != node[b]:
                    assert colours[a] != colours[b], (a, b)
        else:  # shaded: module strands with one parent share a family, in turn its shades
            fam = {c: f for f, shades in enumerate(pal.families) for c in shades}
            parent = ws[-1].parent_strand
            by_parent: dict[int, list] = {}
            for s in plan.copies[0].tolist():
                if parent[s] >= 0:
                    by_parent.setdefault(int(parent[s]), []).append(colours[s])
            for cs in by_parent.values():
                assert len({fam[c] for c in cs}) == 1
                shades = pal.families[fam[cs[0]]]
                assert cs == [shades[i % len(shades)] for i in range(len(cs))]


@pytest.mark.parametrize("spec, levels", SPECS)
def test_plan_names_copies_numbers_across_and_turns_every_copy_with_its_module(spec, levels):
    w = weaves(spec, levels)[-1]
    heading = -np.pi / 2
    plan = plan_modules(w, heading)
    for j, row in enumerate(plan.copies.tolist()):
        assert [plan.labels[s] for s in row] == [f"{copy_letter(j)}{i + 1}"
                                                 for i in range(len(row))]
    assert [plan.labels[s] for s in plan.extras.tolist()] == [
        f"X{i + 1}" for i in range(len(plan.extras))]
    centres = tile_centres(w)

    def printed(s):  # start-to-end direction as printed
        visits, _ = w.strand(s)
        visits = visits[::-1] if plan.reversed[s] else visits
        return centres[visits[-1]] - centres[visits[0]]

    # numbered left to right across the heading (heading down: left is -x)
    mids = [centres[w.strand(s)[0]].mean(axis=0)[0] for s in plan.copies[0].tolist()]
    assert np.all(np.diff(np.round(mids, 6)) >= 0)
    sym = plan.symmetry
    for j in range(plan.k):
        c, s_ = np.cos(j * sym.angle), np.sin(j * sym.angle)
        for a, b in zip(plan.copies[0].tolist(), plan.copies[j].tolist()):
            da = printed(a)
            np.testing.assert_allclose(printed(b), [c * da[0] - s_ * da[1],
                                                    s_ * da[0] + c * da[1]], atol=1e-6)
        for a in plan.copies[0].tolist():  # module strands head near the heading
            d = printed(a)
            assert np.cos(np.arctan2(d[1], d[0]) - heading) >= np.cos(np.pi / plan.k) - 1e-9
