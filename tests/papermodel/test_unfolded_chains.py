"""An unfolded strand measured against the weave and the mesh in space: its visits are the
strand's (a loop repeats its first), two pentagons per visit (the tile's own) joined along the
tile's middle edge, visits joined along the edge from a tip to its face centre, the reported
stretch is each edge's length in the plane over its length in space, the folds are the edges
neighbours share, their angles those between the pentagons' best-fit planes (from an
independent SVD), and a visit's tile polygon is its two pentagons joined."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from weavecut.inputs import get
from weavecut.papermodel.unfold import flatten, unfold
from weavecut.subdivision import subdivide
from weavecut.weave.snub_weave import snub_weaves


@pytest.mark.parametrize("name, levels", [("cube", 1), ("tetrahedron", 2)])
def test_an_unfolding_agrees_with_the_weave_and_the_mesh(name, levels):
    weave = snub_weaves(subdivide(get(name), levels, project="sphere"))[-1]
    dense = weave.mesh.dense_faces()
    flat = flatten(weave)
    for s in range(weave.n_strands):
        u = unfold(weave, s, flat)
        tiles, over = weave.strand(s)
        n = len(tiles)
        assert weave.strand_closed[s]
        assert u.strand == s
        assert u.visits.tolist() == [*range(n), 0]
        assert u.tiles.tolist() == [*tiles.tolist(), int(tiles[0])]
        assert u.over.tolist() == [*over.tolist(), bool(over[0])]
        assert u.face_visit.tolist() == np.repeat(np.arange(n + 1), 2).tolist()
        for v, t in enumerate(u.tiles.tolist()):  # each visit's two pentagons are its tile's
            own = weave.tile_faces[weave.tile_offsets[t]:weave.tile_offsets[t + 1]]
            assert sorted(u.faces[2 * v:2 * v + 2].tolist()) == sorted(own.tolist())
        p = weave.mesh.vertices[dense[u.faces]]  # (K, 5, 3)
        z = u.corners
        length3 = np.linalg.norm(np.roll(p, -1, axis=1) - p, axis=-1)
        assert np.allclose(u.stretch, np.abs(np.roll(z, -1, axis=1) - z) / length3 - 1,
                           atol=1e-12)
        ids = dense[u.faces]
        for k in range(len(u.faces) - 1):
            shared = np.intersect1d(ids[k], ids[k + 1])
            if k % 2:  # visit to visit: along the edge from a tip to its face centre (corner 0)
                assert ids[k, 0] == ids[k + 1, 0] and ids[k, 0] in shared, (s, k)
            else:  # a tile's two pentagons: along its middle edge, clear of the face centres
                assert ids[k, 0] not in shared and ids[k + 1, 0] not in shared, (s, k)
            here = np.sort_complex(z[k][np.isin(ids[k], shared)])
            assert np.array_equal(np.sort_complex(u.folds[k]), here)
            q = [p[j] - p[j].mean(axis=0) for j in (k, k + 1)]
            normals = [np.linalg.svd(a)[2][2] for a in q]
            angle = np.arccos(min(abs(normals[0] @ normals[1]), 1.0))
            assert u.fold_angles[k] == pytest.approx(angle, abs=1e-9)  # a convex ball: > 0
        # each pentagon is its flat self turned and moved: the corners it does not take from
        # the pentagon before keep their flat distances exactly (no scaling)
        for k in range(len(u.faces)):
            mine = np.ones(5, dtype=bool) if k == 0 else ~np.isin(ids[k], ids[k - 1])
            w = flat.coords[u.faces[k]][mine]
            assert np.allclose(np.abs(z[k][mine][:, None] - z[k][mine][None]),
                               np.abs(w[:, None] - w[None]), rtol=0, atol=1e-12)
        polygons = u.tile_polygons()
        assert len(polygons) == n + 1
        faces = shapely.polygons(np.stack([z.real, z.imag], axis=-1))
        assert np.allclose(shapely.area(polygons),
                           shapely.area(faces[0::2]) + shapely.area(faces[1::2]))
        assert shapely.equals(polygons[0], shapely.union(faces[0], faces[1]))


def test_folds_in_a_dent_are_valley_folds():
    """An icosahedron with one vertex pushed in nearly to the centre: its dent folds the other
    way. Every clear fold (over 0.15 rad) has the sign the hinge gives: with the faces' normals
    (independent SVD, turned by the corners' winding) and the shared edge a -> b as the earlier
    face runs round it, (n0 x n1) . (b - a) > 0 for a mountain fold."""
    from weavecut.mesh import Mesh
    ico = get("icosahedron")
    v = ico.vertices.copy()
    v[0] *= 0.05
    weave = snub_weaves(subdivide(Mesh(v, ico.face_offsets, ico.face_indices), 2))[-1]
    dense = weave.mesh.dense_faces()
    flat = flatten(weave)

    def normal(q):
        n = np.linalg.svd(q - q.mean(axis=0))[2][2]
        return n * np.sign(n @ np.cross(q, np.roll(q, -1, axis=0)).sum(axis=0))

    signs = []
    for s in range(weave.n_strands):
        u = unfold(weave, s, flat)
        ids = dense[u.faces]
        p = weave.mesh.vertices[ids]
        for k in np.flatnonzero(np.abs(u.fold_angles) > 0.15).tolist():
            here = np.isin(ids[k], ids[k + 1])
            i = next(j for j in range(5) if here[j] and here[(j + 1) % 5])
            hinge = np.cross(normal(p[k]), normal(p[k + 1])) @ (p[k][(i + 1) % 5] - p[k][i])
            assert np.sign(hinge) == np.sign(u.fold_angles[k]), (s, k)
            signs.append(np.sign(hinge))
    assert signs.count(-1) >= 10 and signs.count(1) >= 300


def test_the_strip_is_laid_out_from_the_flat_pentagons_it_is_given():
    """Turning every flat pentagon by its own angle changes no shape: the strip comes out the
    same, turned as a whole by the angle of its first pentagon (the others are fitted to it)."""
    import dataclasses
    weave = snub_weaves(subdivide(get("cube"), 1, project="sphere"))[-1]
    flat = flatten(weave)
    phase = np.exp(1j * np.random.default_rng(3).uniform(0, 2 * np.pi, len(flat.coords)))
    turned = dataclasses.replace(flat, coords=flat.coords * phase[:, None])
    for s in range(weave.n_strands):
        u, v = unfold(weave, s, flat), unfold(weave, s, turned)
        assert np.allclose(v.corners, u.corners * phase[u.faces[0]], atol=1e-9)
        assert np.allclose(v.stretch, u.stretch, atol=1e-9)
