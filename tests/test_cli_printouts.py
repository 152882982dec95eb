"""What the commands print, read back as a reader reads it: every figure of a printout against
the same run's --json, against the files the run wrote, or recomputed here."""

from __future__ import annotations

import json
import math
import re
import shutil
import subprocess
from pathlib import Path
from xml.etree import ElementTree

import ezdxf
import numpy as np
import pytest
from click.testing import CliRunner

from weavecut import presets
from weavecut.cli import cli

from .test_cli_models import glb_parts

NUMBER = r"(-?\d+(?:\.\d+)?(?:e[-+]\d+)?|-)"
needs_pdfinfo = pytest.mark.skipif(shutil.which("pdfinfo") is None, reason="needs pdfinfo")


def run(*args):
    result = CliRunner().invoke(cli, [str(a) for a in args])
    assert result.exit_code == 0, result.output
    return result


def fractal(*args) -> tuple[list[str], dict]:
    return (run("fractal", *args).stdout.splitlines(),
            json.loads(run("fractal", *args, "--json").stdout))


def near(printed: str, value, decimals: int) -> bool:
    """Whether ``printed`` is ``value`` to the printed decimals ("-" for None)."""
    if value is None:
        return printed == "-"
    return printed != "-" and abs(float(printed) - value) <= 0.5 * 10 ** -decimals + 1e-12


def box_lines(lines: list[str], title: str, box: dict) -> None:
    """The box counting's three lines: its figures, and every fourth size and count."""
    k = lines.index(next(line for line in lines if line.startswith(title + ": D = ")))
    head = re.fullmatch(
        re.escape(title) + rf": D = {NUMBER} ± {NUMBER} \(least-squares slope of log N against "
        rf"log 1/eps and its standard error, r2 = {NUMBER}, (\d+) box sizes {NUMBER} \.\. "
        rf"{NUMBER}, counts averaged over (\d+) shifted grids; the coarser and finer half of "
        rf"the sizes alone give {NUMBER} and {NUMBER}\)", lines[k])
    assert head, lines[k]
    d, err, r2, n, first, last, grids, coarse, fine = head.groups()
    sizes, counts = np.array(box["sizes"]), np.array(box["counts"])
    x, y = np.log(1 / sizes), np.log(counts)
    slope = np.polyfit(x, y, 1)[0]  # the slope of what is printed, fitted here
    assert near(d, slope, 4) and near(d, box["dimension"], 4)
    assert near(r2, 1 - np.var(y - np.polyval(np.polyfit(x, y, 1), x)) / np.var(y), 5)
    assert near(err, box["stderr"], 4)
    assert int(n) == len(sizes) and int(grids) == box["grids"]
    assert float(first) == float(f"{sizes[0]:.4g}") and float(last) == float(f"{sizes[-1]:.4g}")
    half = len(sizes) // 2  # the halves share the middle size
    assert near(coarse, box["halves"][0], 4) and near(fine, box["halves"][1], 4)
    assert near(coarse, np.polyfit(x[:half + 1], y[:half + 1], 1)[0], 4)
    shown = [float(v) for v in lines[k + 1].split()[2:]]
    assert lines[k + 1].startswith("  box size ") and shown == [float(f"{s:.3g}")
                                                                for s in sizes[::4]]
    assert lines[k + 2].startswith("  boxes ") and \
        [float(v) for v in lines[k + 2].split()[1:]] == [round(c, 1) for c in counts[::4]]


def test_the_fractal_printout_says_the_figures_of_its_json():
    lines, doc = fractal("pentagon", "--levels", "7")
    alpha = math.atan(math.sqrt(3) / 5)
    top = re.fullmatch(rf"alpha = atan\(sqrt\(3\)/5\) = {NUMBER} rad = {NUMBER} deg \(from the "
                       rf"Z-triplet: {NUMBER} deg\)", lines[0])
    assert top and near(top[1], alpha, 9) and near(top[2], math.degrees(alpha), 6)
    assert near(top[3], doc["alpha_from_z_triplet_deg"], 6)
    assert lines[1] == (f"L-system: {doc['lsystem']['rule']}   v: rot(+alpha)  ^: rot(-alpha)  "
                        "+: rot(+pi/3)  -: rot(-pi/3); every step scales edges by 1/sqrt(7) = "
                        f"{1 / math.sqrt(7):.6f}")
    errors = doc["boundary_lsystem_max_error"]
    assert len(set(errors)) > 1  # so the largest is told from the others
    assert lines[2] == ("boundary = L-system curve at levels 0..7: largest deviation "
                        f"{max(errors):.2e}")
    assert lines[3] == ("dimension (analytic): log 3 / log sqrt 7 = "
                        f"{math.log(3) / math.log(math.sqrt(7)):.6f}")
    box_lines(lines, "box counting, boundary at level 7", doc["boundary_box_counting"])
    curve = doc["inner_curve"]
    box_lines(lines, f"box counting, curve from level {curve['level']} edge {curve['edge']}",
              curve)
    growth = [line for line in lines if "growth per curve" in line]
    assert len(growth) == len(doc["growth_monotonicity"]) > 1
    for line, m in zip(growth, doc["growth_monotonicity"]):
        assert line.split() == [m["kind"], "born", f"{m['born']}:", str(m["curves"]), "curves;",
                                "growth", "per", "curve", "from", "level", str(m["levels"][0]),
                                "to", f"{m['levels'][1]}:", f"{m['constant']}", "constant,",
                                f"{m['rising']}", "rising,", f"{m['falling']}", "falling,",
                                f"{m['turning']}", "turning"]
    k = lines.index("curves born as one edge at level 'born' (growth = L(t)/L(t-1); boundary: "
                    f"3/sqrt7 = {3 / math.sqrt(7):.6f}):")
    assert lines[k + 1].split() == ["kind", "born", "level", "curves", "edges", "mean", "length",
                                    "mean", "chord", "growth", "min", "median", "max",
                                    "log3/log(3/g)"]
    rows = lines[k + 2:]
    assert len(rows) == len(doc["inner_curves"])
    for line, row in zip(rows, doc["inner_curves"]):
        words = line.split()
        assert words[:5] == [row["kind"], str(row["born"]), str(row["level"]),
                             str(row["curves"]), str(row["edges_each"])]
        assert near(words[5], row["mean_length"], 6) and near(words[6], row["mean_chord"], 6)
        keys = ("growth", "growth_min", "growth_median", "growth_max", "implied_dimension")
        assert len(words) == (12 if "growth" in row else 7)
        assert all(near(w, row[key], 4) for w, key in zip(words[7:], keys))


def test_a_fractal_figure_too_few_box_sizes_leave_undefined_is_a_dash():
    lines, doc = fractal("square-grid", "--levels", "3")
    box = doc["boundary_box_counting"]
    assert box["stderr"] is None and box["halves"][1] is None  # two sizes: one line, no error
    box_lines(lines, "box counting, boundary at level 3", box)
    skipped = doc["inner_curve"]["skipped"]
    assert (f"box counting, curve from level {doc['inner_curve']['level']} edge "
            f"{doc['inner_curve']['edge']}: not measured ({skipped})") in lines


def pdf_pages(path) -> int:
    info = subprocess.run(["pdfinfo", str(path)], capture_output=True, text=True, check=True)
    return int(re.search(r"^Pages:\s+(\d+)", info.stdout, re.M)[1])


def dxf_layers(path) -> dict[str, list[np.ndarray]]:
    """The polylines of each layer of a DXF file, closed ones ending at their start."""
    layers: dict[str, list[np.ndarray]] = {}
    for e in ezdxf.readfile(path).modelspace().query("LWPOLYLINE"):
        points = np.array([p[:2] for p in e.get_points()])
        layers.setdefault(e.dxf.layer, []).append(
            np.vstack([points, points[:1]]) if e.closed else points)
    return layers


# the pentagon at level 2: crossings too small for a name (engraved dots, a warning) and two
# palettes with fewer card colours, each a different number
CARD = ("strands", "pentagon", "-n", "2", "--laser-card", "--tile-size", "15mm")


@needs_pdfinfo
def test_the_laser_cards_json_says_what_it_wrote(tmp_path):
    """Every figure of ``strands --laser-card --json`` read back from the files it wrote: the
    sheets' colours from their SVGs, their strips, scores and cut length from their DXFs, the
    instructions' pages from the PDF, the cutting time from the material's speed."""
    folder = tmp_path / "card"
    result = run(*CARD, "--json", "-o", folder)
    doc = json.loads(result.stdout)
    written = sorted(folder.glob("strands-card-*"))
    assert sorted(Path(f) for f in doc["files"]) == written
    svgs = [p for p in written if p.suffix == ".svg"]
    colours = [re.search(r"card: (#[0-9a-f]{6})", p.read_text())[1] for p in svgs]
    assert doc["sheets"] == len(svgs) == len(written) // 2 and \
        doc["card_colours"] == len(set(colours)) > 1
    root = ElementTree.parse(svgs[0]).getroot()
    assert [root.get("width"), root.get("height")] == [f"{v:g}mm" for v in doc["sheet_mm"]]
    layers = [dxf_layers(p) for p in written if p.suffix == ".dxf"]
    cuts = [line for sheet in layers for line in sheet.get("cut", [])]
    assert doc["strips"] == doc["outlines"] == len(cuts) > doc["sheets"]
    assert doc["score_lines"] == sum(len(sheet.get("score", [])) for sheet in layers) > 0
    length = sum(np.hypot(*np.diff(c, axis=0).T).sum() for c in cuts)
    assert doc["cut_length_mm"] == pytest.approx(length, abs=0.1)
    speed = presets.load("materials", doc["material"])["cut_speed"]
    assert doc["cut_minutes"] == round(length / speed / 60, 1) > 0
    assert doc["instruction_pages"] == pdf_pages(folder / "strands-assembly.pdf")
    warned = [line.removeprefix("weave-cut: warning: ") for line in result.stderr.splitlines()]
    assert doc["warnings"] == warned
    # a dot is engraved where a crossing is too small for its name, as the warning counts them
    assert warned[0].startswith(f"{doc['engraved_dots']} crossings are too small to carry an "
                                "engraved name") and doc["engraved_dots"] == doc["names_left_out"]


def test_the_laser_cards_summary_says_its_json_figures(tmp_path):
    """The summary line of ``strands --laser-card`` against the same kit's --json, and the
    palette it names for fewer card colours against a kit cut with that palette."""
    doc = json.loads(run(*CARD, "--json", "-o", tmp_path / "j").stdout)
    result = run(*CARD, "-o", tmp_path / "card")
    said = re.fullmatch(
        rf"{re.escape(str(tmp_path / 'card'))}: (\d+) sheets of (\S+) in (\d+) card colours, "
        r"(\d+) strip pieces, ([\d.]+) m of cuts \(about (\d+) min\), smallest feature "
        r"([\d.]+) mm; sheets (\d+) % covered: --palette (\S+) needs (\d+) card colours; "
        r"strands-assembly\.pdf \((\d+) pages\): what to cut from which card, how to weave",
        result.stdout.strip())
    assert said, result.stdout
    sheets, material, colours, strips, metres, minutes, feature, covered, fewer, need, pages = \
        said.groups()
    assert (int(sheets), material, int(colours), int(strips), int(pages)) == (
        doc["sheets"], doc["material"], doc["card_colours"], doc["strips"],
        doc["instruction_pages"])
    assert float(metres) == round(doc["cut_length_mm"] / 1000, 1)
    assert int(minutes) == round(doc["cut_minutes"]) and \
        float(feature) == round(doc["min_feature_mm"], 1)
    assert abs(int(covered) - 100 * doc["sheet_fill"]) <= 0.55
    assert [fewer, int(need)] == list(next(iter(doc["fewer_colours"].items())))
    assert len(set(doc["fewer_colours"].values())) > 1  # the first palette's count, not another's
    assert json.loads(run(*CARD, "--palette", fewer, "--json", "-o", tmp_path / "few").stdout)[
        "card_colours"] == int(need) < doc["card_colours"]
    assert result.stderr == "".join(f"weave-cut: warning: {w}\n" for w in doc["warnings"])


@needs_pdfinfo
@pytest.mark.parametrize("how", [("--project", "sphere", "--size", "12cm"), ()],
                         ids=["sphere-12cm", "as-given"])
def test_a_balls_summary_and_3d_model_say_its_json_figures(tmp_path, how):
    """``strands`` of a surface in space: the summary line against the same ball's --json and
    its PDF (its title says the projection asked for), the tile size 40 mm unless a size is
    given, and the woven model beside it: one strip per strand, the ball's size in metres."""
    ball = ("strands", "dodecahedron", "--levels", "1", *how)
    doc = json.loads(run(*ball, "--json", "-o", tmp_path / "j.pdf").stdout)
    out = tmp_path / "ball.pdf"
    said = re.fullmatch(
        rf"{re.escape(str(out))}: (\d+) pages \((\d+) of strips, (\d+) % ink\); (\d+) strips in "
        r"(\d+) pieces, a ball ([\d.]+) cm across; unfolded edges change by at most ([\d.]+) %, "
        r"pentagons are at most ([\d.]+) % off their planes", run(*ball, "-o", out).stdout.strip())
    assert said
    pages, strips, ink, strands, pieces, cm, stretch, planes = said.groups()
    info = subprocess.run(["pdfinfo", str(out)], capture_output=True, text=True).stdout
    assert re.search(r"^Title:\s+(.*)$", info, re.M)[1] == "weave-cut strands: dodecahedron, " \
        "level 1" + (", projected to the sphere" if how else "")
    assert doc["input"] == "dodecahedron" and doc["tile_size_mm"] == (63.09 if how else 40.0)
    assert int(pages) == doc["pages"]["total"] == pdf_pages(out) > int(strips) == \
        doc["pages"]["strip"]
    assert abs(int(ink) - 100 * doc["ink_fraction"]) <= 0.55
    assert (int(strands), int(pieces)) == (doc["strands"], doc["pieces"]) == (6, 12)
    assert float(cm) == round(doc["diameter_mm"] / 10, 1) and (doc["diameter_mm"] == 120.0
                                                                or not how)
    assert near(stretch, doc["largest_edge_change_pct"], 2) and \
        near(planes, doc["largest_non_planarity_pct"], 1)
    model, strips_3d = glb_parts(tmp_path / "ball-3d.glb")
    assert model["nodes"][0]["name"] == "ball" and len(strips_3d) == doc["strands"]
    points = np.vstack(strips_3d)
    radius = np.linalg.norm(points - points.mean(axis=0), axis=1) * 1000  # mm
    # the ball's size, its strips' 0.5 mm paper over and under each other
    assert abs(radius.max() - doc["diameter_mm"] / 2) < 0.6 and np.ptp(radius) > 0.5
