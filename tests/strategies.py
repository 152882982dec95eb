"""Hypothesis strategies for valid planar meshes: jittered grids, convex fans, Voronoi patches."""

from __future__ import annotations

import os

import numpy as np
import shapely
from hypothesis import strategies as st

from weavecut.inputs import _weld
from weavecut.mesh import Mesh

MUTATION_EXAMPLES = 25


def examples(n: int) -> int:
    """``n`` examples for a test that wants more than the profile gives, but at most
    ``MUTATION_EXAMPLES`` under the ``mutation`` profile (tools/mutation.py runs the test once
    per mutant, and an explicit count would override the profile's)."""
    return min(n, MUTATION_EXAMPLES) if os.environ.get("HYPOTHESIS_PROFILE") == "mutation" else n


@st.composite
def jittered_grids(draw, max_size: int = 4) -> Mesh:
    """A w x h quad grid whose inner vertices move by up to 0.2 of a cell (stays convex)."""
    w = draw(st.integers(1, max_size))
    h = draw(st.integers(1, max_size))
    seed = draw(st.integers(0, 2**31 - 1))
    rng = np.random.default_rng(seed)
    x, y = np.meshgrid(np.arange(w + 1.0), np.arange(h + 1.0))
    pts = np.column_stack([x.ravel(), y.ravel()])
    inner = ((pts[:, 0] > 0) & (pts[:, 0] < w) & (pts[:, 1] > 0) & (pts[:, 1] < h))
    pts[inner] += rng.uniform(-0.2, 0.2, size=(int(inner.sum()), 2))
    i, j = np.meshgrid(np.arange(w), np.arange(h))
    v0 = (j * (w + 1) + i).ravel()
    faces = np.column_stack([v0, v0 + 1, v0 + w + 2, v0 + w + 1])
    return Mesh(pts, np.arange(0, 4 * len(v0) + 1, 4), faces.ravel())


@st.composite
def convex_fans(draw) -> Mesh:
    """Triangles fanned around a centre inside a random convex polygon."""
    n = draw(st.integers(3, 12))
    seed = draw(st.integers(0, 2**31 - 1))
    rng = np.random.default_rng(seed)
    t = np.sort(rng.uniform(0, 2 * np.pi, n))
    t = t[np.concatenate([[True], np.diff(t) > 0.2])]
    if len(t) < 3 or (2 * np.pi - (t[-1] - t[0])) < 0.2:
        t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = rng.uniform(0.8, 1.2)
    ring = np.column_stack([np.cos(t), np.sin(t)]) * r
    k = len(ring)
    verts = np.vstack([[0.0, 0.0], ring])
    i = np.arange(k)
    faces = np.column_stack([np.zeros(k, int), 1 + i, 1 + (i + 1) % k])
    return Mesh(verts, np.arange(0, 3 * k + 1, 3), faces.ravel())


@st.composite
def voronoi_patches(draw) -> Mesh:
    """Convex cells of a Voronoi diagram of random points, clipped to the unit square."""
    n = draw(st.integers(3, 14))
    seed = draw(st.integers(0, 2**31 - 1))
    rng = np.random.default_rng(seed)
    box = shapely.box(0, 0, 1, 1)
    pts = shapely.multipoints(rng.uniform(0.05, 0.95, size=(n, 2)))
    cells = shapely.get_parts(shapely.voronoi_polygons(pts, extend_to=box))
    cells = [shapely.intersection(c, box) for c in cells]
    cells = [shapely.set_precision(c, 1e-7) for c in cells]
    polys = [np.asarray(shapely.geometry.polygon.orient(c).exterior.coords)[:-1]
             for c in cells if c.area > 1e-4]
    return _weld(polys, decimals=6)


any_mesh = st.one_of(jittered_grids(), convex_fans(), voronoi_patches())


def _validated(mesh: Mesh) -> Mesh | None:
    from weavecut.errors import MeshError
    from weavecut.validation import validate

    try:
        return validate(mesh)
    except MeshError:
        return None


valid_meshes = any_mesh.map(_validated).filter(lambda m: m is not None)
