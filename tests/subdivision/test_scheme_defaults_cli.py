"""Each documented default of a scheme's parameter, seen through the command line.

``weave-cut subdivide --help`` documents --levels 1, --scheme snub, --chirality left,
--centre vertex and smoothing on (--no-smooth off). Leaving an option out must give the same
mesh as writing the documented value, and a different mesh from every other value, so a
changed default fails here. The classic schemes take no parameter on the command line; their
positions through it are checked against the independent stencils.
"""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.mesh import Mesh
from weavecut.mesh_io import read_mesh, write_mesh

from . import stencil_oracle as oracle
from .classic_meshes import tri_grid
from .test_stencil_oracle import TOL, adjacency, compare, edge_index

DOCUMENTED = ["--levels", "1", "--scheme", "snub", "--chirality", "left", "--centre", "vertex"]
OTHERS = [["--levels", "2"], ["--scheme", "akleman"], ["--chirality", "right"],
          ["--centre", "area"], ["--no-smooth"]]


@pytest.fixture(scope="module")
def irregular_pentagons(tmp_path_factory):
    """Two irregular pentagons: their area centroids are not their vertex means, and the
    mirror image of a step is not the step of the mirror image."""
    v = [(0, 0), (2, -0.2), (3.1, 1), (1.7, 2.3), (0.2, 1.6), (4.6, 0.3), (5.4, 1.8), (4.6, 2.2)]
    path = tmp_path_factory.mktemp("defaults") / "in.json"
    write_mesh(Mesh.from_faces(np.array(v, dtype=float), [[0, 1, 2, 3, 4], [1, 5, 6, 7, 2]]),
               path)
    return path


def subdivided(source, tmp_path, *options) -> Mesh:
    out = tmp_path / f"out{len(list(tmp_path.iterdir()))}.json"
    result = CliRunner().invoke(cli, ["subdivide", str(source), *options, "-o", str(out)])
    assert result.exit_code == 0, result.output
    return read_mesh(out)


def test_leaving_options_out_is_the_documented_values(irregular_pentagons, tmp_path):
    default = subdivided(irregular_pentagons, tmp_path)
    explicit = subdivided(irregular_pentagons, tmp_path, *DOCUMENTED)
    np.testing.assert_array_equal(default.vertices, explicit.vertices)
    np.testing.assert_array_equal(default.face_indices, explicit.face_indices)
    for other in OTHERS:
        changed = subdivided(irregular_pentagons, tmp_path, *other)
        assert (changed.vertices.shape != default.vertices.shape
                or not np.allclose(changed.vertices, default.vertices)), other


def test_help_states_the_defaults_tested_here():
    text = " ".join(CliRunner().invoke(cli, ["subdivide", "--help"]).output.split())
    text = text.split("Options:", 1)[1]
    for option, value in zip(DOCUMENTED[::2], DOCUMENTED[1::2]):
        own = text.split(f"{option} ", 1)[1].split(" --", 1)[0]   # up to the next option
        assert f"[default: {value}" in own, (option, own)


@pytest.mark.parametrize("scheme", ["loop", "butterfly"])
def test_classic_scheme_through_the_command_line(scheme, tmp_path):
    mesh = tri_grid(3, 3, jitter=0.15, seed=4)
    write_mesh(mesh, tmp_path / "in.json")
    child = subdivided(tmp_path / "in.json", tmp_path, "--scheme", scheme)
    adj, ids = adjacency(mesh), edge_index(mesh)
    points = oracle.butterfly(adj) if scheme == "butterfly" else oracle.loop(adj)[1]
    compare(child.vertices, points, lambda e: mesh.n_vertices + ids[e])
    if scheme == "loop":
        compare(child.vertices, oracle.loop(adj)[0], lambda v: v)
    assert TOL["rtol"] == 1e-12
