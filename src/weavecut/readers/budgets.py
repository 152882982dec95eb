"""Budgets of an untrusted drawing, checked before the work they bound.

A drawing of a few kilobytes can ask for 10^8 shapes (nested ``<use>``), a million path
segments or points (a tiny ``--flatten``), coordinates of 1e300 or NaN, or a mesh of a million
cells. Each limit below says what it keeps affordable (times measured on a busy 2-core
machine); a drawing over one is refused in one line with the numbers (``MeshFileError``).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import MeshFileError

MAX_ELEMENTS = 10_000
"""SVG elements (``<use>`` copies expanded) or DXF entities read: each costs about 1 ms
(svgelements' objects, a shapely polygon, welding), so 10 s at most; a mesh drawn by hand has
hundreds of faces."""
MAX_PATH_DATA = 300_000
"""Numbers and commands in SVG ``d``, ``points`` and ``transform`` attributes (``<use>``
copies expanded): svgelements makes Python objects of each, about 15 us a number (5 s); a
path of 100,000 straight segments fits."""
MAX_PATH_TEXT = 32 * MAX_PATH_DATA
"""Characters of that path data: a number is at most 24 characters and a separator; whitespace
beyond costs the counting regex 50 ns a character (60 MB of it took 3 s)."""
MAX_POINTS = 100_000
"""Points of all outlines after curves are flattened: each ring is checked, nested and welded
by shapely and scipy, which a 100,000-point ring keeps within seconds (a self-touching one
costs GEOS about 0.2 ms a point); at the default 0.2 mm a 1 m circle has 111 points."""
MAX_FIT_POINTS = 4_000
"""Fit points of all DXF splines: ezdxf interpolates them with a dense solve (4,000 points
take 2 s, 16,000 a minute)."""
MAX_DXF_LINES = 500_000
"""Lines of DXF text: ezdxf parses about 70,000 tags (two lines each) a second before any
entity can be counted; a LWPOLYLINE of 100,000 vertices fits."""
MAX_DEGREE = 10
"""SPLINE degree: ezdxf evaluates orders up to 11; CAD programs draw degree 3 (rarely 5)."""
MAX_COORDINATE = 1e6
"""mm (1 km, the largest length an option takes): beyond it, squares of coordinates lose
every digit a weld or an area needs, and 1e300 overflows."""
MAX_CELLS = 10_000
"""Faces plus outline points of a meshed outline: the mesher clips, cuts and merges cells one
by one, about 1.5 ms each (4 ms for voronoi), so 15 to 40 s; the snub levels multiply the faces
anyway (mesh coarser and add a level)."""
MAX_GRID = 1_000_000
"""Lattice points or random seeds laid over an outline's bounding box before it is clipped (a
thin diagonal outline fills little of its box): 16 MB and under a second."""


def amount(n: float) -> str:
    """``n`` for a message: '12,345', or '1.2e+40' when it has too many digits to read."""
    return f"{n:,.0f}" if n < 1e15 else f"{n:.2g}"


def curve_pieces(m: float, tolerance: float) -> float:
    """Chords that keep a curve with second derivative at most ``m`` within ``tolerance``:
    cutting the parameter range [0, 1] into n equal parts, a chord strays by at most
    m / (8 n^2). ``math.inf`` when that overflows."""
    n = math.sqrt(m / (8 * tolerance))
    return max(1, math.ceil(n)) if math.isfinite(n) else math.inf


def bezier_pieces(control: np.ndarray, tolerance: float) -> float:
    """``curve_pieces`` of a quadratic (3, 2) or cubic (4, 2) Bezier control polygon."""
    p = control
    if len(p) == 3:
        return curve_pieces(2 * np.hypot(*(p[0] - 2 * p[1] + p[2])), tolerance)
    return curve_pieces(6 * max(np.hypot(*(p[0] - 2 * p[1] + p[2])),
                                np.hypot(*(p[1] - 2 * p[2] + p[3]))), tolerance)


def check_coordinates(where: str, values, mm: float = 1.0, what: str = "coordinate") -> None:
    """Refuse ``values`` (``mm`` millimetres a unit) unless every one is finite and within
    MAX_COORDINATE."""
    with np.errstate(over="ignore", invalid="ignore"):  # 1e300 parsecs: inf, refused below
        values = np.asarray(values, dtype=float).reshape(-1) * mm
    bad = ~(np.abs(values) <= MAX_COORDINATE)  # NaN too
    if bad.any():
        value = float(values[np.argmax(bad)])
        if math.isfinite(value):
            raise MeshFileError(f"{where}: {what} {value:.3g} mm is beyond "
                                f"±{MAX_COORDINATE / 1e6:g} km")
        raise MeshFileError(f"{where}: {what} {value} is not a finite number")


def check_points(where: str, count: float, flatten: float) -> None:
    """Refuse a drawing whose flattened outlines would have more than MAX_POINTS points."""
    if count > MAX_POINTS:
        raise MeshFileError(f"{where}: curves flattened to within --flatten {flatten:g} mm "
                            f"give {amount(count)} points; at most {MAX_POINTS:,} are read: "
                            "give a larger --flatten")
