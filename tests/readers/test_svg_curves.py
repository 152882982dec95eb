"""SVG curves read back: every vertex on the drawn curve, no chord farther from it than the
tolerance, and no more chords than that needs.

The oracle is the curve itself, evaluated here from its control points (Bernstein form) and
sampled densely; the reader's chord count is compared with the fewest equal parameter steps
whose chords keep within the tolerance, found by trying them one by one.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from weavecut.errors import MeshFileError
from weavecut.readers import svg as svg_reader

SVG = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape='
       '"http://www.inkscape.org/namespaces/inkscape" width="{size}" height="{size}" '
       'viewBox="0 0 200 200">{body}</svg>')


def drawing(tmp_path: Path, body: str, size: str = "200mm") -> Path:
    path = tmp_path / "curves.svg"
    path.write_text(SVG.format(size=size, body=body), encoding="utf-8")
    return path


def bezier(control: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Points of the Bézier curve with ``control`` points at parameters ``t`` (Bernstein)."""
    n = len(control) - 1
    basis = np.stack([math.comb(n, k) * t ** k * (1 - t) ** (n - k) for k in range(n + 1)], 1)
    return basis @ control


def chord_error(control: np.ndarray, n: int) -> float:
    """Largest distance between the curve and the chords of ``n`` equal parameter steps."""
    t = np.linspace(0, 1, 200 * n + 1)
    curve = bezier(control, t)
    ends = bezier(control, np.linspace(0, 1, n + 1))
    step = np.minimum((t * n).astype(int), n - 1)
    a, b = ends[step], ends[step + 1]
    s = np.clip(((curve - a) * (b - a)).sum(1) / ((b - a) ** 2).sum(1), 0, 1)
    return float(np.hypot(*(curve - a - s[:, None] * (b - a)).T).max())


def fewest_chords(control: np.ndarray, tolerance: float) -> int:
    n = 1
    while chord_error(control, n) > tolerance:
        n += 1
    return n


def in_mm(points_svg: np.ndarray) -> np.ndarray:
    """SVG user units of the 200 mm document are mm; y turns up."""
    return points_svg * (1.0, -1.0)


@pytest.mark.parametrize("control, flatten", [
    ([(0, 0), (50, 80), (100, 0)], 0.2),
    ([(0, 0), (50, 80), (100, 0)], 0.05),
    ([(10, 10), (150, 20), (20, 190)], 0.3),
    ([(0, 100), (30, 100), (60, 100.5)], 0.2),   # nearly straight: one chord
])
def test_quadratic_curves_take_the_fewest_chords_within_the_tolerance(tmp_path, control,
                                                                      flatten):
    """A parabola's chord error shrinks with the square of the step, so the fewest equal steps
    within the tolerance are found by counting up; the reader takes exactly that many."""
    control = np.array(control, dtype=float)
    (x0, y0), (x1, y1), (x2, y2) = control
    path = drawing(tmp_path, f'<path id="q" d="M {x0},{y0} Q {x1},{y1} {x2},{y2}"/>')
    rings, pieces = svg_reader.read_rings(path, flatten)
    assert not rings and len(pieces) == 1 and pieces[0].label == "<path id='q'>"
    points = pieces[0].points
    n = fewest_chords(in_mm(control), flatten)
    assert len(points) == n + 1
    assert points == pytest.approx(bezier(in_mm(control), np.linspace(0, 1, n + 1)), abs=1e-9)


@pytest.mark.parametrize("flatten", [0.2, 0.02])
def test_cubic_curves_stay_within_the_tolerance(tmp_path, flatten):
    """An S-shaped cubic: vertices on the curve, chords within the tolerance, and at most
    twice the chords the curve needs (the reader's bound is not tight for cubics)."""
    control = np.array([(20, 20), (180, 20), (20, 180), (180, 180)], dtype=float)
    d = "M 20,20 C 180,20 20,180 180,180"
    rings, pieces = svg_reader.read_rings(drawing(tmp_path, f'<path id="s" d="{d}"/>'),
                                          flatten)
    points = pieces[0].points
    n = len(points) - 1
    curve = in_mm(control)
    assert points == pytest.approx(bezier(curve, np.linspace(0, 1, n + 1)), abs=1e-9)
    assert chord_error(curve, n) <= flatten
    assert n <= 2 * fewest_chords(curve, flatten)


@pytest.mark.parametrize("r, flatten", [(20.0, 0.2), (20.0, 0.01), (0.1, 0.2), (60.0, 1.0)])
def test_a_circle_has_the_fewest_points_within_the_tolerance(tmp_path, r, flatten):
    """svgelements draws a circle as four quarter arcs; each is cut into the fewest equal
    steps whose sagitta r (1 - cos(step / 2)) stays within the tolerance (a circle smaller
    than the tolerance keeps one chord per quarter)."""
    rings, _ = svg_reader.read_rings(
        drawing(tmp_path, f'<circle id="c" cx="100" cy="100" r="{r}"/>'), flatten)
    (ring,) = rings
    assert rings[0].label == "<circle id='c'>"
    per_quarter = 1
    while r * (1 - math.cos(math.pi / 4 / per_quarter)) > flatten:
        per_quarter += 1
    assert len(ring.points) == 4 * per_quarter
    assert np.hypot(*(ring.points - (100, -100)).T) == pytest.approx(r, rel=1e-9)


def test_an_elliptic_arc_is_cut_by_its_larger_radius(tmp_path):
    """A half ellipse with radii 40 and 10: the sagitta is worst where the curve is flattest
    (radius 40), so the steps are those of a circle of radius 40 over the half turn."""
    flatten = 0.2
    _, pieces = svg_reader.read_rings(
        drawing(tmp_path, '<path id="e" d="M 20,100 A 40,10 0 0 1 100,100"/>'), flatten)
    steps = math.ceil(math.pi / (2 * math.acos(1 - flatten / 40)))
    assert len(pieces[0].points) == steps + 1


def test_closed_and_open_subpaths(tmp_path):
    """One path of three subpaths: a closed triangle (Z), an open zig-zag, and a square
    whose last point returns to its first without Z (closed as drawn, the repeated point
    dropped). Each is named after its subpath."""
    d = ("M 0,0 L 40,0 L 0,30 Z M 100,0 L 120,20 L 140,0 "
         "M 0,100 L 50,100 L 50,150 L 0,150 L 0,100")
    rings, pieces = svg_reader.read_rings(drawing(tmp_path, f'<path id="p" d="{d}"/>'), 0.2)
    assert [r.label for r in rings] == ["<path id='p'>", "<path id='p'> (subpath 3)"]
    assert [p.label for p in pieces] == ["<path id='p'> (subpath 2)"]
    assert rings[0].points == pytest.approx(np.array([[0, 0], [40, 0], [0, -30]]))
    assert rings[1].points == pytest.approx(np.array([[0, -100], [50, -100], [50, -150],
                                                      [0, -150]]))
    assert pieces[0].points == pytest.approx(np.array([[100, 0], [120, -20], [140, 0]]))


def test_a_lone_move_or_a_shape_without_an_id(tmp_path):
    """A subpath of one point is no outline; an element without id is named by its tag."""
    rings, pieces = svg_reader.read_rings(
        drawing(tmp_path, '<path d="M 5,5"/><rect x="0" y="0" width="10" height="10"/>'), 0.2)
    assert not pieces and [r.label for r in rings] == ["<rect>"]


def test_layers_by_label_or_id_nested_groups(tmp_path):
    """A layer chosen by its Inkscape label or by its id keeps the shapes of groups inside
    it; an unknown layer lists every named group (by label, else id; a group may have a
    label and no id), sorted."""
    ink = "{http://www.inkscape.org/namespaces/inkscape}"
    assert ink == svg_reader.INKSCAPE
    body = ('<g id="g1" inkscape:label="Cut"><g id="inner" inkscape:label="Inner">'
            '<rect id="a" width="10" height="10"/></g></g>'
            '<g id="g2"><rect id="b" x="50" width="10" height="10"/></g>'
            '<rect id="c" x="100" width="10" height="10"/>'
            '<g inkscape:label="No id"><rect id="d" x="150" width="10" height="10"/></g>')
    path = drawing(tmp_path, body)
    for name, expected in (("Cut", ["a"]), ("g1", ["a"]), ("Inner", ["a"]), ("g2", ["b"]),
                           ("No id", ["d"]), (None, ["a", "b", "c", "d"])):
        rings, _ = svg_reader.read_rings(path, 0.2, name)
        assert [r.label for r in rings] == [f"<rect id='{x}'>" for x in expected]
    with pytest.raises(MeshFileError) as error:
        svg_reader.read_rings(path, 0.2, "nope")
    assert str(error.value).endswith(
        "no shapes in a layer or group named 'nope'; layers: Cut, Inner, No id, g2")


def test_a_drawing_without_groups_lists_no_layers(tmp_path):
    path = drawing(tmp_path, '<rect id="a" width="10" height="10"/>')
    with pytest.raises(MeshFileError, match="named 'x'; layers: none$"):
        svg_reader.read_rings(path, 0.2, "x")


@pytest.mark.parametrize("size, viewbox_mm", [("200mm", 1.0), ("20cm", 1.0), ("800q", 1.0),
                                              ("400mm", 2.0), ("200", 25.4 / 96)])
def test_document_units_to_the_last_digit(tmp_path, size, viewbox_mm):
    """A 50-unit square in a 200-unit viewBox: 50 mm in a 200 mm (20 cm, 800 Q) page to the
    last digit (svgelements' 0.0393701 in/mm undone), 100 mm in a 400 mm one; a page without
    units is in CSS pixels."""
    rings, _ = svg_reader.read_rings(
        drawing(tmp_path, '<rect id="a" x="10" y="10" width="50" height="50"/>', size), 0.2)
    side = np.ptp(rings[0].points, axis=0)
    assert side == pytest.approx([50 * viewbox_mm] * 2, rel=1e-13)
