"""The weaves refuse what they cannot weave with the whole message, naming the first bad
element, found here by a loop over the faces."""

from __future__ import annotations

import re

import numpy as np
import pytest

from weavecut import inputs
from weavecut.errors import MeshError
from weavecut.mesh import Mesh
from weavecut.subdivision import subdivide
from weavecut.weave.quad import quad_weave, twins_by_key
from weavecut.weave.snub_weave import snub_weave
from weavecut.weave.triangles import triangle_weave
from weavecut.weave.two_colouring import disc_two_colouring, triangle_three_colouring

from ..subdivision.classic_meshes import quad_grid, tri_grid
from .test_triangle_weaves import split_quads


def refused(call, message: str) -> None:
    with pytest.raises(MeshError, match=f"^{re.escape(message)}$"):
        call()


def test_triangle_weave_refuses_a_bad_colouring_naming_the_first_face():
    mesh, _ = split_quads(2, 1)
    c1 = triangle_three_colouring(mesh)
    last = mesh.faces()[-1]
    c1[last] = [True, True, False]  # two c1 corners in the last face (and its neighbours)
    bad = [f for f, corners in enumerate(mesh.faces()) if c1[corners].sum() != 1]
    assert bad[0] >= 1
    refused(lambda: triangle_weave(mesh, c1),
            f"face {bad[0]} is not a triangle with exactly one c1 corner ({len(bad)} such faces)")
    refused(lambda: triangle_weave(mesh, np.zeros(mesh.n_vertices, dtype=bool)),
            f"face 0 is not a triangle with exactly one c1 corner ({mesh.n_faces} such faces)")


@pytest.mark.parametrize("name, message", [
    ("triangulated-ngon:5", "the triangles have no colouring with one c1 corner each "
                            "(an inner vertex of odd degree)"),
    ("square-grid:2x2", "a triangle weave needs a mesh of triangles only"),
])
def test_triangle_three_colouring_refusals(name, message):
    refused(lambda: triangle_three_colouring(inputs.get(name)), message)


def test_snub_weave_refuses_a_mesh_not_of_pentagons():
    refused(lambda: snub_weave(inputs.get("square-grid:2x2")),
            "the snub weave needs a level made by a pentagon snub step (level >= 1)")


@pytest.mark.parametrize("turned", [None, 1, 3, -1])
def test_snub_weave_names_the_first_pentagon_whose_tip_is_at_no_middle_edge(turned):
    """A snub level with pentagon ``turned`` renumbered one corner on (None: the level 0
    pentagon itself): a pentagon's tip (local vertex 4) must end some pentagon's middle edge
    (local vertices 1 and 2)."""
    mesh = inputs.get("pentagon")
    if turned is not None:
        level = subdivide(mesh, 2)[2].mesh
        faces = level.faces()
        faces[turned] = faces[turned][1:] + faces[turned][:1]
        mesh = Mesh.from_faces(level.vertices, faces)
    faces = mesh.faces()
    ends = {v for f in faces for v in f[1:3]}
    bad = [p for p, f in enumerate(faces) if f[4] not in ends]
    refused(lambda: snub_weave(mesh),
            f"pentagon {bad[0]} has no middle edge at its tip: not a snub level")


def test_disc_colouring_names_the_first_edge_within_one_colour():
    """Two triangles: BFS layers from vertex 0 give 0 c1 and 1, 2, 3 c2; edges (1, 3) and
    (2, 3) join c2 to c2 ((0, 3), the diagonal, is the other way)."""
    mesh = tri_grid(1, 1)
    edges = [tuple(e) for e in mesh.topology.edges.tolist()]
    bad = [e for e in edges if e in {(1, 3), (2, 3)}]
    assert len(bad) == 2
    refused(lambda: disc_two_colouring(mesh),
            f"not two-colourable: edge {bad[0]} joins two vertices of one colour "
            "(2 such edges)")


def test_quad_weave_refusals():
    refused(lambda: quad_weave(inputs.get("triangle-grid:2x2"), np.zeros(9, dtype=bool)),
            "the quad weave needs a mesh of quads only")
    mesh = quad_grid(2, 1)
    refused(lambda: quad_weave(mesh, np.zeros(6, dtype=bool), twins_by_key(mesh)),
            "not two-colourable: a quad has two neighbouring corners of one colour")
