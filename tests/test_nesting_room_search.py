"""The search for the lowest, then leftmost, free window in a frame's room (``nesting._place``)
finds what a plain scan of every window, row by row, finds on random rooms and random sizes,
windows taken before included."""

from __future__ import annotations

import numpy as np
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from weavecut.layout import nesting


def _scan(inside, sizes):
    """The oracle: every window of every row, lowest row first, each cell looked at."""
    taken = ~inside.copy()
    out = []
    for wx, wy in sizes:
        spot = next(((j, i) for j in range(inside.shape[0] - wy + 1)
                     for i in range(inside.shape[1] - wx + 1)
                     if not taken[j:j + wy, i:i + wx].any()), None)
        if spot is not None:
            taken[spot[0]:spot[0] + wy, spot[1]:spot[1] + wx] = True
        out.append(spot)
    return out


@settings(max_examples=150, deadline=None)
@given(st.integers(1, 70), st.integers(1, 45), st.integers(0, 2**32 - 1), st.floats(0.0, 0.3),
       st.lists(st.tuples(st.integers(1, 12), st.integers(1, 12)), max_size=25))
def test_the_room_search_finds_what_a_scan_of_every_window_finds(ny, nx, seed, holes, sizes):
    rng = np.random.default_rng(seed)
    inside = rng.random((ny, nx)) >= holes  # a room with scattered cells outside it
    assert nesting._place(inside.copy(), [list(s) for s in sizes]) == _scan(inside, sizes)


def test_a_room_taller_than_one_band_of_rows():
    """Windows found past the first rows looked at together, and one that fits nowhere."""
    inside = np.ones((3 * nesting.ROWS + 5, 9), dtype=bool)
    inside[:2 * nesting.ROWS, 3:] = False  # a narrow shaft below, the room's width above
    sizes = [(5, 4), (4, 3), (9, nesting.ROWS + 6), (9, 2), (3, 2)]
    assert nesting._place(inside.copy(), [list(s) for s in sizes]) == _scan(inside, sizes)


@settings(max_examples=120, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(3, 9), st.booleans(), st.booleans(),
       st.sampled_from([1.0, 0.5, 0.3]))
@example(seed=4, corners=4, on_grid=False, holed=True, grid=1.0)  # a hole's top on a row
def test_the_cells_inside_a_room_are_those_shapely_finds(seed, corners, on_grid, holed, grid):
    """Row crossings against ``shapely.contains_xy`` cell by cell: random polygons (with a
    hole, as a second part), some with every corner on a cell centre's row or column, and
    edges through cell centres (those cells are shapely's to decide)."""
    import shapely

    rng = np.random.default_rng(seed)
    angle = np.sort(rng.uniform(0, 2 * np.pi, corners))
    radius = rng.uniform(3, 10, corners)
    ring = np.column_stack([10 + radius * np.cos(angle), 10 + radius * np.sin(angle)])
    if on_grid:  # corners on cell centres (and so edges through some)
        ring = (np.round(ring / grid - 0.5) + 0.5) * grid
    area = shapely.make_valid(shapely.Polygon(ring))
    if holed:
        area = shapely.union(shapely.difference(area, shapely.box(8.5, 8.5, 11.5, 11.5)),
                             shapely.box(22, 3, 25.5, 9))
    # a room is an area: corners on one line (cells' centres on one column) make a line, whose
    # points shapely counts as inside it
    assume(area.geom_type in ("Polygon", "MultiPolygon"))
    xs, ys = (np.arange(int(27 / grid)) + 0.5) * grid, (np.arange(int(21 / grid)) + 0.5) * grid
    cx, cy = np.meshgrid(xs, ys)
    assert np.array_equal(nesting.cells_inside(area, xs, ys), shapely.contains_xy(area, cx, cy))
