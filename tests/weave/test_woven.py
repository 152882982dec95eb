"""The woven 3-D model as a viewer gets it: written to glTF binary, read back by trimesh, and
checked against the weave it was made from, on the woven ball, the cube, and both flat paper
models. No holes (the strips seen along the surface's normal cover it), normals that point
out and are shared within a strip (smooth shading), the strip on top clearing the one below
by the thickness, the palette's colours, metres.

The coverage and clearance oracle casts a line along the surface's normal through points
trimesh samples evenly on the weave's surface (the sphere's radius for a ball, the vertical
for a flat model) and finds every triangle of every strip it meets, by barycentric
coordinates (trimesh), independently of how the model was built.
"""

from __future__ import annotations

import io

import numpy as np
import pytest

from weavecut.export.gltf import glb_bytes, linear
from weavecut.inputs import get
from weavecut.subdivision import subdivide
from weavecut.surface import circumsphere
from weavecut.weave import woven
from weavecut.weave.colour import palette, strand_colours
from weavecut.weave.snub_weave import snub_weaves
from weavecut.weave.woven import woven_mm

trimesh = pytest.importorskip("trimesh")

THICKNESS = 0.5  # mm
SAMPLES = 12_000
CASES = {"ball": ("dodecahedron", 1, "sphere", 120.0), "cube": ("cube", 2, "sphere", 120.0),
         "square-grid": ("square-grid", 2, None, 270.0),
         "pentagon-flower": ("pentagon-flower", 3, None, 230.0)}


def build(case: str):
    name, levels, project, size = CASES[case]
    weaves = snub_weaves(subdivide(get(name), levels, project=project))
    weave = weaves[-1]
    colours = strand_colours(weaves, palette("maritime-12"))
    v = weave.mesh.vertices
    mm = size / float(np.ptp(v, axis=0).max())
    return weave, colours, mm, woven_mm(weave, colours, mm, THICKNESS)


def read_back(data: bytes):
    """(vertices mm z-up, faces, vertex normals, part, material colours) from a .glb."""
    scene = trimesh.load(io.BytesIO(data), file_type="glb")
    parts = list(scene.geometry.values())
    back = lambda p: np.column_stack([p[:, 0], -p[:, 2], p[:, 1]])  # glTF y-up -> z-up
    offsets = np.cumsum([0] + [len(g.vertices) for g in parts])
    return (np.concatenate([back(g.vertices) * 1000 for g in parts]),
            np.concatenate([g.faces + o for g, o in zip(parts, offsets)]),
            np.concatenate([back(g.vertex_normals) for g in parts]),
            np.repeat(np.arange(len(parts)), [len(g.faces) for g in parts]),
            [tuple(g.visual.material.baseColorFactor.tolist()) for g in parts])


@pytest.fixture(scope="module", params=list(CASES))
def case(request):
    weave, colours, mm, model = build(request.param)
    data = glb_bytes(model)
    return request.param, weave, colours, mm, model, read_back(data), data


def base_surface(weave, mm, model):
    """The weave's surface in the model's mm frame, as a trimesh, and its centre (sphere) or
    None (flat)."""
    mesh = weave.mesh
    v = mesh.vertices if mesh.dim == 3 else np.column_stack([mesh.vertices,
                                                             np.zeros(mesh.n_vertices)])
    faces = mesh.dense_faces()
    fan = np.concatenate([faces[:, [0, i, i + 1]] for i in range(1, faces.shape[1] - 1)])
    raw = woven.woven_model(weave, ["#000000"] * weave.n_strands, 0.0).vertices
    centre_raw = (raw.max(axis=0) + raw.min(axis=0)) / 2
    surface = trimesh.Trimesh((v - centre_raw) * mm, fan, process=False)
    centre = None
    if mesh.dim == 3:
        centre = (circumsphere(mesh.vertices)[0] - centre_raw) * mm
    return surface, centre


def crossings(vertices, faces, part, points, centre):
    """Every (point, height along the line from it, part) where the line through each point
    along the surface's normal (vertical, or from the ``centre`` of a sphere) meets a
    triangle; heights from the point outwards."""
    tri = vertices[faces]
    if centre is None:
        directions = np.tile([0.0, 0.0, 1.0], (len(points), 1))
        key, corner_key = points[:, :2], tri[:, :, :2]
    else:
        directions = (points - centre) / np.linalg.norm(points - centre, axis=1)[:, None]
        key = directions
        corner_key = (tri - centre) / np.linalg.norm(tri - centre, axis=2)[:, :, None]
    pad = 1e-6 if centre is None else 0.05  # a unit direction between corners bulges out
    lo_box, hi_box = corner_key.min(axis=1) - pad, corner_key.max(axis=1) + pad
    # candidate (point, triangle) pairs: the point's key inside the triangle's box
    order = np.argsort(key[:, 0], kind="stable")
    first = np.searchsorted(key[order, 0], lo_box[:, 0])
    last = np.searchsorted(key[order, 0], hi_box[:, 0], side="right")
    count = last - first
    ti = np.repeat(np.arange(len(tri)), count)
    pi = order[np.repeat(first, count) + np.arange(count.sum())
               - np.repeat(np.cumsum(count) - count, count)]
    inbox = ((key[pi] >= lo_box[ti]) & (key[pi] <= hi_box[ti])).all(axis=1)
    pi, ti = pi[inbox], ti[inbox]
    a, b, c = tri[ti, 0], tri[ti, 1], tri[ti, 2]
    n = np.cross(b - a, c - a)
    d = directions[pi]
    denom = (n * d).sum(axis=1)
    ok = np.abs(denom) > 1e-12
    t = np.where(ok, ((a - points[pi]) * n).sum(axis=1) / np.where(ok, denom, 1), np.inf)
    near = ok & (np.abs(t) < 10 * THICKNESS)
    hit = points[pi[near]] + t[near, None] * d[near]
    bary = trimesh.triangles.points_to_barycentric(tri[ti[near]], hit)
    inside = (bary >= -1e-9).all(axis=1)
    return np.column_stack([pi[near][inside], t[near][inside], part[ti[near][inside]]])


@pytest.fixture(scope="module")
def sampled(case):
    name, weave, colours, mm, model, (v, f, vn, part, mats), data = case
    surface, centre = base_surface(weave, mm, model)
    points, _ = trimesh.sample.sample_surface_even(surface, SAMPLES, seed=7)
    hits = crossings(v, f, part, points, centre)
    return points, hits


def test_the_strips_cover_the_surface_but_for_the_cut_corners(case, sampled):
    points, hits = sampled
    covered = np.unique(hits[:, 0].astype(int))
    share = len(covered) / len(points)
    print(f"{case[0]}: coverage {100 * share:.2f} %")
    assert share >= 0.995


def test_the_strip_on_top_clears_the_one_below_by_the_thickness(case, sampled):
    points, hits = sampled
    order = np.lexsort((hits[:, 1], hits[:, 0]))
    h = hits[order]
    same_point = h[1:, 0] == h[:-1, 0]
    other_strand = h[1:, 2] != h[:-1, 2]
    gaps = (h[1:, 1] - h[:-1, 1])[same_point & other_strand]
    assert len(gaps) > len(points) // 2  # most points lie under two strips
    print(f"{case[0]}: smallest clearance {gaps.min():.4f} mm")
    # the only tolerance: the .glb holds float32 metres (a relative 1e-7)
    assert gaps.min() >= THICKNESS * (1 - 1e-5)


def test_normals_point_out_and_are_shared_within_a_strip(case):
    name, weave, colours, mm, model, (v, f, vn, part, mats), data = case
    surface, centre = base_surface(weave, mm, model)
    corners = v[f]
    face_n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    mid = corners.mean(axis=1)
    out = np.tile([0.0, 0.0, 1.0], (len(f), 1)) if centre is None else mid - centre
    assert ((face_n * out).sum(axis=1) > 0).all()  # every triangle faces out
    vertex_out = np.tile([0.0, 0.0, 1.0], (len(v), 1)) if centre is None else v - centre
    assert ((vn * vertex_out).sum(axis=1) > 0).all()
    # a strip is one piece whose triangles share their corners: shading runs smoothly over it
    for p in np.unique(part):
        mesh = trimesh.Trimesh(v, f[part == p], process=False)
        mesh.remove_unreferenced_vertices()
        assert len(trimesh.graph.connected_components(mesh.face_adjacency,
                                                      nodes=np.arange(len(mesh.faces)))) == 1
        assert len(np.unique(np.round(mesh.vertices, 6), axis=0)) == len(mesh.vertices)


def test_colours_are_the_palettes_and_lengths_are_metres(case):
    name, weave, colours, mm, model, (v, f, vn, part, mats), data = case
    want = [tuple(round(255 * x) for x in linear(colours[s])) for s in range(weave.n_strands)]
    assert mats == want
    span = np.ptp(v, axis=0)
    assert abs(span.max() - CASES[name][3]) < 0.05 * CASES[name][3] + 2 * THICKNESS


def test_the_same_weave_gives_the_same_bytes(case):
    name, weave, colours, mm, model, *_ = case
    assert glb_bytes(woven_mm(weave, colours, mm, THICKNESS)) == case[-1]
