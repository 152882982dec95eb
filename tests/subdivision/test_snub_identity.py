"""The in-place snub step gives the same arrays, bit for bit, as the direct one it replaced
(``snub_oracle.py``): on built-in and random meshes, both chiralities, both centres, with and
without smoothing, over several levels (faces of one degree and of mixed degrees)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings

from tests import meshes
from tests.strategies import valid_meshes
from tests.subdivision import snub_oracle
from weavecut import inputs
from weavecut.mesh import Mesh, Topology
from weavecut.subdivision import snub

OPTIONS = [dict(chirality=c, centre=k, smooth=s)
           for c, k, s in itertools.product(snub.CHIRALITIES, snub.CENTRES, (True, False))]
MESHES = {name: (lambda name=name: inputs.get(name)) for name in
          ["pentagon", "tiling-8-4:2x2", "triangulated-ngon:6", "square-grid:3x2",
           "hex-grid:2x2", "pentagon-flower"]}
MESHES["mixed"] = meshes.mixed


def _arrays(level) -> dict[str, np.ndarray]:
    mesh, topo = level.mesh, level.mesh.topology
    return {"vertices": mesh.vertices, "face_offsets": mesh.face_offsets,
            "face_indices": mesh.face_indices, "edges": topo.edges,
            "half_edge_edge": topo.half_edge_edge, "half_edge_side": topo.half_edge_side,
            "boundary_edges": topo.boundary_edges, "parent_face": level.parent_face,
            "parent_corner": level.parent_corner, "parent_edge": level.parent_edge,
            "edge_part": level.edge_part}


def _bits(a: np.ndarray) -> bytes:
    """The array's bytes: 0 ulp, and 0.0 is not -0.0 (``array_equal`` would let both pass)."""
    return np.ascontiguousarray(a).tobytes()


def _assert_same_chain(mesh: Mesh, levels: int, **options) -> None:
    new = old = mesh
    for t in range(1, levels + 1):
        got, want = snub.step(new, **options), snub_oracle.step(old, **options)
        for name, expected in _arrays(want).items():
            actual = _arrays(got)[name]
            assert actual.dtype == expected.dtype, (t, name)
            assert actual.shape == expected.shape, (t, name)
            assert _bits(actual) == _bits(expected), f"level {t}: {name} differs"
        # what the step stores for the next step equals what the mesh would derive itself
        fresh = Mesh.trusted(got.mesh.vertices, got.mesh.face_offsets, got.mesh.face_indices)
        assert got.mesh.face_degree == fresh.face_degree
        rebuilt = Topology(got.mesh.topology.edges, got.mesh.topology.half_edge_edge,
                           got.mesh.topology.half_edge_side)
        assert np.array_equal(got.mesh.topology.edge_half_edges, rebuilt.edge_half_edges)
        assert np.array_equal(got.mesh.topology.boundary_edges, rebuilt.boundary_edges)
        new, old = got.mesh, want.mesh


@pytest.mark.parametrize("options", OPTIONS, ids=lambda o: "-".join(map(str, o.values())))
@pytest.mark.parametrize("name", MESHES)
def test_same_arrays_as_the_direct_step(name, options):
    mesh = MESHES[name]()
    _assert_same_chain(mesh, 4 if mesh.n_faces < 4 else 3, **options)


@settings(max_examples=25, deadline=None)
@given(valid_meshes)
def test_same_arrays_on_random_meshes(mesh):
    for options in OPTIONS[::3]:
        _assert_same_chain(mesh, 2, **options)


@pytest.mark.parametrize("options", OPTIONS[::2], ids=lambda o: "-".join(map(str, o.values())))
@pytest.mark.parametrize("name", ["cube", "dodecahedron", "icosphere:1"])
def test_surface_topology_as_the_direct_step(name, options):
    """On a surface in space only the vertices differ from the planar step: every other array
    is the direct step's on the same faces (given (x, y) only), over two levels."""
    options = {**options, "centre": "vertex"}  # a surface has vertex centres only
    mesh = inputs.get(name)
    for _ in range(2):
        got = snub.step(mesh, **options)
        flat = Mesh.trusted(np.ascontiguousarray(mesh.vertices[:, :2]), mesh.face_offsets,
                            mesh.face_indices, mesh.topology)  # the same edge numbering
        want = snub_oracle.step(flat, **options)
        for key, expected in _arrays(want).items():
            if key != "vertices":
                assert _bits(_arrays(got)[key]) == _bits(expected), key
        assert got.mesh.vertices.shape == (want.mesh.n_vertices, 3)
        mesh = got.mesh
