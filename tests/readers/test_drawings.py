"""SVG and DXF drawings read back as meshes: counts, areas, units, shared edges, clear errors.

The drawings here are written by hand in Inkscape's dialect (layers, transforms, mm document
units) or with ezdxf, as LibreCAD or any CAD program would write them; the expected numbers
come from the drawing (sides, radii, unit factors), not from the reader.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from weavecut.errors import MeshError, MeshFileError
from weavecut.mesh import Mesh, edge_faces
from weavecut.mesh_geometry import signed_areas
from weavecut.readers.drawing import read_drawing
from weavecut.validation import validate

from ..strategies import valid_meshes

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

INKSCAPE = """<?xml version="1.0" encoding="UTF-8" standalone="no"?>
<svg width="{width}" height="{height}" viewBox="{viewbox}" version="1.1" id="svg1"
   xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
   xmlns:sodipodi="http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"
   xmlns="http://www.w3.org/2000/svg" xmlns:svg="http://www.w3.org/2000/svg">
  <sodipodi:namedview id="namedview1" inkscape:document-units="mm"/>
  <defs id="defs1"/>
{body}
</svg>
"""


def svg(tmp_path: Path, body: str, width="200mm", height="200mm", viewbox="0 0 200 200",
        name="drawing.svg") -> Path:
    path = tmp_path / name
    path.write_text(INKSCAPE.format(width=width, height=height, viewbox=viewbox, body=body),
                    encoding="utf-8")
    return path


def euler(mesh: Mesh) -> int:
    return mesh.n_vertices - mesh.topology.n_edges + mesh.n_faces


def layer(label: str, body: str, transform: str = "", hidden: bool = False) -> str:
    attrs = f' transform="{transform}"' if transform else ""
    attrs += ' style="display:none"' if hidden else ""
    return (f'  <g inkscape:label="{label}" inkscape:groupmode="layer" id="{label}"{attrs}>\n'
            f"{body}\n  </g>")


# --- SVG: units, transforms, layers -------------------------------------------------------

@pytest.mark.parametrize("width, viewbox, unit_mm", [
    ("200mm", "0 0 200 200", 1.0),          # Inkscape's default: user unit = mm
    ("100mm", "0 0 400 400", 0.25),         # a scaled viewBox
    ("4in", "0 0 4 4", 25.4),               # inches
    ("400", "0 0 400 400", 25.4 / 96),      # bare numbers are CSS pixels
    ("20cm", "0 0 200 200", 1.0),
    ("288pt", "0 0 4 4", 25.4),             # points, 72 per inch
    ("400px", "0 0 400 400", 25.4 / 96),    # CSS pixels, 96 per inch, written out
    ("24pc", "0 0 4 4", 25.4),              # picas, 6 per inch (CSS Values 3, sec. 6.2)
    ("400Q", "0 0 100 100", 1.0),           # quarter-millimetres (CSS Values 3, sec. 6.2)
])
def test_a_square_is_its_size_in_every_unit(tmp_path, width, viewbox, unit_mm):
    side = float(viewbox.split()[2]) / 4
    body = layer("Layer 1", f'    <rect id="r" x="{side}" y="{side}" width="{side}" '
                 f'height="{side}"/>')
    mesh = read_drawing(svg(tmp_path, body, width=width, height=width, viewbox=viewbox),
                        mesh="none")
    assert mesh.n_faces == 1 and mesh.n_vertices == 4
    # exact: the reader undoes svgelements' 0.0393701 inch per mm (5.4 ppm above 1 / 25.4)
    assert abs(signed_areas(mesh)).sum() == pytest.approx((side * unit_mm) ** 2, rel=1e-12)
    assert np.ptp(mesh.vertices, axis=0) == pytest.approx([side * unit_mm] * 2, rel=1e-12)


def test_inkscape_drawing_with_layers_transforms_and_a_hidden_layer(tmp_path):
    """A 50 mm square moved by its layer, a 30 x 20 mm rectangle rotated by 30 degrees and
    scaled by 2 in a group, a path with relative commands, and a hidden layer."""
    body = "\n".join([
        layer("Squares", '    <rect id="square" x="0" y="0" width="50" height="50"/>\n'
              '    <g transform="rotate(30 120 40) scale(2)">\n'
              '      <rect id="scaled" x="50" y="10" width="15" height="10"/>\n    </g>',
              transform="translate(10,20)"),
        layer("Paths", '    <path id="tri" d="m 10,150 h 40 l -40,30 z"/>'),
        layer("Hidden", '    <rect id="ghost" x="100" y="100" width="80" height="80"/>',
              hidden=True),
    ])
    path = svg(tmp_path, body)
    mesh = read_drawing(path, mesh="none")
    areas = np.sort(np.abs(signed_areas(mesh)))
    assert mesh.n_faces == 3
    assert areas == pytest.approx(sorted([2500.0, 30 * 20, 40 * 30 / 2]), rel=2e-5)
    # the translate moved the square: its corners are (10, 20) .. (60, 70), y turned up
    square = mesh.vertices[mesh.faces()[int(np.argmax(np.abs(signed_areas(mesh))))]]
    assert sorted(map(tuple, square.round(3))) == [(10, -70), (10, -20), (60, -70), (60, -20)]
    only = read_drawing(path, mesh="none", layer="Paths")
    assert only.n_faces == 1 and abs(signed_areas(only)[0]) == pytest.approx(600.0, rel=2e-5)


def test_curves_are_flattened_to_the_tolerance(tmp_path):
    """A circle (r = 20 mm) and a path of two arcs: every vertex on the circle, the area
    within perimeter x tolerance of pi r^2, and to 0.1 % at a fine tolerance."""
    body = layer("Layer 1", '    <circle id="c" cx="100" cy="100" r="20"/>\n'
                 '    <path id="arcs" d="M 20,40 A 10,10 0 0 1 40,40 A 10,10 0 0 1 20,40 Z"/>')
    path = svg(tmp_path, body)
    for flatten in (0.2, 0.01):
        mesh = read_drawing(path, mesh="none", flatten=flatten)
        areas = np.abs(signed_areas(mesh))
        big, small = np.argmax(areas), np.argmin(areas)
        for face, r in ((big, 20.0), (small, 10.0)):
            pts = mesh.vertices[mesh.faces()[face]]
            centre = pts.mean(axis=0)
            radii = np.hypot(*(pts - centre).T)
            assert radii == pytest.approx(r, rel=1e-6)
            chord = 2 * r * np.sin(np.pi / len(pts))
            assert r - np.sqrt(r ** 2 - chord ** 2 / 4) <= flatten + 1e-9  # sagitta
            assert math.pi * r ** 2 - areas[face] <= 2 * math.pi * r * flatten
        if flatten == 0.01:
            assert areas[big] == pytest.approx(math.pi * 400, rel=1e-3)


# --- shared edges ------------------------------------------------------------------------

def test_example_tiles_share_their_edges():
    """The hand-drawn 3.4.6.4 patch: 1 hexagon, 6 squares, 6 triangles; V = 6 + 12 = 18,
    E = 6 + 6 + 12 + 6 = 30 (hexagon, square outer, square-triangle, triangle outer)."""
    reports = []
    mesh = validate(read_drawing(EXAMPLES / "tiles.svg", report=reports.append))
    assert (mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces) == (18, 30, 13)
    assert euler(mesh) == 1
    assert np.bincount(mesh.face_sizes)[3:] .tolist() == [6, 6, 0, 1]
    sides = np.hypot(*(mesh.vertices[mesh.topology.edges[:, 0]]
                       - mesh.vertices[mesh.topology.edges[:, 1]]).T)
    assert sides == pytest.approx(20.0, abs=0.06)
    assert "1 points within 0.2 mm merged" in reports[0]


def test_t_junctions_and_near_misses_become_shared_edges(tmp_path):
    """A 40 mm square beside two 20 mm squares (its edge is split by their common corner on
    one side only), one corner 0.05 mm off: 8 vertices, 10 edges, 3 faces, Euler 1."""
    body = layer("Layer 1", '\n'.join([
        '    <polygon id="big" points="0,0 40,0 40,40 0,40"/>',
        '    <polygon id="top" points="40,0 60,0 60,20 40.05,20"/>',   # clockwise in y-up
        '    <polygon id="bottom" points="40,40 40,20 60,20 60,40"/>',
    ]))
    reports = []
    mesh = validate(read_drawing(svg(tmp_path, body), report=reports.append))
    assert (mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces) == (8, 10, 3)
    assert euler(mesh) == 1
    assert (edge_faces(mesh) >= 0).all(axis=1).sum() == 3  # shared: 2 halves + 1
    assert "1 points within 0.2 mm merged" in reports[0]


# --- DXF ---------------------------------------------------------------------------------

def dxf(tmp_path: Path, units: int, build) -> Path:
    doc = ezdxf.new("R2000")
    doc.units = units
    build(doc, doc.modelspace())
    path = tmp_path / "drawing.dxf"
    doc.saveas(path)
    return path


def _two_squares_a_loop_and_a_circle(doc, msp):
    msp.add_lwpolyline([(0, 0), (1, 0), (1, 1), (0, 1)], close=True)
    msp.add_lwpolyline([(1, 1), (1, 0), (2, 0), (2, 1)], close=True)  # clockwise
    for a, b in [((0, 1), (2, 1)), ((2, 1), (1, 2)), ((1, 2), (0, 1))]:  # a roof of LINEs
        msp.add_line(a, b)
    msp.add_circle((5, 5), 1, dxfattribs={"layer": "EXTRA"})
    block = doc.blocks.new("B")
    block.add_lwpolyline([(0, 0), (9, 0), (9, 9)], close=True)
    msp.add_blockref("B", (0, 0))


@pytest.mark.parametrize("units, mm", [(1, 25.4), (4, 1.0), (5, 10.0), (6, 1000.0)])
def test_dxf_faces_and_units(tmp_path, units, mm):
    path = dxf(tmp_path, units, _two_squares_a_loop_and_a_circle)
    mesh = validate(read_drawing(path, layer="0", mesh="none"))
    # two unit squares and a triangle (base 2, height 1): 5 vertices... plus the roof's apex
    assert (mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces) == (7, 9, 3)
    assert euler(mesh) == 1
    assert np.abs(signed_areas(mesh)).sum() == pytest.approx(3.0 * mm ** 2, rel=2e-5)
    circle = read_drawing(path, layer="EXTRA", mesh="none", flatten=0.001 * mm)
    assert abs(signed_areas(circle)).sum() == pytest.approx(math.pi * mm ** 2, rel=1e-3)


def test_example_plate_dxf():
    """examples/plate.dxf, in cm: a 16 x 10 cm plate with 2 cm round corners on OUTLINE
    (meshed), a 4 x 2 grid of 2 cm squares drawn as 13 LINEs on GRID (faces as drawn)."""
    grid = validate(read_drawing(EXAMPLES / "plate.dxf", layer="GRID"))
    assert (grid.n_vertices, grid.topology.n_edges, grid.n_faces) == (15, 22, 8)
    assert np.abs(signed_areas(grid)) == pytest.approx(400.0)
    plate = read_drawing(EXAMPLES / "plate.dxf", layer="OUTLINE")
    expected = 160 * 100 - (4 - math.pi) * 20 ** 2
    assert signed_areas(plate).sum() == pytest.approx(expected, rel=1e-3)


# --- errors ------------------------------------------------------------------------------

@pytest.mark.parametrize("body, message", [
    ('<path id="bow" d="M 0,0 L 30,10 L 30,0 L 0,20 Z"/>', "<path id='bow'> crosses itself"),
    ('<rect id="a" width="20" height="20"/><rect id="b" x="10" y="10" width="20" height="20"/>',
     "<rect id='a'> and <rect id='b'> overlap"),
    ('<path id="open" d="M 0,0 L 10,10 L 10,0"/>',
     "<path id='open'> near (0, 0) mm has an open end"),
    ('<path id="flat" d="M 0,0 L 10,0 L 20,0 Z"/>', "<path id='flat'> encloses no area"),
])
def test_bad_drawings_name_the_element(tmp_path, body, message):
    with pytest.raises(MeshFileError, match=re.escape(message)):
        read_drawing(svg(tmp_path, layer("L", body)), mesh="none")


def test_a_hole_needs_meshing(tmp_path):
    body = layer("L", '<rect id="outer" width="50" height="50"/>'
                 '<rect id="inner" x="20" y="20" width="10" height="10"/>')
    with pytest.raises(MeshFileError, match="<rect id='inner'> lies inside <rect id='outer'>"):
        read_drawing(svg(tmp_path, body), mesh="none")
    mesh = read_drawing(svg(tmp_path, body), cell=5.0)  # auto: meshed, the hole kept
    assert signed_areas(mesh).sum() == pytest.approx(2500 - 100, rel=2e-5)
    assert euler(mesh) == 0  # an annulus


def test_unknown_layer_lists_the_layers(tmp_path):
    path = dxf(tmp_path, 4, _two_squares_a_loop_and_a_circle)
    with pytest.raises(MeshFileError, match="no outlines on layer 'NOPE'; layers: 0, EXTRA"):
        read_drawing(path, layer="NOPE")


def test_an_outline_with_lines_across_it(tmp_path):
    """A 40 x 20 mm rectangle (a rect) cut by a vertical line and a polyline: three faces."""
    body = layer("L", '<rect id="r" width="40" height="20"/>'
                 '<line id="a" x1="10" y1="0" x2="10" y2="20"/>'
                 '<polyline id="b" points="25,0 20,10 25,20" style="fill:none"/>')
    mesh = read_drawing(svg(tmp_path, body), mesh="none", allow_nonconvex=True)
    assert mesh.n_faces == 3
    assert np.sort(np.abs(signed_areas(mesh))) == pytest.approx([200.0, 250.0, 350.0], rel=2e-5)


def test_open_line_names_its_entity(tmp_path):
    def build(doc, msp):
        msp.add_line((0, 0), (1, 0))
        msp.add_line((1, 0), (1, 1))
        msp.add_line((1, 1), (0, 0))
        msp.add_line((1, 1), (3, 3))  # a dangling line
    with pytest.raises(MeshFileError, match=r"LINE #\w+ \(layer '0'\) near .* has an open end"):
        read_drawing(dxf(tmp_path, 4, build))


def test_not_a_drawing(tmp_path):
    for name, data in (("x.svg", b"\x00\x01binary"), ("x.dxf", b"not a dxf")):
        (tmp_path / name).write_bytes(data)
        with pytest.raises(MeshError):
            read_drawing(tmp_path / name)


def test_mesh_errors_name_the_element(tmp_path):
    body = layer("L", '<rect id="a" width="20" height="20"/>'
                 '<polygon id="b" points="20,0 40,0 30,10 40,20 20,20"/>')
    with pytest.raises(MeshError, match=r"face 1 \(<polygon id='b'>\) is not convex"):
        read_drawing(svg(tmp_path, body))
    assert read_drawing(svg(tmp_path, body), allow_nonconvex=True).n_faces == 2


@settings(max_examples=20, deadline=None)
@given(valid_meshes, st.integers(0, 2**31 - 1))
def test_random_meshes_drawn_face_by_face_read_back(tmp_path_factory, mesh, seed):
    """Any valid mesh, scaled to 100 mm, drawn as one SVG polygon per face with random
    orientation and every corner nudged by up to 0.05 mm, reads back with its V, E, F."""
    rng = np.random.default_rng(seed)
    points = mesh.vertices / np.ptp(mesh.vertices, axis=0).max() * 100.0
    edges = mesh.topology.edges
    gaps = shapely.distance(shapely.linestrings(points[edges]).reshape(-1, 1),
                            shapely.points(points).reshape(1, -1))
    gaps[np.arange(len(edges)), edges[:, 0]] = gaps[np.arange(len(edges)), edges[:, 1]] = np.inf
    assume(gaps.min() > 1.0)  # nothing closer than 1 mm that the drawing would merge
    shapes = []
    for k, face in enumerate(mesh.faces()):
        corners = points[face] + rng.uniform(-0.035, 0.035, size=(len(face), 2))
        corners = corners[::-1] if rng.integers(2) else corners
        shapes.append(f'<polygon id="f{k}" points="'
                      + " ".join(f"{x:.4f},{-y:.4f}" for x, y in corners) + '"/>')
    path = svg(tmp_path_factory.mktemp("draw"), layer("L", "\n".join(shapes)),
               viewbox="-10 -110 120 120")
    read = validate(read_drawing(path, mesh="none", allow_nonconvex=True))
    assert (read.n_vertices, read.topology.n_edges, read.n_faces) == (
        mesh.n_vertices, mesh.topology.n_edges, mesh.n_faces)
