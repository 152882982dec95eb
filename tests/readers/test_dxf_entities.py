"""DXF entities read back as rings or open pieces, written with ezdxf as a CAD program would.

Expected shapes come from the entities' own geometry (bulge arcs, ellipse radii, circle
sagitta in mm whatever the drawing unit), not from the reader.
"""

from __future__ import annotations

import math
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely

from weavecut.errors import MeshFileError
from weavecut.readers import dxf as dxf_reader
from weavecut.readers.drawing import read_drawing


def write(tmp_path: Path, build, units: int = 4) -> Path:
    doc = ezdxf.new("R2000")
    doc.units = units
    build(doc.modelspace())
    path = tmp_path / "entities.dxf"
    doc.saveas(path)
    return path


def kinds(rings) -> list[str]:
    return [r.label.split()[0] for r in rings]


def test_every_closed_entity_is_a_ring_and_open_ones_are_pieces(tmp_path):
    """Closed LWPOLYLINE (with a bulge), closed 2-D POLYLINE, full ELLIPSE, closed SPLINE,
    and an LWPOLYLINE not flagged closed whose last point is its first are rings; a half
    ELLIPSE, an ARC, a LINE are pieces; a 3-D POLYLINE is no planar outline."""
    def build(msp):
        msp.add_lwpolyline([(0, 0, 0), (10, 0, 1), (10, 10, 0), (0, 10, 0)], format="xyb",
                           close=True)
        msp.add_polyline2d([(20, 0), (30, 0), (30, 10)], close=True)
        msp.add_polyline3d([(40, 0, 0), (50, 0, 1), (50, 10, 2)], close=True)
        msp.add_ellipse((100, 0), major_axis=(20, 0), ratio=0.5)
        msp.add_ellipse((100, 100), major_axis=(20, 0), ratio=0.5, start_param=0,
                        end_param=math.pi)
        msp.add_spline([(0, 80), (10, 90), (20, 80), (10, 70)]).closed = True
        msp.add_lwpolyline([(60, 60), (70, 60), (70, 70), (60, 70), (60, 60)])
        msp.add_arc((0, -50), 10, 0, 180)
        msp.add_line((0, -80), (10, -80))
    rings, pieces = dxf_reader.read_rings(write(tmp_path, build), 0.05)
    assert kinds(rings) == ["LWPOLYLINE", "POLYLINE", "ELLIPSE", "SPLINE", "LWPOLYLINE"]
    assert kinds(pieces) == ["ELLIPSE", "ARC", "LINE"]
    areas = [shapely.Polygon(r.points).area for r in rings]
    # the square with a half circle of radius 5 bulging out of its right side
    assert areas[0] == pytest.approx(100 + math.pi * 25 / 2, abs=math.pi * 5 * 0.05)
    assert areas[1] == pytest.approx(50.0)
    assert areas[2] == pytest.approx(math.pi * 20 * 10, abs=2 * math.pi * 20 * 0.05)
    assert areas[4] == pytest.approx(100.0)
    # no ring repeats its first point at its end; the open pieces keep both ends
    assert all(np.hypot(*(r.points[-1] - r.points[0])) > 0.05 for r in rings)
    assert len(rings[4].points) == 4
    assert pieces[2].points.tolist() == [[0, -80], [10, -80]]
    arc = pieces[1].points
    assert arc[0] == pytest.approx([10, -50]) and arc[-1] == pytest.approx([-10, -50])


def test_an_ellipse_from_any_start_is_closed_when_it_turns_once(tmp_path):
    """A full turn that starts at a quarter is closed; three quarters of a turn are not."""
    def build(msp):
        msp.add_ellipse((0, 0), major_axis=(20, 0), ratio=0.5, start_param=math.pi / 2,
                        end_param=math.pi / 2 + 2 * math.pi)
        msp.add_ellipse((100, 0), major_axis=(20, 0), ratio=0.5, start_param=0,
                        end_param=1.5 * math.pi)
    rings, pieces = dxf_reader.read_rings(write(tmp_path, build), 0.05)
    assert len(rings) == 1 and len(pieces) == 1
    x, y = rings[0].points.T
    assert (x / 20) ** 2 + (y / 10) ** 2 == pytest.approx(1.0, abs=2e-3)


@pytest.mark.slow
@pytest.mark.parametrize("units, mm", [(0, 1.0), (1, 25.4), (4, 1.0), (5, 10.0), (6, 1000.0)])
def test_curves_are_flattened_to_the_tolerance_in_mm(tmp_path, units, mm):
    """A circle of radius 1 drawing unit: in mm, within the 0.2 mm tolerance of the true circle
    all round (Hausdorff distance), with no more than twice the vertices that needs (a
    unitless drawing is in mm). ezdxf flattens the Bézier form of the circle, which strays
    from it by 2.7e-4 of the radius."""
    rings, _ = dxf_reader.read_rings(write(tmp_path, lambda m: m.add_circle((3, 4), 1.0),
                                           units), 0.2)
    points = rings[0].points
    t = np.linspace(0, 2 * np.pi, 20000, endpoint=False)
    circle = shapely.LinearRing(np.column_stack([3 + np.cos(t), 4 + np.sin(t)]) * mm)
    assert shapely.hausdorff_distance(shapely.LinearRing(points), circle,
                                      densify=0.01) <= 0.2 + 3e-4 * mm
    fewest = math.ceil(math.pi / math.acos(1 - min(0.2 / mm, 1.0)))
    assert len(points) <= 2 * max(fewest, 16)  # ezdxf cuts a circle into 16 at least


def test_layers(tmp_path):
    def build(msp):
        msp.add_circle((0, 0), 5, dxfattribs={"layer": "A"})
        msp.add_circle((20, 0), 5, dxfattribs={"layer": "B"})
        msp.add_line((0, 0), (1, 1), dxfattribs={"layer": "B"})
    path = write(tmp_path, build)
    rings, pieces = dxf_reader.read_rings(path, 0.2, "B")
    assert [r.label.split("(")[1] for r in rings + pieces] == ["layer 'B')"] * 2
    assert np.mean(rings[0].points, axis=0) == pytest.approx([20, 0], abs=0.1)
    with pytest.raises(MeshFileError, match=r"no outlines on layer 'C'; layers: A, B$"):
        dxf_reader.read_rings(path, 0.2, "C")


def test_not_a_dxf_is_one_short_line(tmp_path):
    path = tmp_path / "x.dxf"
    path.write_bytes(b"0\nSECTION\n2\nHEADER\n" + b"x" * 5000)
    with pytest.raises(MeshFileError) as error:
        dxf_reader.read_rings(path, 0.2)
    text = str(error.value)
    assert "\n" not in text and len(text) <= 200 and "not a readable DXF" in text
    with pytest.raises(MeshFileError, match="not a readable DXF"):
        dxf_reader.read_rings(tmp_path / "missing.dxf", 0.2)


@pytest.mark.parametrize("add", ["lwpolyline", "polyline2d"])
def test_a_closed_polyline_of_two_points_is_a_ring_that_encloses_nothing(tmp_path, add):
    """Closed is the entity's flag, not a count of points: a closed polyline drawn through two
    points is a ring (there and back), and reading the drawing names it as enclosing no
    area, not as a line with an open end."""
    def build(msp):
        msp.add_lwpolyline([(0, 0), (10, 0), (10, 10), (0, 10)], close=True)
        getattr(msp, f"add_{add}")([(20, 0), (30, 0)], close=True)
    path = write(tmp_path, build)
    rings, pieces = dxf_reader.read_rings(path, 0.05)
    assert len(rings) == 2 and not pieces
    assert rings[1].points.tolist() == [[20, 0], [30, 0]]
    with pytest.raises(MeshFileError, match=r"(LW)?POLYLINE #\w+ \(layer '0'\) encloses no "
                                            r"area$"):
        read_drawing(path)


@pytest.mark.parametrize("error", [ValueError("Invalid major axis (null vector)."),
                                   ZeroDivisionError("float division")])
def test_an_error_of_ezdxfs_repair_is_one_line(tmp_path, monkeypatch, error):
    """ezdxf's recover/audit raises ValueError ("Invalid major axis (null vector)", seen on a
    degenerate ELLIPSE) or ZeroDivisionError on data it cannot repair: the reader names the
    file and the error in one line (the corpus holds a drawing that raises the second)."""
    path = write(tmp_path, lambda msp: msp.add_circle((0, 0), 5))

    def fails(stream):
        raise error

    monkeypatch.setattr(dxf_reader.recover, "read", fails)
    with pytest.raises(MeshFileError, match=r"not a readable DXF \(ezdxf's repair failed: "
                       + type(error).__name__) as info:
        dxf_reader.read_rings(path, 0.1)
    assert str(path) in str(info.value) and "\n" not in str(info.value)
