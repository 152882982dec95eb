"""The sphere of ``--project sphere`` (surface.circumsphere, onto_sphere) wherever the mesh
sits: a fit and a projection about a centre far from the origin are those about the origin,
moved (#34: mutants no test killed, as every tested sphere was centred at the origin)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from weavecut import inputs, surface
from weavecut.errors import MeshError

SPHERE = inputs.get("icosphere:2").vertices.astype(float)  # 162 points on the unit sphere
OFFSETS = [(0.0, 0.0, 0.0), (1e3, -2e3, 5e2), (-3e5, 7e4, 1e6), (1e6, -2e6, 5e5)]


@pytest.mark.parametrize("radius", [1.0, 150.0])
@pytest.mark.parametrize("offset", OFFSETS, ids=str)
def test_a_sphere_far_from_the_origin_is_found_as_at_the_origin(offset, radius):
    """Points carry about 1e-16 of their size in rounding: the centre and radius are found
    to that, not to the offset's square (a fit not centred on the points loses it)."""
    centre = np.array(offset)
    found, r = surface.circumsphere(SPHERE * radius + centre)
    scale = max(1.0, float(np.abs(centre).max()))
    assert np.abs(found - centre).max() <= 1e-12 * scale + 1e-12 * radius
    assert abs(r - radius) <= 1e-12 * scale + 1e-12 * radius


def test_a_flat_mesh_has_no_sphere():
    with pytest.raises(MeshError) as caught:
        surface.circumsphere(SPHERE[:, :2].copy())
    assert str(caught.value) == "--project sphere needs a surface in space (x, y, z vertices)"


@given(st.tuples(*[st.floats(-1e4, 1e4)] * 3), st.floats(0.5, 500))
def test_each_point_moves_along_its_ray_from_the_centre_onto_the_sphere(centre, radius):
    centre = np.array(centre)
    rng = np.random.default_rng(7)
    before = centre + rng.uniform(-1, 1, (50, 3)) * rng.uniform(0.1, 3, (50, 1)) * radius
    before = before[np.linalg.norm(before - centre, axis=1) > 1e-3 * radius]
    after = before.copy()
    surface.onto_sphere(after, centre, radius)
    scale = radius + np.abs(centre).max()
    assert np.allclose(np.linalg.norm(after - centre, axis=1), radius, rtol=0,
                       atol=1e-9 * scale)
    ray, moved = before - centre, after - centre  # the same direction: parallel, not opposed
    assert np.allclose(np.cross(ray, moved), 0, atol=1e-9 * scale * np.abs(ray).max())
    assert ((ray * moved).sum(axis=1) > 0).all()
