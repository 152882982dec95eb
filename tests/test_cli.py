"""The CLI: every command runs, errors are one line with the right exit status, outputs are
deterministic and atomic."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from xml.etree import ElementTree

import ezdxf
import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from PIL import Image

from weavecut.cli import cli
from weavecut.mesh_io import read_mesh
from weavecut.subdivision import subdivide
from weavecut import inputs


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_version_and_help():
    assert "0.1.0" in run("--version").output
    for command in ("inputs", "subdivide", "stats"):
        result = run(command, "--help")
        assert result.exit_code == 0 and "Example" in result.output


def test_inputs_lists_every_builtin():
    result = run("inputs", "--json")
    rows = json.loads(result.output)
    assert [r["name"].split("[")[0] for r in rows] == list(inputs.INPUTS)
    pentagon = rows[0]
    assert (pentagon["vertices"], pentagon["edges"], pentagon["faces"]) == (5, 5, 1)


def test_stats_json_matches_equation_2():
    result = run("stats", "pentagon", "--levels", "6", "--json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.output)
    assert doc["input"] == "pentagon"
    v, e, f = 5, 5, 1
    for row in doc["levels"]:
        assert (row["vertices"], row["edges"], row["faces"]) == (v, e, f)
        v, e, f = v + 2 * e + f, 3 * e + 5 * f, 5 * f
    first = doc["levels"][0]
    assert set(first) == {"level", "vertices", "edges", "faces", "inner_vertex_degrees",
                          "outer_vertex_degrees", "face_degrees", "nonconvex_faces",
                          "min_angle_deg", "max_angle_deg", "boundary_edges", "boundary_length"}
    assert first["face_degrees"] == {"5": 1} and first["outer_vertex_degrees"] == {"2": 5}
    assert first["min_angle_deg"] == pytest.approx(108.0)
    lengths = [row["boundary_length"] for row in doc["levels"]]
    assert lengths[1] / lengths[0] == pytest.approx(3 / 7 ** 0.5, rel=1e-5)


@pytest.mark.parametrize("suffix", ["obj", "json"])
def test_subdivide_writes_a_mesh_that_reads_back(tmp_path, suffix):
    out = tmp_path / f"m.{suffix}"
    assert run("subdivide", "square-grid:2x2", "--levels", "2", "-o", out).exit_code == 0
    back = read_mesh(out)
    expect = subdivide(inputs.get("square-grid:2x2"), 2)[-1].mesh
    assert back.vertices.tobytes() == expect.vertices.tobytes()
    assert back.faces() == expect.faces()
    again = tmp_path / f"again.{suffix}"
    assert run("subdivide", out, "--levels", "1", "-o", again).exit_code == 0
    assert read_mesh(again).n_faces == 5 * back.n_faces


def _segments(polylines) -> set[tuple]:
    """Every segment of the polylines as a pair of rounded points, in either direction."""
    out = []
    for p in polylines:
        pts = [tuple(round(c, 5) for c in xy) for xy in p.get_points("xy")]
        if p.closed:
            pts.append(pts[0])
        out += [tuple(sorted(s)) for s in zip(pts[:-1], pts[1:])]
    return out


def test_subdivide_dxf_cuts_every_edge_once(tmp_path):
    out = tmp_path / "p.dxf"
    assert run("subdivide", "pentagon", "--levels", "3", "-o", out).exit_code == 0
    doc = ezdxf.readfile(out)
    auditor = doc.audit()
    assert not auditor.has_errors
    assert doc.header["$INSUNITS"] == 4
    assert {layer.dxf.name for layer in doc.layers} - {"0", "Defpoints"} == {"cut-1-inner",
                                                                         "cut-2-outline"}
    mesh = subdivide(inputs.get("pentagon"), 3)[-1].mesh
    msp = doc.modelspace()
    inner = _segments(msp.query('LWPOLYLINE[layer=="cut-1-inner"]'))
    outline = _segments(msp.query('LWPOLYLINE[layer=="cut-2-outline"]'))
    n_boundary = 5 * 3 ** 3  # every step turns a boundary edge into three (paper, eq. 2)
    assert len(outline) == len(set(outline)) == n_boundary
    assert len(inner) == len(set(inner)) == mesh.topology.n_edges - n_boundary
    assert not set(inner) & set(outline)


def test_subdivide_earlier_levels_get_their_own_layers(tmp_path):
    out = tmp_path / "p.dxf"
    assert run("subdivide", "pentagon", "--levels", "3", "--earlier-levels", "-o",
               out).exit_code == 0
    msp = ezdxf.readfile(out).modelspace()
    segments = [_segments(msp.query(f'LWPOLYLINE[layer=="level-{t}"]')) for t in range(3)]
    assert [len(s) for s in segments] == [len(set(s)) for s in segments] == [5, 20, 85]  # eq. 2
def test_subdivide_svg_size_is_in_mm(tmp_path):
    out = tmp_path / "p.svg"
    assert run("subdivide", "pentagon", "--levels", "2", "--size", "10cm", "-o", out).exit_code == 0
    root = ElementTree.parse(out).getroot()
    assert root.get("width").endswith("mm") and root.get("height").endswith("mm")
    width, height = (float(root.get(k)[:-2]) for k in ("width", "height"))
    assert max(width, height) == pytest.approx(120.0)  # 100 mm plus two 10 mm margins
    assert root.get("viewBox") == f"0 0 {width:g} {height:g}"
    # the drawn mesh itself is 100 mm across, measured on the paths, not on the sheet
    numbers = [float(v) for path in root.iter("{http://www.w3.org/2000/svg}path")
               for v in re.findall(r"-?\d+(?:\.\d+)?", path.get("d"))]
    xy = np.array(numbers).reshape(-1, 2)
    assert (xy.max(axis=0) - xy.min(axis=0)).max() == pytest.approx(100.0, abs=0.01)


@pytest.mark.parametrize("suffix", ["svg", "dxf", "obj", "json"])
def test_same_bytes_across_runs_and_hash_seeds(tmp_path, suffix):
    outs = []
    for seed in ("1", "2"):  # the same command line (it is in the metadata) in two folders
        folder = tmp_path / seed
        folder.mkdir()
        env = dict(os.environ, PYTHONHASHSEED=seed)
        subprocess.run([sys.executable, "-m", "weavecut", "subdivide", "tiling-8-4:2x2",
                        "--levels", "2", "-o", f"out.{suffix}"], check=True, env=env, cwd=folder)
        outs.append((folder / f"out.{suffix}").read_bytes())
    assert outs[0] == outs[1]


@pytest.mark.parametrize("args, status, message", [
    (["subdivide", "nope", "-o", "{d}/x.svg"], 1, "unknown input 'nope'"),
    (["subdivide", "pentagon", "--levels", "14", "-o", "{d}/x.svg"], 1, "needs about"),
    (["subdivide", "pentagon", "-o", "{d}/x.xyz"], 2, "unknown format '.xyz'"),
    (["subdivide", "pentagon", "--levels", "-1", "-o", "{d}/x.svg"], 2, "--levels"),
    (["subdivide", "pentagon", "--size", "-5mm", "-o", "{d}/x.svg"], 2, "must be > 0"),
    (["subdivide", "pentagon", "--size", "big", "-o", "{d}/x.svg"], 2, "is not a length"),
    (["subdivide", "pentagon", "-o", "{d}/missing/x.svg"], 2, "does not exist; create it"),
    (["subdivide", "pentagon", "-o", "{d}"], 2, "directory"),
    (["subdivide", "{d}/missing.obj", "-o", "{d}/x.svg"], 1, "cannot read"),
    (["stats", "ngon:2"], 1, "ngon takes a number from 3"),
    (["stats", "square-grid:axb"], 1, "WxH"),
])
def test_errors_are_one_line(tmp_path, args, status, message):
    result = run(*[a.format(d=tmp_path) for a in args])
    assert result.exit_code == status, result.output
    assert message in result.output
    assert "Traceback" not in result.output
    assert not list(tmp_path.glob("*.svg")) and not list(tmp_path.glob(".*part"))


def test_console_script_prints_no_traceback(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0\nv 1 0\nv 0 1\nf 1 2 9\n")
    proc = subprocess.run([sys.executable, "-m", "weavecut", "subdivide", str(bad), "-o",
                           str(tmp_path / "x.svg")], capture_output=True, text=True)
    assert proc.returncode == 1
    assert proc.stderr.strip().count("\n") == 0 and "face index 9" in proc.stderr


def test_unwritable_output_leaves_nothing(tmp_path):
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        result = run("subdivide", "pentagon", "-o", folder / "x.svg")
        if os.geteuid() != 0:  # root writes anywhere
            assert result.exit_code == 1 and "cannot write" in result.output
        assert not list(folder.glob(".*part"))
    finally:
        folder.chmod(0o700)


def test_weave_json_counts_and_lineage():
    result = run("weave", "square-grid:3x3", "--levels", "3", "--json")
    assert result.exit_code == 0, result.output
    levels = json.loads(result.output)["levels"]
    assert [lv["level"] for lv in levels] == [1, 2, 3]
    for lv in levels:
        assert lv["octagons"] + lv["boundary_pentagons"] == lv["tiles"]
        assert sum(lv["strand_length_histogram"].values()) == lv["strands"]
    assert "lineage" not in levels[0] and levels[2]["lineage"]["orphans"] == 0
    # the square grid's level-t tiles are the edges of level t-1: E' = 3E + 4F
    e, f = 24, 9
    assert levels[0]["tiles"] == e and levels[1]["tiles"] == 3 * e + 4 * f


def test_weave_pictures_in_every_format(tmp_path):
    """One weave in four formats, each read back by its own reader, shows the same picture:
    the SVG's tile colours are the DXF's tile layers and are painted in the PNG, whose shape is
    the SVG's; the PDF is one page."""
    args = ["weave", "pentagon", "--levels", "3", "--outline-level", "2", "--crossings",
            "--middle-edges"]
    for suffix in ("svg", "pdf", "png", "dxf"):
        result = run(*args, "-o", tmp_path / f"w.{suffix}")
        assert result.exit_code == 0, result.output
    assert run(*args[:4], "-o", tmp_path / "tiles.png").exit_code == 0  # no lines over tiles
    root = ElementTree.parse(tmp_path / "w.svg").getroot()
    ns = "{http://www.w3.org/2000/svg}"
    tiles = [g for g in root.iter(f"{ns}g") if g.get("id") == "paint-tiles"][0]
    fills = {p.get("fill") for p in tiles.iter(f"{ns}path")}
    assert len(fills) >= 10 and all(re.fullmatch(r"#[0-9a-f]{6}", f) for f in fills)
    doc = ezdxf.readfile(tmp_path / "w.dxf")
    assert doc.header["$INSUNITS"] == 4  # mm
    assert {layer.dxf.name for layer in doc.layers if layer.dxf.name.startswith("tiles-")} == \
        {f"tiles-{f[1:]}" for f in fills}
    assert len(doc.modelspace().query("HATCH")) >= len(fills)
    with Image.open(tmp_path / "w.png") as im:
        im.verify()
    with Image.open(tmp_path / "tiles.png") as im:
        pixels = np.asarray(im.convert("RGB"))
    height, width = pixels.shape[:2]
    w_mm, h_mm = (float(root.get(k).removesuffix("mm")) for k in ("width", "height"))
    assert width / height == pytest.approx(w_mm / h_mm, abs=2 / height)
    # a point inside each SVG tile has the tile's colour in the PNG (tile outlines cover a few)
    hits = []
    for path in tiles.iter(f"{ns}path"):
        for ring in path.get("d").split("M")[1:]:
            xy = [tuple(map(float, p.split(","))) for p in ring.rstrip("Z").split()]
            inside = shapely.Polygon(xy).representative_point()
            rgb = pixels[int(inside.y * height / h_mm), int(inside.x * width / w_mm)]
            hits.append("#%02x%02x%02x" % tuple(rgb) == path.get("fill"))
    assert len(hits) > 100 and np.mean(hits) > 0.9
    pdf = (tmp_path / "w.pdf").read_bytes()
    assert pdf.startswith(b"%PDF-") and pdf.rstrip().endswith(b"%%EOF")
    assert len(re.findall(rb"/Type /Page\b", pdf)) == 1


@pytest.mark.parametrize("scheme, mesh", [("loop", "triangle-grid:2x2"),
                                          ("catmull-clark", "square-grid:2x2"),
                                          ("sqrt3", "triangle-grid:2x2"),
                                          ("doo-sabin", "hex-grid:2x2")])
def test_weave_other_schemes_as_ribbons(tmp_path, scheme, mesh):
    out = tmp_path / "r.svg"
    result = run("weave", mesh, "--scheme", scheme, "--levels", "2", "--style", "ribbons",
                 "-o", out)
    assert result.exit_code == 0, result.output
    assert "ribbons" in out.read_text()


@pytest.mark.parametrize("args, status, message", [
    (["weave", "pentagon", "--levels", "2"], 2, "give -o OUTPUT"),
    (["weave", "pentagon", "--levels", "2", "--outline-level", "2", "--json"], 2, "below"),
    (["weave", "pentagon", "--levels", "2", "--palette", "nope", "--json"], 1, "unknown palette"),
    (["weave", "pentagon", "--levels", "0", "--json"], 2, "--levels 1 or more"),
    (["weave", "ngon:7", "--scheme", "loop", "--levels", "1", "--json"], 1, "3 corners"),
    (["weave", "triangulated-ngon:5", "--scheme", "loop", "--levels", "1", "--json"], 1,
     "odd degree"),
])
def test_weave_errors(args, status, message):
    result = run(*args)
    assert result.exit_code == status, result.output
    assert message in result.output
