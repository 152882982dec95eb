"""The rules ``validate`` and ``check_layout`` enforce, each with its exact message, at the edge
of its tolerance, and on surfaces in space."""

from __future__ import annotations

import re

import numpy as np
import pytest
import shapely

from tests import meshes
from weavecut.errors import MeshError, NonManifoldError
from weavecut.mesh import Mesh, Numbering
from weavecut.mesh_geometry import signed_areas
from weavecut.surface import signed_volume
from weavecut.validation import MAX_COORDINATE, check_layout, validate

SQUARE = [(0, 0), (1, 0), (1, 1), (0, 1)]


@pytest.mark.parametrize("coordinate", [MAX_COORDINATE * 1.5, -MAX_COORDINATE * 1.5])
def test_coordinates_beyond_a_billion_are_refused_either_side(coordinate):
    mesh = Mesh.from_faces([(0, 0), (1, 0), (0, 1), (coordinate, 1)], [[0, 1, 2], [1, 3, 2]])
    with pytest.raises(MeshError, match=r"^vertex 3 has a coordinate beyond 1e\+09; scale the "
                                        "mesh down$"):
        validate(mesh)
    at_the_limit = Mesh.from_faces([(0, 0), (MAX_COORDINATE, 0), (0, MAX_COORDINATE)],
                                   [[0, 1, 2]])
    assert validate(at_the_limit) is at_the_limit


def test_zero_area_is_relative_to_the_size_of_the_mesh():
    # a triangle of area 0.5 is flat next to a face a million units wide, not on its own
    small = [(0, 0), (1, 0), (0, 1)]
    assert validate(Mesh.from_faces(small, [[0, 1, 2]])).n_faces == 1
    wide = small + [(2e6, 0), (2e6, 2e6)]
    with pytest.raises(MeshError, match=r"^face 0 has zero area$"):
        validate(Mesh.from_faces(wide, [[0, 1, 2], [1, 3, 4]]))
    thin = [(0, 0), (1e6, 0), (0, 1e-3), (1e6, 1e6)]  # area 500, a millionth of 1e6 squared
    assert validate(Mesh.from_faces(thin, [[0, 1, 2], [1, 3, 2]])).n_faces == 2
    with pytest.raises(MeshError, match=r"^face 2 \(line 9\) has zero area$"):
        validate(Mesh.from_faces(small + [(2, 0)], [[0, 1, 2], [0, 3, 1]]),
                 numbering=Numbering(first=1, face_lines=np.array([8, 9])))


def test_a_clockwise_mesh_is_turned_and_then_checked():
    # all clockwise: turned; the turned mesh must still pass the overlap checks
    fan = meshes.hexagon().reversed()
    turned = validate(fan)
    assert (signed_areas(turned) > 0).all() and turned.faces() == meshes.hexagon().faces()
    nested = Mesh.from_faces([(0, 0), (4, 0), (4, 4), (0, 4), (1, 1), (2, 1), (2, 2), (1, 2)],
                             [[3, 2, 1, 0], [7, 6, 5, 4]])
    with pytest.raises(MeshError, match=r"^vertex 4 lies inside face 0 \(faces overlap\)$"):
        validate(nested)
    bent = Mesh.from_faces([(0, 0), (2, 0), (2, 2), (1, 0.5), (0, 2)], [[4, 3, 2, 1, 0]])
    with pytest.raises(MeshError, match=r"^face 0 is not convex at vertex 3: the snub scheme "
                                        r"assumes convex faces \(deep levels of some inputs have"
                                        r" a few non-convex faces, see weave-cut convexity\); "
                                        r"pass --allow-nonconvex to use the mesh anyway$"):
        validate(bent)
    assert signed_areas(validate(bent, allow_nonconvex=True))[0] > 0


def test_one_clockwise_face_of_many_is_named_with_the_count():
    grid = Mesh.from_faces([(x, y) for y in range(2) for x in range(5)],
                           [[i, i + 1, i + 6, i + 5] for i in range(4)])
    faces = grid.faces()
    for wrong in ([2], [1, 3], [0, 1, 3]):
        mixed = Mesh.from_faces(grid.vertices, [f[::-1] if k in wrong else f
                                                for k, f in enumerate(faces)])
        with pytest.raises(MeshError, match=rf"^face {wrong[0]} is clockwise while others are "
                                            rf"counter-clockwise \({len(wrong)} of 4 faces are "
                                            r"clockwise\)$"):
            validate(mixed)


def test_a_corner_that_turns_right_by_a_hair_is_convex_enough():
    # the middle corner sits 1e-14 of the size inside the straight line: a rounding error
    hair = Mesh.from_faces([(0, 0), (1, 1e-14), (2, 0), (2, 1), (0, 1)], [[0, 1, 2, 3, 4]])
    assert validate(hair) is hair
    dent = Mesh.from_faces([(0, 0), (1, 1e-6), (2, 0), (2, 1), (0, 1)], [[0, 1, 2, 3, 4]])
    with pytest.raises(MeshError, match="^face 0 is not convex at vertex 1"):
        validate(dent)


def test_faces_folded_round_a_vertex_give_the_angle_sum():
    t = np.linspace(0, 4 * np.pi, 7)[:-1] + 0.1
    ring = np.column_stack([np.cos(t), np.sin(t)])
    fan = Mesh.from_faces(np.vstack([[0.0, 0.0], ring]),
                          [[0, 1 + i, 1 + (i + 1) % 6] for i in range(6)])
    with pytest.raises(MeshError, match=r"^faces around vertex 0 overlap \(their angles add up "
                                        r"to 720\.0 degrees\)$"):
        validate(fan)
    # five of the six: a boundary vertex may have less than a full turn, not more
    open_fan = Mesh.from_faces(fan.vertices, fan.faces()[:5])
    with pytest.raises(MeshError, match=r"^faces around vertex 0 overlap \(their angles add up "
                                        r"to 600\.0 degrees\)$"):
        validate(open_fan)
    three = Mesh.from_faces(fan.vertices[:5], fan.faces()[:3])  # 360 degrees, no overlap yet
    assert validate(three) is three
    with pytest.raises(MeshError, match=r"^vertex 5 is in no face$"):  # was: "overlap, 0.0"
        validate(Mesh.from_faces(fan.vertices, fan.faces()[:3]))


def test_an_inner_vertex_whose_faces_leave_a_gap_is_refused():
    # four triangles round vertex 0 that close up topologically but cover only 3/4 of a turn
    # cannot lie flat: the fourth is folded back over the first
    t = np.radians([0, 60, 120, 180])
    ring = np.column_stack([np.cos(t), np.sin(t)])
    pinched = Mesh.from_faces(np.vstack([[0.0, 0.0], ring]),
                              [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]])
    with pytest.raises(MeshError):
        validate(pinched, allow_nonconvex=True)


def test_crossing_boundary_edges_are_named():
    # a star of David: no vertex of one triangle lies inside the other, but their edges cross
    t = np.pi / 2 + 2 * np.pi * np.arange(6) / 6
    pts = np.column_stack([np.cos(t), np.sin(t)])
    star = Mesh.from_faces(pts, [[0, 2, 4], [1, 3, 5]])
    with pytest.raises(MeshError) as error:
        validate(star)
    found = re.fullmatch(r"faces overlap: boundary edges \((\d), (\d)\) and \((\d), (\d)\) cross",
                         str(error.value))
    assert found, error.value
    a, b, c, d = map(int, found.groups())
    assert {a, b} < {0, 2, 4} and {c, d} < {1, 3, 5}
    assert shapely.LineString(pts[[a, b]]).crosses(shapely.LineString(pts[[c, d]]))
    one_based = Numbering(first=1, face_lines=np.array([7, 8]))
    with pytest.raises(MeshError, match=rf"^faces overlap: boundary edges \({a + 1}, {b + 1}\) "
                                        rf"and \({c + 1}, {d + 1}\) cross$"):
        validate(star, numbering=one_based)


def test_faces_that_only_touch_at_a_corner_or_edge_are_valid():
    corner = Mesh.from_faces(SQUARE + [(2, 1), (2, 2), (1, 2)], [[0, 1, 2, 3], [2, 4, 5, 6]])
    with pytest.raises(NonManifoldError, match="vertex 2 joins 2 separate fans"):
        validate(corner)
    apart = Mesh.from_faces(SQUARE + [(1.5, 0), (2.5, 0), (2.5, 1), (1.5, 1)],
                            [[0, 1, 2, 3], [4, 5, 6, 7]])
    assert validate(apart) is apart
    mesh = meshes.mixed()
    assert validate(mesh) is mesh


def test_the_lowest_vertex_inside_a_face_is_named():
    big = [(0, 0), (10, 0), (10, 10), (0, 10)]
    inner = [(6, 6), (7, 6), (7, 7), (6, 7), (2, 2), (3, 2), (3, 3), (2, 3)]
    mesh = Mesh.from_faces(big + inner, [[0, 1, 2, 3], [4, 5, 6, 7], [8, 9, 10, 11]])
    with pytest.raises(MeshError, match=r"^vertex 4 lies inside face 0 \(faces overlap\)$"):
        validate(mesh)


def test_the_lowest_vertex_is_named_before_the_lowest_face():
    def square(x, y, size):
        return [(x, y), (x + size, y), (x + size, y + size), (x, y + size)]

    # face 0 holds vertices 8..11, face 2 holds vertices 4..7: vertex 4 is named, in face 2
    points = square(0, 0, 10) + square(22, 2, 1) + square(2, 2, 1) + square(20, 0, 10)
    faces = [[0, 1, 2, 3], [8, 9, 10, 11], [12, 13, 14, 15], [4, 5, 6, 7]]
    with pytest.raises(MeshError, match=r"^vertex 4 lies inside face 2 \(faces overlap\)$"):
        validate(Mesh.from_faces(points, faces))


def test_self_intersection_is_named_for_the_first_such_face():
    bow = [(3, 0), (5, 2), (5, 0), (3, 3)]  # a bow-tie quad with positive area
    mesh = Mesh.from_faces(SQUARE + bow + [(10, 0), (12, 2), (12, 0), (10, 3)],
                           [[0, 1, 2, 3], [4, 5, 6, 7], [8, 9, 10, 11]])
    with pytest.raises(MeshError, match=r"^face 1 intersects itself$"):
        validate(mesh, allow_nonconvex=True)


# -- surfaces in space -------------------------------------------------------------------------

TETRAHEDRON = ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)],
               [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])  # outward


def test_a_closed_surface_is_turned_outwards_and_an_open_one_left_alone():
    outward = Mesh.from_faces(*TETRAHEDRON)
    assert signed_volume(outward) > 0 and validate(outward) is outward
    inside_out = outward.reversed()
    turned = validate(inside_out)
    assert signed_volume(turned) > 0 and turned.faces() == outward.faces()
    cap = Mesh.from_faces(TETRAHEDRON[0], TETRAHEDRON[1][1:]).reversed()  # open: no inside
    assert validate(cap) is cap


def test_a_face_of_one_point_has_zero_area_in_the_plane_and_in_space():
    for point in ((2.0, 3.0), (2.0, 3.0, 4.0)):
        with pytest.raises(MeshError, match=r"^face 0 has zero area$"):
            validate(Mesh.from_faces([point] * 3, [[0, 1, 2]]))


def test_zero_area_in_space_is_relative_to_the_widest_extent():
    # a unit triangle next to one two million wide: flat beside it, not on its own
    big = [(0, 0, 0), (2e6, 0, 0), (0, 2e6, 0)]
    unit = [(5, 5, 1), (6, 5, 1), (5, 6, 1)]
    with pytest.raises(MeshError, match=r"^face 1 has zero area$"):
        validate(Mesh.from_faces(big + unit, [[0, 1, 2], [3, 4, 5]]))
    ten = [(5, 5, 1), (15, 5, 1), (5, 15, 1)]  # area 50: above 1e-12 of (2e6)^2
    assert validate(Mesh.from_faces(big + ten, [[0, 1, 2], [3, 4, 5]])).n_faces == 2
    # far from the origin along x only: the extent is 1 in every axis, not a million
    far = Mesh.from_faces([(1e6, 0, 0), (1e6 + 1, 0, 0), (1e6, 1, 1)], [[0, 1, 2]])
    assert validate(far) is far


def test_surface_messages_count_as_the_obj_file(tmp_path):
    from weavecut.mesh_io import read_valid_mesh

    path = tmp_path / "flip.obj"
    v, f = TETRAHEDRON
    faces = [f[0], f[1][::-1], f[2], f[3]]
    path.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in v) + "# faces\n"
                    + "".join("f " + " ".join(str(i + 1) for i in face) + "\n"
                              for face in faces))
    with pytest.raises(NonManifoldError, match=rf"^{path}: edge \(1, 2\) runs the same way in "
                                               r"face 1 \(line 6\) and face 2 \(line 7\)"):
        read_valid_mesh(path)


def test_a_closed_surface_without_volume_is_left_as_it_is():
    pillow = Mesh.from_faces([(0, 0, 0), (1, 0, 0), (0, 1, 1)], [[0, 1, 2], [0, 2, 1]])
    assert signed_volume(pillow) == 0 and validate(pillow) is pillow


def test_surface_faces_must_have_area_and_agree_in_orientation():
    v, f = TETRAHEDRON
    flat = Mesh.from_faces(v + [(2, 0, 0)], f + [[1, 4, 3], [0, 1, 4]])  # (0, 1, 4) collinear
    with pytest.raises(MeshError, match=r"^face 5 has zero area$"):
        validate(flat)
    flipped = Mesh.from_faces(v, [f[0], f[1][::-1], f[2], f[3]])
    with pytest.raises(NonManifoldError, match=r"^edge \(0, 1\) runs the same way in face 0 "
                                               r"and face 1"):
        validate(flipped)
    small = Mesh.from_faces([(0, 0, 0), (1e-7, 0, 0), (0, 1e-7, 1e-7)], [[0, 1, 2]])
    assert validate(small) is small  # zero area is relative to the size


# -- what the puzzle and the paper model lay out ---------------------------------------------

def quotient(mesh: Mesh) -> np.ndarray:
    """4 pi A / P^2 of every face, by shapely."""
    polys = [shapely.Polygon(mesh.vertices[f]) for f in mesh.faces()]
    return np.array([4 * np.pi * p.area / p.length ** 2 for p in polys])


def test_check_layout_refuses_slivers_surfaces_and_separate_parts():
    assert check_layout(meshes.two_squares(), "the puzzle", connected=True).n_faces == 2
    square = [(0, 0), (10, 0), (10, 10), (0, 10), (20, 0)]  # 10 long: P^2 is not 2 P
    sliver = Mesh.from_faces(square + [(20, 0.004)], [[0, 1, 2, 3], [1, 4, 5]])
    q = quotient(sliver)[1]
    with pytest.raises(MeshError, match=rf"^face 2 is a sliver \(area {q:.1e} of a circle with "
                                        r"its perimeter\); the puzzle needs faces at least "
                                        r"0\.001 of that$"):
        check_layout(sliver, "the puzzle")
    thin = Mesh.from_faces(square + [(20, 0.015)], sliver.faces())
    assert 1e-3 < quotient(thin)[1] < 3e-3  # thin, not a sliver (nor a tenth of one)
    assert check_layout(thin, "the puzzle") is thin
    w = 0.0003185126899526086  # a 1 x w rectangle's quotient is 0.001 to the last bit
    limit = Mesh.from_faces([(0, 0), (1, 0), (1, w), (0, w)], [[0, 1, 2, 3]])
    assert check_layout(limit, "the puzzle") is limit  # at the limit: accepted
    # the isolated square last: its part has no shared edge to size the face graph by
    apart = Mesh.from_faces(SQUARE + [(3, 0), (4, 0), (4, 1), (3, 1), (1, 2), (0, 2)],
                            [[0, 1, 2, 3], [3, 2, 8, 9], [4, 5, 6, 7]])
    assert check_layout(apart, "the paper model") is apart
    with pytest.raises(MeshError, match=r"^the mesh has 2 separate parts; the paper model "
                                        r"needs one piece$"):
        check_layout(apart, "the paper model", connected=True)
    three = Mesh.from_faces(SQUARE + [(3, 0), (4, 0), (4, 1), (3, 1), (6, 0), (7, 0), (7, 1)],
                            [[4, 5, 6, 7], [0, 1, 2, 3], [8, 9, 10]])
    with pytest.raises(MeshError, match=r"^the mesh has 3 separate parts; the puzzle needs"):
        check_layout(three, "the puzzle", connected=True)
    with pytest.raises(MeshError, match=r"^the mesh is a surface in space \(x, y, z vertices\); "
                                        r"the puzzle needs a flat mesh so far$"):
        check_layout(Mesh.from_faces(*TETRAHEDRON), "the puzzle")
