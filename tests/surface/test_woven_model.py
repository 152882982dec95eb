"""The woven ball in 3-D: ribbon geometry, and the .obj/.glb/.png files read back by trimesh
(an independent glTF/OBJ loader) and Pillow."""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

from weavecut import inputs
from weavecut.cli import cli
from weavecut.subdivision import subdivide
from weavecut.weave.ribbons import ribbons, tile_normals
from weavecut.weave.snub_weave import snub_weaves

pytestmark = pytest.mark.slow  # woven 3D models read back by trimesh

trimesh = pytest.importorskip("trimesh")


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.fixture(scope="module")
def weave():
    return snub_weaves(subdivide(inputs.get("dodecahedron"), 2, project="sphere"))[-1]


def test_ribbons_pass_over_and_under_by_twice_the_lift(weave):
    lift, width = 0.01, 0.05
    model = ribbons(weave, width, lift)
    n = len(weave.strand_visits)
    assert len(model.triangles) == 4 * n  # a quad from every visit and every crossing
    left, right = model.vertices[0::2], model.vertices[1::2]
    np.testing.assert_allclose(np.linalg.norm(left - right, axis=1), width, rtol=1e-12)
    centre = (left + right)[0::2] / 2  # the centre line at the visits
    tile = weave.strand_visits
    height = np.einsum("ij,ij->i", centre - weave.tile_centres[tile], tile_normals(weave)[tile])
    np.testing.assert_allclose(height, np.where(weave.visit_over, lift, -lift), atol=1e-15)
    # at every octagon the strand on top is 2 lift above the one below
    over = np.zeros(weave.n_tiles)
    np.add.at(over, tile, np.where(weave.visit_over, height, -height))
    np.testing.assert_allclose(over, 2 * lift, rtol=1e-12)


def test_ribbon_triangles_face_outwards(weave):
    model = ribbons(weave, 0.05, 0.0)
    c = model.vertices[model.triangles]
    normal = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    assert (np.einsum("ij,ij->i", normal, c.mean(axis=1)) > 0).all()


@pytest.fixture(scope="module")
def ball_files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ball")
    for suffix in ("obj", "glb", "png"):
        result = run("weave", "dodecahedron", "--levels", 1, "--size", "150mm",
                     "-o", folder / f"ball.{suffix}")
        assert result.exit_code == 0, result.output
    return folder


@pytest.mark.parametrize("suffix, metres, sides", [("glb", 1.0, 1), ("obj", 1000.0, 2)])
def test_model_reads_back_in_trimesh_at_the_asked_diameter(ball_files, suffix, metres, sides):
    mesh = trimesh.load(ball_files / f"ball.{suffix}", force="mesh", process=False)
    # 60 visits (30 octagons), each an octagon whose four corners where three tiles meet are
    # cut (12 outline points), 3 triangles per point; the .obj repeats them facing in (the
    # .glb's materials are double-sided)
    assert len(mesh.faces) == sides * 60 * 12 * 3
    radius = np.linalg.norm(mesh.vertices - mesh.vertices.mean(axis=0), axis=1).max()
    # the flat strips span 150 mm; lifted by the 0.5 mm paper (and 2 % more, as flat
    # triangles between points of a sphere sag) they stick out by that
    assert 0.150 < 2 * radius / metres <= 0.150 + 2 * 0.00051
    if suffix == "obj":
        colours = np.unique(np.asarray(mesh.visual.vertex_colors)[:, :3], axis=0)
    else:
        scene = trimesh.load(ball_files / "ball.glb")
        colours = {tuple(g.visual.material.baseColorFactor) for g in scene.geometry.values()}
    assert len(colours) == 6  # one colour per strand


def test_png_views_show_the_ball(ball_files):
    image = Image.open(ball_files / "ball.png")
    assert image.size == (960, 960) and image.info["Title"].startswith("dodecahedron")
    pixels = np.asarray(image.convert("RGB")).reshape(-1, 3)
    assert 0.3 < (pixels != 255).any(axis=1).mean() < 0.9  # four balls with gaps between


def test_models_are_the_same_bytes_every_time(ball_files, tmp_path):
    for suffix in ("obj", "glb"):
        run("weave", "dodecahedron", "--levels", 1, "--size", "150mm", "-o",
            tmp_path / f"again.{suffix}")
        again = (tmp_path / f"again.{suffix}").read_bytes()
        first = (ball_files / f"ball.{suffix}").read_bytes()
        if suffix == "obj":  # the command line is in the comments
            again, first = (b"\n".join(x for x in d.splitlines() if not x.startswith(b"#"))
                            for d in (again, first))
        assert again == first


def test_a_flat_weave_is_no_3d_model(tmp_path):
    result = run("weave", "pentagon", "--levels", 2, "-o", tmp_path / "x.glb")
    assert result.exit_code == 1 and "needs a surface in space" in result.output
    assert not list(tmp_path.iterdir())
