"""Every numeric option is finite and in range, refused before any file is written."""

from __future__ import annotations

import pytest

from .helpers import refused, run

# each once wrote NaN or 'infmm' into a file, or was an internal error
CASES = [
    ["strands", "square-grid", "--turn", "nan", "-o", "{d}/s.pdf"],
    ["strands", "square-grid", "--turn", "inf", "-o", "{d}/s.pdf"],
    ["strands", "square-grid", "--turn", "1e400", "-o", "{d}/s.pdf"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--speed", "nan"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--speed", "inf"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--speed", "-1"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--sheet", "1e400x1e400"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--sheet", "nanxnan"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--sheet", "100000x100000mm"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--kerf", "1e400"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--size", "1e309mm"],
    ["puzzle", "-o", "{d}/p", "--levels", "2", "--frame", "-1mm"],
    ["strands", "square-grid", "--page", "1e400x1e400", "-o", "{d}/s.pdf"],
    ["strands", "square-grid", "--margin", "nan", "-o", "{d}/s.pdf"],
    ["subdivide", "pentagon", "--size", "1e400", "-o", "{d}/x.svg"],
    ["weave", "square-grid", "--size", "-0", "-o", "{d}/x.svg"],
    ["levels", "pentagon", "--levels", "2", "--window", "nan,0,1,1", "-o", "{d}/l.png"],
    ["levels", "pentagon", "--levels", "2", "--window", "0,0,1e400,1", "-o", "{d}/l.png"],
    ["levels", "pentagon", "--levels", "2", "--window", "-1e308,-1e308,1e308,1e308", "-o",
     "{d}/l.png"],
]


@pytest.mark.parametrize("args", CASES, ids=[" ".join(a[2:5]) for a in CASES])
def test_non_finite_and_out_of_range_numbers_are_usage_errors(tmp_path, args):
    refused(run(*[a.format(d=tmp_path) for a in args]), status=(2,))
    assert not list(tmp_path.iterdir())
