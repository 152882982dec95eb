"""Hostile drawings: budgets before the work (elements after ``<use>``, path data, points after
flattening, DXF lines and entities, curve numbers, cells of a meshed outline), and the internal
errors a drawing once caused.

The corpus (``corpus/*.svg``, ``corpus/*.dxf``) holds the small cases, each starting with what
it must give (SVG: ``<?expect ...?>`` and ``<?options ...?>``; DXF: 999 comment groups
``expect: ...`` and ``options: ...``); the large ones are made here. Every case runs under
``bounded``: had its guard gone, it would run for minutes or take gigabytes.
"""

from __future__ import annotations

import contextlib
import math
import re
import resource
import signal
import xml.etree.ElementTree as ET
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
from ezdxf import path as dxfpath
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from weavecut.errors import MeshError
from weavecut.mesh_geometry import signed_areas
from weavecut.readers import dxf, outline_mesh
from weavecut.readers.drawing import read_drawing
from weavecut.readers.tessellations import _lattice

from . import strategies as ws
from .helpers import files_under, refused, run

CORPUS = Path(__file__).with_name("corpus")
DRAWINGS = sorted([*CORPUS.glob("*.svg"), *CORPUS.glob("*.dxf")])


class Overran(BaseException):
    """Raised by ``bounded`` (a BaseException, so no ``except Exception`` turns it into a
    clean refusal)."""


@contextlib.contextmanager
def bounded(seconds: float = 60, memory: int = 3 * 2**30):
    """Run the block for at most ``seconds`` and with at most ``memory`` bytes more address
    space than now: a missing guard fails the test instead of hanging or swapping the machine
    (these inputs took minutes or tens of GB unguarded; refused, each takes well under one)."""
    def overran(signum, frame):
        raise Overran(f"still running after {seconds} s")

    limits = resource.getrlimit(resource.RLIMIT_AS)
    status = Path("/proc/self/status")
    used = (int(re.search(r"VmSize:\s*(\d+) kB", status.read_text())[1]) * 1024
            if status.exists() else None)
    previous = signal.signal(signal.SIGALRM, overran)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    if used is not None:
        resource.setrlimit(resource.RLIMIT_AS, (used + memory, limits[1]))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, limits)
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def header(path: Path) -> dict[str, str]:
    """``expect`` and ``options`` from the first lines of a corpus drawing."""
    found = (re.fullmatch(r"(?:<\?)?(expect|options):? (.*?)(?:\?>)?", line)
             for line in path.read_text(encoding="utf-8").splitlines()[:8])
    return {m[1]: m[2] for m in found if m}


def refused_quickly(path: Path, *options: str, needles=()) -> str:
    with bounded():
        result = run("stats", path, "--levels", "0", *options)
    return refused(result, path.name, *needles)


def refused_when_made(folder: Path, name: str, text: str, needle: str) -> None:
    path = folder / name
    path.write_text(text)
    refused_quickly(path, needles=[needle])
    assert files_under(folder) == {name}


@pytest.mark.parametrize("path", DRAWINGS, ids=lambda p: p.name)
def test_corpus_drawing(path):
    meta = header(path)
    assert "expect" in meta and path.stat().st_size < 20_000
    refused_quickly(path, *meta.get("options", "").split(), needles=[meta["expect"]])


def test_corpus_headers_are_read(tmp_path):
    """Every drawing states what it must give, and the SVG headers leave the XML well formed
    (a ``--`` in an XML comment would make it unreadable for the wrong reason)."""
    for path in DRAWINGS:
        assert header(path)["expect"], path
        if path.suffix == ".svg":
            ET.parse(path)
    svg, dxf_file = tmp_path / "a.svg", tmp_path / "a.dxf"
    svg.write_text("<?expect --cell 1 mm?>\n<?options --mesh quad?>\n<!-- why -->\n<svg/>\n")
    dxf_file.write_text("999\nexpect: degree 50\n999\noptions: --flatten 1mm\n0\nEOF\n")
    assert header(svg) == {"expect": "--cell 1 mm", "options": "--mesh quad"}
    assert header(dxf_file) == {"expect": "degree 50", "options": "--flatten 1mm"}


# --- SVG --------------------------------------------------------------------------------

SVG = ('<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
       'viewBox="0 0 100 100">{}</svg>')
LARGE_SVG = {  # made here: a file each of 0.3 to 60 MB
    "path-1e6-segments.svg": (SVG.format('<path d="M0 0' + " l1 0 l0 1" * 500_000 + ' z"/>'),
                              "more than 300,000 numbers and commands of path data"),
    "rects-1e5.svg": (SVG.format('<rect width="1" height="1"/>' * 100_000),
                      "more than 10,000 elements; at most 10,000 are read"),
    "polygon-2e5-points.svg": (SVG.format('<polygon points="' + "1,2 " * 200_000 + '"/>'),
                               "more than 300,000 numbers and commands of path data"),
    "spaces-60MB.svg": (SVG.format('<path d="M0 0' + " " * 60_000_000 + 'L10 0 L10 10 Z"/>'),
                        "more than 9,600,000 characters of path data"),
}


@pytest.mark.parametrize("name", sorted(LARGE_SVG))
def test_large_svg_is_refused_before_the_work(tmp_path, name):
    refused_when_made(tmp_path, name, *LARGE_SVG[name])


def test_a_long_tag_is_read_in_one_piece(tmp_path):
    """50 MB of comment and 9 MB of spaces in a path: read at once, not 16 KiB at a time
    (expat reads a tag across n reads n times over: minutes for this file)."""
    path = tmp_path / "long.svg"
    path.write_text(SVG.format('<!--' + "x" * 50_000_000 + '--><path d="M0 0' + " " * 9_000_000
                               + 'L10 0 L10 10 Z"/>'))
    with bounded():
        result = run("stats", path, "--levels", "0", "--mesh", "none")
    assert result.exit_code == 0, result.output
    assert "1 faces, 3 vertices" in result.output


def test_the_point_budget_is_for_the_whole_drawing(tmp_path):
    """Circles of 448 points each at --flatten 0.001mm: one is well within the budget, the
    224th passes it."""
    path = tmp_path / "circles.svg"
    path.write_text(SVG.format('<circle cx="50" cy="50" r="40"/>' * 300))
    refused_quickly(path, "--flatten", "0.001mm", needles=["give 100,352 points; at most "
                                                           "100,000 are read"])
    path.write_text(SVG.format('<circle cx="50" cy="50" r="40"/>'))
    assert run("stats", path, "--levels", "0", "--flatten", "0.001mm").exit_code == 0


def test_a_1e_300_viewbox_of_a_1e_301_rect_reads_fine(tmp_path):
    """Extreme but consistent numbers: the viewBox scales the rect up to 10 mm."""
    path = tmp_path / "x.svg"
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
                    'viewBox="0 0 1e-300 1e-300"><rect width="1e-301" height="1e-301"/></svg>')
    assert signed_areas(read_drawing(path, mesh="none")).sum() == pytest.approx(100.0)


# --- DXF --------------------------------------------------------------------------------

DXF = ("0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n"
       "0\nSECTION\n2\nENTITIES\n{}0\nENDSEC\n0\nEOF\n")
LINE = "0\nLINE\n8\n0\n10\n0\n20\n0\n11\n1\n21\n1\n"
CIRCLE = "0\nCIRCLE\n8\n0\n10\n0\n20\n0\n40\n1\n"


def fit_spline(n: int) -> str:
    return ("0\nSPLINE\n100\nAcDbEntity\n8\n0\n100\nAcDbSpline\n70\n0\n71\n3\n"
            f"74\n{n}\n" + "".join(f"11\n{k}\n21\n{k % 7}\n31\n0\n" for k in range(n)))


LARGE_DXF = {  # made here: a file each of 0.3 to 26 MB
    "lines-1e6.dxf": (DXF.format(LINE * 1_000_000), "12,000,022 lines of DXF text; at most "
                                                     "500,000 are read"),
    "circles-2e5.dxf": (DXF.format(CIRCLE * 200_000), "2,000,022 lines of DXF text"),
    "circles-2e4.dxf": (DXF.format(CIRCLE * 20_000), "20,000 entities (LWPOLYLINE POLYLINE "
                                                     "CIRCLE ELLIPSE SPLINE LINE ARC); at most "
                                                     "10,000 are read"),
    "fit-points-5000.dxf": (DXF.format(fit_spline(5000)), "the splines have more than 4,000 "
                                                          "fit points in all"),
}


@pytest.mark.parametrize("name", sorted(LARGE_DXF))
def test_large_dxf_is_refused_before_the_work(tmp_path, name):
    refused_when_made(tmp_path, name, *LARGE_DXF[name])


def spline_text(scale: float) -> str:
    points = [(0, 0), (40, 0), (40, 40), (0, 40), (0, 0)]
    knots = [k * scale for k in (0, 0, 0, 0, 0.5, 1, 1, 1, 1)]
    return ("0\nSPLINE\n100\nAcDbEntity\n8\n0\n100\nAcDbSpline\n70\n1\n71\n3\n72\n9\n73\n5\n"
            + "".join(f"40\n{k!r}\n" for k in knots)
            + "".join(f"10\n{x}\n20\n{y}\n30\n0\n" for x, y in points))


def test_knots_of_1e300_read_as_the_same_spline(tmp_path):
    """Knots are parameters: scaled by 1e300 they draw the same curve."""
    rings = []
    for scale in (1.0, 1e300):
        path = tmp_path / "s.dxf"
        path.write_text(DXF.format(spline_text(scale)))
        rings.append(dxf.read_rings(path, 0.2)[0][0].points)
    assert rings[0] == pytest.approx(rings[1])


def test_the_flattening_estimate_follows_ezdxf():
    """The points budget of a DXF is counted before ezdxf flattens: within a factor of two of
    what it gives (it halves a curve until the chord is close enough)."""
    msp = ezdxf.new().modelspace()
    rng = np.random.default_rng(3)
    entities = [msp.add_circle((0, 0), r) for r in (0.5, 50, 500)]
    entities += [msp.add_ellipse((0, 0), (r, 0), 0.3) for r in (1, 300)]
    entities += [msp.add_open_spline(rng.uniform(-50, 50, (12, 2)), degree=d) for d in (2, 3, 5)]
    entities.append(msp.add_lwpolyline([(0, 0, 0.5), (10, 0, 2), (10, 10, -1), (0, 10)],
                                       format="xyb", close=True))
    for tolerance in (1.0, 0.2, 0.01, 1e-4):
        for entity in entities:
            p = dxfpath.make_path(entity)
            estimate = dxf._flattened_count(p, tolerance, 1.0, "here")
            actual = len(list(p.flattening(tolerance)))
            assert estimate / 2 <= actual <= 2 * estimate, (entity.dxftype(), tolerance)


# --- meshing an outline ---------------------------------------------------------------------

def test_an_over_budget_mesh_is_refused_before_any_cell_is_made(monkeypatch):
    """The estimate comes first: the tessellation is never started."""
    def never(*args):
        raise AssertionError("cells were made")

    monkeypatch.setattr(outline_mesh, "_relaxed_cells", never)
    monkeypatch.setattr(outline_mesh, "_triangles", never)
    square, sliver = shapely.box(0, 0, 100, 100), shapely.box(0, 0, 100, 0.3)
    for kind, region, cell, needle in [
            ("quad", square, 0.2, "would give about 250,000 faces (10,000 mm²) and 2,005 "
                                  "outline points; at most 10,000 in all"),
            ("tri", square, 0.2, "250,000 faces"),
            ("voronoi", sliver, 0.001, "30,000,000 faces"),
            ("hex", square, 0.0, "--cell 0 mm is not a positive length"),
            ("hex", shapely.Polygon([(0, 0), (10, 10), (10, 0), (0, 10)]), None,
             "the outline encloses no area")]:
        with pytest.raises(MeshError, match=re.escape(needle)):
            outline_mesh.mesh_outline(region, kind, cell)


def test_a_thin_diagonal_outline_is_refused_by_its_bounding_box():
    """A band 1414 mm long and 0.5 mm wide at 45 degrees: 873 cells of 0.9 mm inside it, 1.2
    million over its bounding box."""
    band = shapely.LineString([(0, 0), (1000, 1000)]).buffer(0.25, cap_style="flat")
    with pytest.raises(MeshError, match=r"^--cell 0.9 mm would lay 1,239,891 cells over the "
                                        r"outline's bounding box \(1000 x 1000 mm\) for 873 "
                                        r"inside it; at most 1,000,000: give a larger --cell$"):
        outline_mesh.mesh_outline(band, "quad", 0.9)


def test_the_lattice_covers_the_bounding_box_only():
    """The lattice points inside an outline are those of the old lattice over a square twice
    the largest side around it (16 million points for a 100 x 0.01 mm sliver), in the same
    order: meshes of valid drawings do not change."""
    def old(kind, region, spacing):
        x0, y0, x1, y1 = region.bounds
        a = np.array([spacing, 0.0])
        b = (np.array([0.0, spacing]) if kind == "quad"
             else spacing * np.array([0.5, math.sqrt(3) / 2]))
        n = int(math.ceil(2 * max(x1 - x0, y1 - y0) / spacing)) + 2
        i, j = np.meshgrid(np.arange(-n, n + 1), np.arange(-n, n + 1))
        points = i.reshape(-1, 1) * a + j.reshape(-1, 1) * b + (a + b) / 2 + (x0, y0)
        return points[shapely.contains_xy(region, *points.T)]

    rng = np.random.default_rng(7)
    regions = [shapely.box(0, 0, 100, 0.5), shapely.box(-3, 7, 4, 90),
               shapely.Point(5, 5).buffer(40),
               shapely.box(0, 0, 50, 50).difference(shapely.box(10, 10, 20, 20)),
               *(shapely.Polygon(rng.uniform(-50, 50, (3, 2))) for _ in range(12))]
    for region in regions:
        for kind in ("quad", "hex"):
            for spacing in (0.7, 3.7, 13.0, 60.0):
                got, want = _lattice(kind, region, spacing), old(kind, region, spacing)
                assert got.shape == want.shape and (got == want).all(), (kind, spacing)


# --- any hostile drawing ------------------------------------------------------------------

@settings(max_examples=max(10, settings.default.max_examples // 2),
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                 HealthCheck.function_scoped_fixture])
@given(ws.hostile_drawings(), st.sampled_from([[], ["--mesh", "none"], ["--flatten", "1e-6mm"],
                                               ["--mesh", "quad", "--cell", "0.5mm"]]))
def test_hostile_drawing_is_read_or_refused_in_one_line(tmp_path, drawing, options):
    """Hostile numbers, deep <use>, many elements: read fine or refused in one line, within
    the bound, never an internal error (nor 'out of memory' from a small drawing)."""
    suffix, text = drawing
    path = tmp_path / f"hostile{suffix}"
    path.write_text(text)
    with bounded():
        result = run("stats", path, "--levels", "0", *options)
    event(f"{suffix} exit {result.exit_code}")
    if result.exit_code == 0:
        assert "Traceback" not in result.output and "internal error" not in result.output
        return
    line = refused(result)
    assert "out of memory" not in line, line
