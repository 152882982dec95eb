"""The pentagon snub step against the paper: counts, degrees, Z geometry, smoothing, symmetry."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from hypothesis import given

from tests import meshes
from tests.strategies import valid_meshes
from weavecut import inputs
from weavecut.cli import cli
from weavecut.mesh_io import read_mesh, write_mesh
from weavecut.mesh import Mesh, Topology, outer_vertices, vertex_degrees
from weavecut.mesh_geometry import corner_angles, edge_lengths, mirrored, signed_areas
from weavecut.subdivision import snub, subdivide
from weavecut.validation import validate

BUILTINS = ["pentagon", "ngon:7", "triangulated-ngon:6", "square-grid:3x2", "tiling-8-4:2x2",
            "pentagon-flower", "triangle-grid:2x2", "hex-grid:2x2"]


def eq2(mesh: Mesh, levels: int):
    """(V, E, F) per level from the paper's eq. (2), computed here independently."""
    v, e, f = mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces
    corners = mesh.n_corners
    out = [(v, e, f)]
    for _ in range(levels):
        v, e, f, corners = v + 2 * e + f, 3 * e + corners, corners, 5 * corners
        out.append((v, e, f))
    return out


@pytest.mark.parametrize("name", BUILTINS)
def test_counts_follow_equation_2(name):
    mesh = inputs.get(name)
    levels = 5 if mesh.n_faces < 8 else 4
    hierarchy = subdivide(mesh, levels)
    got = [(lv.mesh.n_vertices, Topology.build(lv.mesh).n_edges, lv.mesh.n_faces)
           for lv in hierarchy]
    assert got == eq2(mesh, levels)
    assert all(lv.mesh.face_degree == 5 for lv in hierarchy[1:])


def test_pentagon_counts_follow_equation_1():
    hierarchy = subdivide(inputs.get("pentagon"), 6)
    for prev, cur in zip(hierarchy, hierarchy[1:]):
        v, e, f = prev.mesh.n_vertices, prev.mesh.topology.n_edges, prev.mesh.n_faces
        assert cur.mesh.n_vertices == v + 2 * e + f
        assert cur.mesh.topology.n_edges == 3 * e + 5 * f
        assert cur.mesh.n_faces == 5 * f


def _check_derived_topology(mesh: Mesh) -> None:
    """The topology a step derives equals the one built from scratch by sorting."""
    derived, built = mesh.topology, Topology.build(mesh)
    assert set(map(tuple, derived.edges.tolist())) == set(map(tuple, built.edges.tolist()))
    assert (derived.edges[:, 0] < derived.edges[:, 1]).all()
    u = mesh.face_indices
    w = u[mesh.next_half_edge]
    e = derived.edges[derived.half_edge_edge]
    s = derived.half_edge_side
    assert (np.where(s == 0, e[:, 0], e[:, 1]) == u).all()
    assert (np.where(s == 0, e[:, 1], e[:, 0]) == w).all()
    assert (derived.boundary_edges == (derived.edge_half_edges < 0).any(axis=1)).all()
    assert derived.boundary_edges.sum() == built.boundary_edges.sum()


def _check_degrees(hierarchy) -> None:
    """Input vertices keep their degree; inner vertices born from step 2 on have degree 3 or 5;
    new outer vertices have degree 2 or 3."""
    first = hierarchy[0].mesh
    n0 = first.n_vertices
    deg0 = vertex_degrees(first)
    for t in range(1, len(hierarchy)):
        mesh = hierarchy[t].mesh
        deg = vertex_degrees(mesh)
        outer = outer_vertices(mesh)
        assert (deg[:n0] == deg0).all()
        born_after_1 = np.arange(mesh.n_vertices) >= hierarchy[1].mesh.n_vertices
        assert np.isin(deg[born_after_1 & ~outer], [3, 5]).all()
        new = np.arange(mesh.n_vertices) >= n0
        assert np.isin(deg[new & outer], [2, 3]).all()


def _check_boundary(hierarchy) -> None:
    """Outer vertices never move; a level-t boundary edge is L / sqrt(7)^t of its ancestor."""
    first = hierarchy[0].mesh
    ancestor = np.arange(first.topology.n_edges)
    for t in range(1, len(hierarchy)):
        level, prev = hierarchy[t], hierarchy[t - 1].mesh
        mesh = level.mesh
        zpart = level.edge_part != snub.SPOKE
        ancestor = np.where(zpart, ancestor[np.minimum(level.parent_edge, len(ancestor) - 1)], -1)
        b = mesh.topology.boundary_edges
        assert (ancestor[b] >= 0).all()
        expect = edge_lengths(first)[ancestor[b]] / math.sqrt(7) ** t
        np.testing.assert_allclose(edge_lengths(mesh)[b], expect, rtol=1e-9)
        keep = outer_vertices(prev)
        np.testing.assert_array_equal(mesh.vertices[:prev.n_vertices][keep], prev.vertices[keep])


@pytest.mark.parametrize("name", BUILTINS)
def test_degree_and_boundary_facts_on_builtins(name):
    hierarchy = subdivide(inputs.get(name), 3)
    _check_degrees(hierarchy)
    _check_boundary(hierarchy)
    for lv in hierarchy[1:]:
        _check_derived_topology(lv.mesh)
        assert (signed_areas(lv.mesh) > 0).all()


@given(valid_meshes)
def test_facts_hold_on_random_meshes(mesh):
    hierarchy = subdivide(mesh, 3)
    assert [(lv.mesh.n_vertices, lv.mesh.topology.n_edges, lv.mesh.n_faces)
            for lv in hierarchy] == eq2(mesh, 3)
    _check_degrees(hierarchy)
    _check_boundary(hierarchy)
    for lv in hierarchy[1:]:
        _check_derived_topology(lv.mesh)


@pytest.mark.parametrize("chirality", snub.CHIRALITIES)
def test_z_triplet_geometry(chirality):
    mesh = inputs.get("square-grid:2x2")
    level = snub.step(mesh, smooth=False, chirality=chirality)
    child = level.mesh
    topo = mesh.topology
    assert snub.ALPHA == pytest.approx(math.atan(math.sqrt(3) / 5))
    lengths = edge_lengths(child).reshape(-1)[: 3 * topo.n_edges].reshape(-1, 3)
    np.testing.assert_allclose(lengths, edge_lengths(mesh)[:, None] / math.sqrt(7) * np.ones(3))
    v = child.vertices
    n_v = mesh.n_vertices
    u, w = v[topo.edges[:, 0]], v[topo.edges[:, 1]]
    z0, z1 = v[n_v::2][: topo.n_edges], v[n_v + 1::2][: topo.n_edges]

    def angle(p, q, r):  # angle at q
        a, b = p - q, r - q
        return np.degrees(np.arccos((a * b).sum(1) / np.hypot(*a.T) / np.hypot(*b.T)))

    np.testing.assert_allclose(angle(u, z0, z1), 120.0)
    np.testing.assert_allclose(angle(z0, z1, w), 120.0)
    d, first = w - u, z0 - u
    turn = np.degrees(np.arctan2(d[:, 0] * first[:, 1] - d[:, 1] * first[:, 0],
                                 (d * first).sum(1)))
    sign = 1 if chirality == "left" else -1
    np.testing.assert_allclose(turn, sign * math.degrees(snub.ALPHA))


@pytest.mark.parametrize("mesh", [meshes.two_squares(), meshes.mixed(), inputs.get("pentagon")],
                         ids=["two-squares", "mixed", "pentagon"])
@pytest.mark.parametrize("smooth", [False, True])
def test_matches_loop_reference(mesh, smooth):
    once = snub.step(mesh, smooth=smooth).mesh
    assert meshes.face_set(meshes.mesh_face_points(once)) == meshes.face_set(
        meshes.reference_snub_step(mesh, smooth))
    twice = snub.step(once, smooth=smooth).mesh
    assert meshes.face_set(meshes.mesh_face_points(twice)) == meshes.face_set(
        meshes.reference_snub_step(once, smooth))


def test_smoothing_by_hand_on_two_squares():
    """Two unit squares: the inner Z vertex of the shared edge moves to the mean of the
    centroids of its three pentagons, computed here by hand from the Z formula."""
    mesh = meshes.two_squares()
    raw = snub.step(mesh, smooth=False).mesh
    smoothed = snub.step(mesh, smooth=True).mesh
    e = int(np.flatnonzero((mesh.topology.edges == [1, 4]).all(axis=1))[0])
    z = mesh.n_vertices + 2 * e  # z0 of the shared edge (1,0)->(1,1): (1 - sqrt3/14, 5/14)
    np.testing.assert_allclose(raw.vertices[z], [1 - math.sqrt(3) / 14, 5 / 14])
    faces = [f for f in raw.faces() if z in f]
    assert len(faces) == 3
    expect = np.mean([raw.vertices[f].mean(axis=0) for f in faces], axis=0)
    np.testing.assert_allclose(smoothed.vertices[z], expect)
    # the outer vertices stay, and the centres of the squares move
    np.testing.assert_array_equal(smoothed.vertices[:6], raw.vertices[:6])


@pytest.mark.parametrize("name", ["pentagon", "square-grid:2x2", "triangulated-ngon:5"])
def test_mirror_with_opposite_chirality_gives_the_mirror(name):
    mesh = inputs.get(name)
    left = subdivide(mesh, 3, chirality="left")[-1].mesh
    right = subdivide(mirrored(mesh), 3, chirality="right")[-1].mesh
    assert meshes.face_set(meshes.mirror_points(meshes.mesh_face_points(left))) == \
        meshes.face_set(meshes.mesh_face_points(right))
    other = subdivide(mirrored(mesh), 3, chirality="left")[-1].mesh
    assert meshes.face_set(meshes.mirror_points(meshes.mesh_face_points(left))) != \
        meshes.face_set(meshes.mesh_face_points(other))


def _centres(mesh, centre):
    """Face centres by an independent rule: shapely's area centroid, or the vertex mean."""
    if centre == "area":
        return np.array([shapely.Polygon(mesh.vertices[f]).centroid.coords[0]
                         for f in mesh.faces()])
    return np.array([mesh.vertices[f].mean(axis=0) for f in mesh.faces()])


@pytest.mark.parametrize("centre", snub.CENTRES)
@pytest.mark.parametrize("make", [meshes.mixed, lambda: inputs.get("pentagon-flower")])
def test_smoothing_moves_inner_vertices_to_the_mean_of_the_chosen_centres(make, centre):
    """Operation 4 by hand: every inner vertex of the unsmoothed child moves to the mean centre
    (of the kind asked for) of the child faces around it; outer vertices stay. On these inputs
    the two kinds of centre differ, so the smoothed meshes differ too."""
    raw = snub.step(make(), smooth=False, centre=centre).mesh
    smoothed = snub.step(make(), smooth=True, centre=centre).mesh
    centres, faces = _centres(raw, centre), raw.faces()
    inner = ~outer_vertices(raw)
    want = raw.vertices.copy()
    for v in np.flatnonzero(inner):
        want[v] = centres[[k for k, f in enumerate(faces) if v in f]].mean(axis=0)
    np.testing.assert_allclose(smoothed.vertices, want, atol=1e-12)
    other = "vertex" if centre == "area" else "area"
    assert not np.allclose(smoothed.vertices, snub.step(make(), centre=other).mesh.vertices)


def test_cli_passes_centre_area_to_the_smoothing(tmp_path):
    source = tmp_path / "mixed.obj"
    write_mesh(meshes.mixed(), source)
    for centre in snub.CENTRES:
        out = tmp_path / f"{centre}.json"
        result = CliRunner().invoke(cli, ["subdivide", str(source), "--levels", "1",
                                          "--centre", centre, "-o", str(out)])
        assert result.exit_code == 0, result.output
        want = snub.step(validate(read_mesh(source)), centre=centre).mesh
        np.testing.assert_allclose(read_mesh(out).vertices, want.vertices, atol=1e-9)


def test_area_centre_option_differs_only_for_irregular_faces():
    square = snub.step(meshes.square(), centre="area").mesh
    np.testing.assert_allclose(square.vertices[-1], [0.5, 0.5])
    mixed_v = snub.step(meshes.mixed(), smooth=False, centre="vertex").mesh.vertices
    mixed_a = snub.step(meshes.mixed(), smooth=False, centre="area").mesh.vertices
    assert not np.allclose(mixed_v[-1], mixed_a[-1])  # the irregular pentagon's centre
    np.testing.assert_array_equal(mixed_v[:-3], mixed_a[:-3])


def test_provenance_points_into_the_parent():
    mesh = inputs.get("pentagon-flower")
    parent, child = subdivide(mesh, 2)[1:]
    pm = parent.mesh
    assert (child.parent_face == pm.half_edge_face).all()
    # every child face contains the parent corner vertex it was made for (left chirality: b)
    b = pm.face_indices[pm.next_half_edge]
    assert (child.mesh.dense_faces()[:, 3] == b).all()
    # middle edges are local edge 1 of their faces
    middle = child.mesh.topology.half_edge_edge.reshape(-1, 5)[:, 1]
    assert (child.edge_part[middle] == snub.MIDDLE).all()
    assert (child.edge_part == snub.MIDDLE).sum() == pm.topology.n_edges


def test_angles_stay_in_range_and_faces_convex_on_pentagon():
    mesh = subdivide(inputs.get("pentagon"), 5)[-1].mesh
    angles = np.degrees(corner_angles(mesh))
    assert angles.max() < 180 and angles.min() > 0
