"""The callouts of crossings the strips cannot name, checked on the small square grid (k = 4)
with hand-picked crossings: which tiles are called out in each layout, where the dot goes, how
the dot looks, and that the pattern on the crossing pages keeps clear of the callout columns."""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np
import pytest
import shapely

from weavecut import inputs
from weavecut.layout.contrast import MIN_CONTRAST, contrast_ratio
from weavecut.layout.drawing import Polygons, Polylines
from weavecut.papermodel.assembly import _crossing_spot
from weavecut.papermodel.crossings import (
    CASING,
    DOT,
    callout_shapes,
    column_callouts,
    crossing_pages,
    left_out_crossings,
)
from weavecut.papermodel.pages import GAP, PageArea
from weavecut.papermodel.modules import copy_colours, plan_modules
from weavecut.papermodel.strips import build_strips
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves


def grid():
    """(weave, plan, colours) of the square grid 2 x 2 at level 2 (4 copies of 6 strands)."""
    weave = snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2))[-1]
    plan = plan_modules(weave)
    return weave, plan, copy_colours(plan, palette("maritime-4"))


def weave_tiles(weave, plan, strand: int, copy: int, indices) -> list[int]:
    """The weave's tiles that tiles ``indices`` of copy ``copy``'s print of module strand
    ``strand`` stand for: the strand's visits in the order its strip reads, turned j times."""
    visits, _ = weave.strand(strand)
    if plan.reversed[strand]:
        visits = visits[::-1]
    return plan.symmetry.tile_powers()[copy, visits[list(indices)]].tolist()


def test_left_out_crossings_are_named_once_per_copy_only_in_the_module_layout():
    """A module print (one per copy) that leaves two under tiles unnamed leaves them unnamed on
    every copy: the crossings are those tiles' orbits, a set the pattern's turns map onto
    itself. In the mixed layout every strip is its own print: the crossings are exactly the
    tiles its pieces leave unnamed (here on copies A and B), each with the strand on top there
    and the piece's strand below."""
    weave, plan, colours = grid()
    powers = plan.symmetry.tile_powers()
    prints = {j: build_strips(weave, plan, colours, 1.0, plan.copies[0], j) for j in (0, 1)}
    i = int(np.argmax([(~p.over).sum() for p in prints[0]]))  # the strip most often under
    s, strips = int(plan.copies[0, i]), {j: prints[j][i] for j in (0, 1)}
    under = np.flatnonzero(~strips[0].over)[:2].tolist()
    assert len(under) == 2

    module = left_out_crossings(weave, plan, [replace(strips[0], left_out=tuple(under))],
                                "module")
    tiles = [t for t, _, _ in module]
    want = np.unique(powers[:, weave_tiles(weave, plan, s, 0, under)])
    assert tiles == want.tolist() and len(tiles) == 2 * plan.k
    assert set(powers[:, tiles].ravel().tolist()) == set(tiles)  # closed under the turns

    pieces = [replace(strips[0], left_out=tuple(under)), replace(strips[1], left_out=(under[0],))]
    mixed = left_out_crossings(weave, plan, pieces, "mixed")
    want = sorted(weave_tiles(weave, plan, s, 0, under) + weave_tiles(weave, plan, s, 1,
                                                                       under[:1]))
    assert [t for t, _, _ in mixed] == want
    assert set(powers[:, want].ravel().tolist()) != set(want)  # not expanded to orbits
    for t, over, below in mixed:
        assert (over, below) == (weave.tile_over[t], weave.tile_under[t])
        assert below in (strips[0].strand, strips[1].strand)


@pytest.mark.parametrize("top", [1.5, 2.5, 2.8, 3.5])
def test_a_crossing_dot_keeps_clear_of_what_is_drawn_in_its_tile(top):
    """A 4 mm tile whose lower part, up to ``top``, is taken by a label: the dot (radius DOT)
    goes 0.4 mm inside the tile and 0.3 mm clear of the label, or nowhere when the strip left
    above the label is too thin for that (top + DOT + 0.3 >= 4 - 0.4)."""
    tile = shapely.box(0.0, 0.0, 4.0, 4.0)
    label = shapely.box(-1.0, -1.0, 5.0, top)
    spot = _crossing_spot(tile, [label])
    if top + DOT + 0.3 >= 3.6:
        assert spot is None
        return
    dot = shapely.Point(spot)
    assert dot.distance(label) >= DOT + 0.3 - 1e-6
    assert shapely.buffer(tile, -0.4).covers(dot)


def test_a_callouts_plate_and_dot_show_on_any_tile_and_the_dot_sits_on_its_crossing():
    """Callouts for three spots: each text on a white plate with a dark outline (it shows on
    the blank page beside the pattern); each dot a disc of radius DOT on its spot, black (it
    shows on a light tile) in a white ring (it shows on a dark one); each leader ends on it.
    Colours are spelled "#rrggbb" in lower case, as the palettes spell them, so a page's file
    names each colour one way."""
    spots = np.array([[30.0, 50.0], [70.0, 40.0], [60.0, 80.0]])
    labels = ["A1 over B2", "C3 over D4", "B5 over A6"]
    placed = column_callouts(spots, labels, (0.0, 0.0, 100.0, 100.0), 50.0)
    shapes, texts = callout_shapes(placed, spots)
    assert [t.text for t in texts] == labels
    plates, dots = shapes[0], shapes[-1]
    assert plates.style.fill == "#ffffff" and plates.style.stroke_width > 0
    assert contrast_ratio(plates.style.stroke, "#ffffff") >= MIN_CONTRAST
    for (_, plate, _), box in zip(placed, plates.to_shapely()):
        assert shapely.equals(plate, box)
    assert isinstance(dots, Polygons)
    discs = dots.to_shapely()
    assert len(discs) == len(spots)
    for disc, spot in zip(discs, spots):
        centre = np.asarray(disc.centroid.coords[0])
        assert centre == pytest.approx(spot, abs=1e-6)
        assert disc.area == pytest.approx(np.pi * DOT ** 2, rel=0.02)
    assert contrast_ratio(dots.style.fill, "#ffffff") >= MIN_CONTRAST
    assert contrast_ratio(dots.style.stroke, "#000000") >= MIN_CONTRAST
    # the ring is there, and leaves a black core wider than the leader's white casing
    assert 0 < dots.style.stroke_width and 2 * DOT - dots.style.stroke_width > CASING.stroke_width
    colours = [c for shape in shapes for c in (shape.style.stroke, shape.style.fill) if c]
    assert all(re.fullmatch("#[0-9a-f]{6}", c) for c in colours), colours  # one spelling each
    for (_, _, leader), spot in zip(placed, spots):
        assert leader[-1] == pytest.approx(spot)


def test_the_crossing_pages_keep_the_pattern_clear_of_the_callout_columns():
    """On a portrait A4 page the grid's pattern is as wide as the room between the two columns
    of callouts allows: 3 GAP clear of the widest plate on each side (room for the leaders to
    reach their dots), so no plate lies on the pattern; every crossing is called out once."""
    weave, plan, colours = grid()
    both = np.flatnonzero((weave.tile_over >= 0) & (weave.tile_under >= 0))[::3]
    crossings = [(int(t), int(weave.tile_over[t]), int(weave.tile_under[t])) for t in both]
    area = PageArea(210.0, 297.0, 10.0)
    pages = crossing_pages(weave, plan, colours, area, crossings, 0.0)
    named = []
    for layers in pages:
        shapes = {layer.name: layer for layer in layers}["pattern"].shapes
        px0, _, px1, _ = shapely.total_bounds(shapes[0].to_shapely())
        plates = shapes[1].to_shapely()
        assert len(plates)
        for plate in plates:
            x0, _, x1, _ = plate.bounds
            clear = px0 - x1 if x1 < (px0 + px1) / 2 else x0 - px1
            assert clear >= 3 * GAP - 1e-6
        named += [t.text for t in {layer.name: layer for layer in layers}["crossings"].shapes]
    ids = plan.labels
    assert sorted(named) == sorted(f"{ids[o]} over {ids[u]}" for _, o, u in crossings)
    widest = max(p.bounds[2] - p.bounds[0] for layers in pages
                 for p in layers[0].shapes[1].to_shapely())
    x0, _, x1, _ = area.box
    assert px1 - px0 == pytest.approx(x1 - x0 - 2 * (widest + 3 * GAP), abs=1e-6)


def test_a_side_with_more_callouts_than_its_columns_hold_lends_them_to_the_other(monkeypatch):
    """The 26 tiles of the small square grid left of its middle, called out with a column
    holding 15 plates: one page, not two, the callouts nearest the middle in the right column;
    every label once, no two leaders crossing. Planted: the side by the spot's x alone (all 26
    in the left column, more than it holds)."""
    from weavecut.papermodel import crossings
    from weavecut.papermodel.strips import model_tiles

    weave, _, colours = grid()
    x = shapely.get_coordinates(shapely.centroid(model_tiles(weave)))[:, 0]
    left = np.argsort(x, kind="stable")[:26].tolist()
    labels = [f"T{t}" for t in left]
    monkeypatch.setattr(crossings, "column_room", lambda frame: 15)
    pages = crossings.callout_pages(weave, colours, PageArea(210.0, 297.0, 10.0), left, labels,
                                    "note", 0.0, ["ids"] * len(left))
    assert len(pages) == 1
    layers = {layer.name: layer for layer in pages[0]}
    assert sorted(t.text for t in layers["ids"].shapes) == sorted(labels)
    xs = [t.x for t in layers["ids"].shapes]
    assert sum(v > 105.0 for v in xs) == 11
    lines = [line for s in layers["pattern"].shapes if isinstance(s, Polylines)
             and s.style.stroke == "#000000" for line in s.lines()]
    a, b = np.array([line[0] for line in lines]), np.array([line[1] for line in lines])
    assert not crossings.segments_cross(a, b).any()
