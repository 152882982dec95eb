"""The woven 3-D models the commands write, read back here without weave-cut's own readers (a
.glb's chunks and an .obj's lines parsed as the formats define them): ``weave`` of a surface
in space, of a snub weave (its tiles as strips) and of a face-split weave (ribbons through the
tiles), at the asked size, one colour per strand, the same colours in both files."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from weavecut.cli import cli


def glb_parts(path) -> tuple[dict, list[np.ndarray]]:
    """A .glb file's JSON and the vertices (metres) of each primitive of its mesh."""
    data = path.read_bytes()
    assert data[:4] == b"glTF" and int.from_bytes(data[8:12], "little") == len(data)
    n = int.from_bytes(data[12:16], "little")
    doc = json.loads(data[20:20 + n])
    binary = data[20 + n + 8:]
    points = []
    for primitive in doc["meshes"][0]["primitives"]:
        accessor = doc["accessors"][primitive["attributes"]["POSITION"]]
        view = doc["bufferViews"][accessor["bufferView"]]
        points.append(np.frombuffer(binary, "<f4", 3 * accessor["count"],
                                    view["byteOffset"]).reshape(-1, 3))
    return doc, points


def obj_points(path) -> tuple[np.ndarray, np.ndarray]:
    """An .obj file's vertices (mm) and their colours as #rrggbb."""
    rows = [line.split()[1:] for line in path.read_text().splitlines() if line.startswith("v ")]
    values = np.array(rows, dtype=float)
    colours = np.array(["#" + "".join(f"{round(255 * c):02x}" for c in rgb)
                        for rgb in values[:, 3:6]])
    return values[:, :3], colours


def radii(points: np.ndarray) -> np.ndarray:
    return np.linalg.norm(points - points.mean(axis=0), axis=1)


@pytest.mark.parametrize("how", [(), ("--face-split",)], ids=["snub", "face-split"])
def test_a_woven_ball_is_its_size_in_each_file_with_a_colour_per_strand(tmp_path, how):
    for suffix in ("obj", "glb"):
        result = CliRunner().invoke(cli, ["weave", "dodecahedron", "--levels", "1", *how,
                                          "--size", "150mm", "--thickness", "1mm", "-o",
                                          str(tmp_path / f"ball.{suffix}")])
        assert result.exit_code == 0, result.output
    doc, parts = glb_parts(tmp_path / "ball.glb")
    kind = "face-split" if how else "snub"  # the model names the weave it is
    assert doc["nodes"][0]["name"] == f"dodecahedron, {kind} weave, level 1"
    assert f"{kind} weave" in (tmp_path / "ball.obj").read_text().splitlines()[0]
    colours = [doc["materials"][p["material"]]["name"] for p in doc["meshes"][0]["primitives"]]
    assert len(parts) == len(set(colours)) == 6  # six strands round the ball
    points, painted = obj_points(tmp_path / "ball.obj")
    assert set(painted) == set(colours)
    for r, unit in ((radii(points), 1.0), (radii(np.vstack(parts)), 1000.0)):
        r = r * unit  # mm
        # the strips span 150 mm; those on top stand out from the surface by at most the
        # --thickness (1 mm, as its help says) and by more than a quarter of it
        assert 75.0 + 0.25 < r.max() <= 75.0 + 1.0 + 0.02
