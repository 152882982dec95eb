"""Every pentagon of a ball flattened on its own best-fit plane (``unfold.flatten``), checked in
space: the plane goes through the corners' mean with a unit normal turned outwards, each corner
is its in-plane point plus its height (Pythagoras), the reported non-planarity is the largest
height over the pentagon's diameter, no other plane through the mean fits better, and the flat
pentagon is counter-clockwise (seen from outside, so nothing is mirrored)."""

from __future__ import annotations

import numpy as np
import pytest

from weavecut.inputs import get
from weavecut.papermodel.unfold import flatten
from weavecut.subdivision import subdivide
from weavecut.weave.snub_weave import snub_weaves


@pytest.mark.parametrize("name", ["cube", "tetrahedron"])
def test_each_pentagon_lies_on_its_best_fit_plane_seen_from_outside(name):
    weave = snub_weaves(subdivide(get(name), 1, project="sphere"))[-1]
    flat = flatten(weave)
    p = weave.mesh.vertices[weave.mesh.dense_faces()]  # (F, 5, 3)
    f = len(p)
    assert flat.coords.shape == (f, 5) and flat.normals.shape == (f, 3)
    assert np.allclose(flat.centres, p.mean(axis=1))
    assert np.allclose(np.linalg.norm(flat.normals, axis=1), 1.0)
    # outwards: the ball is centred on the origin
    assert (np.einsum("fk,fk->f", flat.normals, flat.centres) > 0).all()
    x = p - flat.centres[:, None]
    height = np.einsum("fvk,fk->fv", x, flat.normals)
    assert np.allclose(np.einsum("fvk,fvk->fv", x, x), np.abs(flat.coords) ** 2 + height ** 2)
    assert np.allclose(flat.coords.mean(axis=1), 0.0, atol=1e-12)
    diameter = np.array([max(np.linalg.norm(a - b) for a in q for b in q) for q in p])
    assert np.allclose(flat.non_planarity, np.abs(height).max(axis=1) / diameter)
    assert (flat.non_planarity > 0).any()  # the pentagons on a sphere are not flat
    # no plane through the mean fits better: tilt the normal a little every way
    best = (height ** 2).sum(axis=1)
    rng = np.random.default_rng(1)
    for _ in range(20):
        tilted = flat.normals + 0.05 * rng.normal(size=(f, 3))
        tilted /= np.linalg.norm(tilted, axis=1)[:, None]
        assert ((np.einsum("fvk,fk->fv", x, tilted) ** 2).sum(axis=1) >= best - 1e-12).all()
    # counter-clockwise in the plane, as the corners go round the outward normal in space
    z = flat.coords
    area = 0.5 * np.imag(np.conj(z) * np.roll(z, -1, axis=1)).sum(axis=1)
    assert (area > 0).all()
    # the in-plane corners keep each pentagon's shape up to its bending: every distance in the
    # plane is the distance in space less at most twice the largest height
    d2 = np.abs(z[:, :, None] - z[:, None, :])
    d3 = np.linalg.norm(p[:, :, None] - p[:, None], axis=-1)
    assert (d2 <= d3 + 1e-12).all()
    assert (d3 - d2 <= 2 * np.abs(height).max(axis=1)[:, None, None] + 1e-12).all()
