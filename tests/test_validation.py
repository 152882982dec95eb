"""Validation of input meshes: orientation, zero area, convexity, overlaps."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from tests import meshes
from tests.strategies import examples, valid_meshes
from weavecut import inputs
from weavecut.errors import MeshError
from weavecut.mesh import Mesh
from weavecut.mesh_geometry import signed_areas
from weavecut.validation import validate


@pytest.mark.parametrize("spec", [
    *inputs.INPUTS, "ngon:3", "ngon:10000", "triangulated-ngon:3", "triangulated-ngon:300",
    "square-grid:1x1", "square-grid:1x7", "tiling-8-4:1x1", "tiling-8-4:2x1", "tiling-8-4:7x5",
    "triangle-grid:1x1", "triangle-grid:9x4", "hex-grid:1x1", "hex-grid:1x2", "hex-grid:8x5",
    "icosphere:0", "icosphere:4"])
def test_builtin_inputs_are_valid_as_built(spec):
    # the command line uses them without validating them
    mesh = inputs.get(spec)
    assert validate(mesh) is mesh


def test_clockwise_mesh_is_reoriented():
    mesh = meshes.two_squares().reversed()
    assert (signed_areas(mesh) < 0).all()
    fixed = validate(mesh)
    assert (signed_areas(fixed) > 0).all()
    # the same points, each face's corners in the opposite order
    np.testing.assert_array_equal(fixed.vertices, mesh.vertices)
    assert [set(zip(f, f[1:] + f[:1])) for f in fixed.faces()] == \
        [set(zip(f[1:] + f[:1], f)) for f in mesh.faces()]


@pytest.mark.parametrize("clockwise", [[0, 1], [0, 2], [1, 2], [0], [2]])
def test_a_mesh_mostly_or_partly_clockwise_is_refused_not_reoriented(clockwise):
    """Only a mesh whose faces are all clockwise is turned; two of three (or one of three)
    clockwise faces are an error that names the first clockwise face and the count."""
    v = [(0, 0), (1, 0), (2, 0), (3, 0), (0, 1), (1, 1), (2, 1), (3, 1)]
    faces = [[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6]]
    faces = [f[::-1] if k in clockwise else f for k, f in enumerate(faces)]
    with pytest.raises(MeshError, match=rf"^face {clockwise[0]} is clockwise while others are "
                                        rf"counter-clockwise \({len(clockwise)} of 3 faces"):
        validate(Mesh.from_faces(v, faces))


def test_mixed_orientation_is_an_error():
    v = [(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (0, 1)]
    mesh = Mesh.from_faces(v, [[0, 1, 4, 5], [1, 4, 3, 2]])
    with pytest.raises(MeshError, match="face 1 is clockwise"):
        validate(mesh)


def test_zero_area_face():
    mesh = Mesh.from_faces([(0, 0), (1, 0), (2, 0)], [[0, 1, 2]])
    with pytest.raises(MeshError, match="face 0 has zero area"):
        validate(mesh)


def test_nonconvex_face_is_an_error_unless_allowed():
    v = [(0, 0), (2, 0), (2, 2), (1, 0.5), (0, 2)]
    mesh = Mesh.from_faces(v, [[0, 1, 2, 3, 4]])
    with pytest.raises(MeshError, match="face 0 is not convex at vertex 3"):
        validate(mesh)
    assert validate(mesh, allow_nonconvex=True).n_faces == 1


def test_overlapping_faces():
    v = [(0, 0), (2, 0), (2, 2), (0, 2), (1, 1), (3, 1), (3, 3), (1, 3)]
    mesh = Mesh.from_faces(v, [[0, 1, 2, 3], [4, 5, 6, 7]])
    with pytest.raises(MeshError, match="overlap"):
        validate(mesh)


def test_self_intersecting_face():
    v = [(0, 0), (2, 2), (2, 0), (0, 3)]
    mesh = Mesh.from_faces(v, [[0, 1, 2, 3]])  # a bow-tie quad with positive area
    with pytest.raises(MeshError, match="face 0 intersects itself"):
        validate(mesh, allow_nonconvex=True)


def test_empty_mesh():
    with pytest.raises(MeshError, match="no faces"):
        validate(Mesh(np.zeros((0, 2)), [0], []))


def test_valid_meshes_pass_unchanged():
    mesh = meshes.mixed()
    assert validate(mesh) is mesh


def test_face_nested_inside_another_and_folded_fans():
    outer = [(0, 0), (4, 0), (4, 4), (0, 4)]
    inner = [(1, 1), (2, 1), (2, 2), (1, 2)]
    mesh = Mesh.from_faces(outer + inner, [[0, 1, 2, 3], [4, 5, 6, 7]])
    with pytest.raises(MeshError, match="lies inside face 0"):
        validate(mesh)
    # six triangles around a vertex that turn around it twice (each CCW, no edge shared twice)
    t = np.linspace(0, 4 * np.pi, 7)[:-1] + 0.1
    ring = [(float(np.cos(a)), float(np.sin(a))) for a in t]
    fan = Mesh.from_faces([(0.0, 0.0)] + ring, [[0, 1 + i, 1 + (i + 1) % 6] for i in range(6)])
    with pytest.raises(MeshError, match="overlap"):
        validate(fan)


def test_huge_coordinates_are_refused():
    mesh = Mesh.from_faces([(0, 0), (1e300, 0), (0, 1)], [[0, 1, 2]])
    with pytest.raises(MeshError, match="beyond"):
        validate(mesh)


@settings(max_examples=examples(150), deadline=None)
@given(valid_meshes, st.integers(0, 2**32 - 1), st.floats(0.05, 1.5))
def test_verdict_agrees_with_polygon_union(mesh, seed, reach):
    """Move one vertex at random; validate must accept the mesh exactly when its faces are
    simple polygons whose union has the sum of their areas (no overlap), name the first face
    that crosses itself, and refuse non-convex faces unless allowed (hull area > area)."""
    rng = np.random.default_rng(seed)
    v = mesh.vertices.copy()
    v[rng.integers(len(v))] += rng.normal(size=2) * reach * np.ptp(v, axis=0).max()
    moved = Mesh(v, mesh.face_offsets, mesh.face_indices)
    areas = signed_areas(moved)
    assume((areas > 1e-6 * areas.max()).all())  # orientation and zero area are tested above
    polys = np.array([shapely.Polygon(v[f]) for f in moved.faces()])
    simple = shapely.is_valid(polys)
    embedded = simple.all() and (  # the union of invalid polygons is not defined
        abs(shapely.union_all(polys).area - areas.sum()) < 1e-9 * areas.sum())
    convex = np.abs(shapely.area(shapely.convex_hull(polys)) - areas) < 1e-9 * areas.max()
    for allow in (True, False):
        try:
            validate(moved, allow_nonconvex=allow)
            verdict = "valid"
        except MeshError as exc:
            verdict = str(exc)
        if not allow and not convex.all():
            assert "not convex" in verdict
        elif not simple.all():
            assert verdict.startswith(f"face {np.flatnonzero(~simple)[0]} intersects itself")
        else:
            assert (verdict == "valid") == embedded, verdict


@pytest.mark.parametrize("allow", [False, True])
def test_a_star_that_turns_left_at_every_corner_intersects_itself(allow):
    t = np.pi / 2 + 2 * np.pi * np.arange(5) / 5
    star = Mesh.from_faces(np.column_stack([np.cos(t), np.sin(t)]), [[0, 2, 4, 1, 3]])
    assert signed_areas(star)[0] > 0  # it winds round twice, always turning left
    with pytest.raises(MeshError, match="face 0 intersects itself"):
        validate(star, allow_nonconvex=allow)


@settings(max_examples=60)
@given(st.sampled_from([1e-6, 1e-3, 1.0, 1e3, 1e6]), st.sampled_from([0.0, 10.0]))
def test_flat_and_reflex_thresholds_are_relative_to_the_mesh_size(scale, lift):
    """The zero-area and reflex-corner tests compare with AREA_EPS times the squared largest
    side of the bounding box, whatever the size and position: a sliver of relative area
    0.5e-12 is flat and one of 4e-12 is not; a corner turning by -0.25e-12 (relative) is
    straight enough, one turning by -8e-12 is reflex."""
    from weavecut.validation import validate

    def mesh(points, faces):
        return Mesh.from_faces(scale * (np.array(points) + [0.0, lift]), faces)

    with pytest.raises(MeshError, match="^face 0 has zero area"):
        validate(mesh([(0, 0), (1, 0), (0.5, 1e-12)], [[0, 1, 2]]))
    validate(mesh([(0, 0), (1, 0), (0.5, 8e-12)], [[0, 1, 2]]))
    dent = [(0, 0), (1, 0), (1, 1), (0.5, 1 - 0.25e-12), (0, 1)]
    validate(mesh(dent, [[0, 1, 2, 3, 4]]))
    dent[3] = (0.5, 1 - 8e-12)
    with pytest.raises(MeshError, match="^face 0 is not convex at vertex 3"):
        validate(mesh(dent, [[0, 1, 2, 3, 4]]))


def test_mixed_orientation_names_the_first_clockwise_face_and_counts_them():
    """The message names the first clockwise face (not merely a small one) and the count."""
    from weavecut.validation import validate
    m = Mesh.from_faces([(0, 0), (0.1, 0), (0, 0.1), (2, 0), (2, 1), (3, 0)],
                        [[0, 1, 2], [3, 4, 5]])
    with pytest.raises(MeshError, match=r"^face 1 is clockwise while others are "
                                        r"counter-clockwise \(1 of 2 faces are clockwise\)$"):
        validate(m)


def test_a_mesh_without_faces_is_refused_in_words():
    from weavecut.validation import validate
    with pytest.raises(MeshError, match="^the mesh has no faces$"):
        validate(Mesh.from_faces([(0, 0), (1, 0), (0, 1)], []))


def test_a_face_wholly_inside_another_far_from_the_origin_is_found():
    """A small triangle inside a big one (no edges cross; only the boundary-vertex test sees
    it), the big one second and far from the origin, the small one near its corner: the
    prefilter's circle is centred on the big face's own vertex mean."""
    from weavecut.validation import validate
    points = [(100, 100), (101, 100), (100, 101),  # face 0, apart
              (50, 50), (60, 50), (50, 60),  # face 1, the big one
              (50.5, 50.5), (51, 50.5), (50.5, 51)]  # face 2, inside face 1 near vertex 3
    with pytest.raises(MeshError, match=r"^vertex 6 lies inside face 1 \(faces overlap\)$"):
        validate(Mesh.from_faces(points, [[0, 1, 2], [3, 4, 5], [6, 7, 8]]))
