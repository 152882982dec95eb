"""Polygons from shapely, as the writers get them: every polygon's exterior (counter-clockwise)
then its holes (clockwise), each ring without its closing point, in the polygons' order (an
empty polygon: one ring without points); read back polygon by polygon, ring by ring."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout.drawing import Style, polygons_from_shapely


@st.composite
def polygons(draw):
    """A polygon with holes (from buffered points), or an empty one."""
    if draw(st.booleans()) and draw(st.booleans()):
        return shapely.Polygon()
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    blob = shapely.MultiPoint(rng.uniform(0, 10, (int(rng.integers(1, 12)), 2))).buffer(
        rng.uniform(0.5, 3), quad_segs=int(rng.integers(1, 4)))
    holes = shapely.MultiPoint(rng.uniform(0, 10, (int(rng.integers(0, 6)), 2))).buffer(
        0.4, quad_segs=1)
    parts = shapely.get_parts(shapely.difference(blob, holes))
    part = parts[int(rng.integers(len(parts)))] if len(parts) else shapely.Polygon()
    if draw(st.booleans()):  # the same polygon turned the other way round
        part = shapely.Polygon(part.exterior.coords[::-1],
                               [h.coords[::-1] for h in part.interiors]) if not part.is_empty \
            else part
    return part


@settings(max_examples=60, deadline=None)
@given(st.lists(polygons(), max_size=6), st.booleans())
def test_rings_of_every_polygon_in_order_and_orientation(geoms, with_fills):
    fills = [f"#0000{k:02x}" for k in range(len(geoms))] if with_fills else None
    got = polygons_from_shapely(geoms, Style(), fills)
    assert got.fills == (None if fills is None else tuple(fills))
    po = got.polygon_rings()
    rings = got.rings()
    assert len(po) == len(geoms) + 1 and got.coords.shape[1] == 2
    for k, g in enumerate(geoms):
        mine = rings[po[k]:po[k + 1]]
        if g.is_empty:
            assert [len(r) for r in mine] == [0]
            continue
        assert len(mine) == 1 + len(g.interiors)
        for ring, want, ccw in zip(mine, [g.exterior, *g.interiors],
                                   [True] + [False] * len(g.interiors)):
            assert shapely.LinearRing(ring).is_ccw == ccw
            assert len(ring) == len(want.coords) - 1  # no closing point
            assert shapely.equals(shapely.Polygon(ring), shapely.Polygon(want))
    if not any(g.is_empty for g in geoms):  # (to_shapely takes no ring without points)
        assert shapely.equals(got.to_shapely(), np.array(geoms, dtype=object)).all()
