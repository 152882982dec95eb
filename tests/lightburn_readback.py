"""A LightBurn project read back by lbrnts (npm, MIT; not written here), against the DXF of
the same sheet read by ezdxf.

``tests/lightburn/`` pins the reader (package.json, package-lock.json); ``.ci/run`` installs it
(``npm ci``). Where node or the reader is missing the tests are skipped, except in CI.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import ezdxf
import numpy as np
import pytest

FOLDER = Path(__file__).parent / "lightburn"
SCRIPT = FOLDER / "read.mjs"
TOLERANCE = 0.01  # mm: the writers round to 1e-4 mm (lbrn2) and 1e-6 mm (DXF)


def node() -> str:
    """The node program, with lbrnts installed beside the script; skipped where missing,
    except in CI (``.ci/run`` installs it)."""
    path = shutil.which("node")
    problem = ("node is not installed" if path is None else
               None if (FOLDER / "node_modules" / "lbrnts").is_dir() else
               "lbrnts is not installed: npm ci --prefix tests/lightburn")
    if problem:
        if os.environ.get("CI"):
            pytest.fail(f"{problem}; .ci/run installs it")
        pytest.skip(problem)
    return path


def read(*paths) -> list[dict]:
    """What lbrnts reads in every project (see read.mjs)."""
    out = subprocess.run([node(), str(SCRIPT), *map(str, paths)], capture_output=True,
                         text=True, check=False, cwd=FOLDER)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def picture(path, svg) -> None:
    """lbrnts's own SVG drawing of the project ``path``."""
    out = subprocess.run([node(), str(SCRIPT), "--svg", str(path), str(svg)],
                         capture_output=True, text=True, check=False, cwd=FOLDER)
    assert out.returncode == 0, out.stderr


@dataclass(frozen=True)
class Path2:
    """A path as a reader found it: its layer's name, closed or not, its points (mm, y up;
    a closed one without its first point repeated)."""

    layer: str
    closed: bool
    xy: np.ndarray

    @property
    def length(self) -> float:
        ring = np.vstack([self.xy, self.xy[:1]]) if self.closed else self.xy
        return float(np.hypot(*np.diff(ring, axis=0).T).sum())


def lbrn_paths(doc: dict) -> list[Path2]:
    """The paths of a project as lbrnts read it, each named by its CutSetting's name."""
    names = {c["index"]: c["name"] for c in doc["cutSettings"]}
    return [Path2(names[p["cutIndex"]], p["closed"], np.array(p["verts"], dtype=float))
            for p in doc["paths"]]


def dxf_paths(path, layers) -> list[Path2]:
    """The LWPOLYLINEs of the DXF on ``layers``, as ezdxf reads them; one whose last point is
    its first is closed (a trail that returns to its start), written without the repeat."""
    out = []
    for e in ezdxf.readfile(path).modelspace().query("LWPOLYLINE"):
        if e.dxf.layer not in layers:
            continue
        xy = np.array([p[:2] for p in e.get_points("xy")], dtype=float)
        closed = bool(e.closed)
        if len(xy) > 2 and np.abs(xy[0] - xy[-1]).max() <= 1e-9:
            xy, closed = xy[:-1], True
        out.append(Path2(e.dxf.layer, closed, xy))
    return out


@dataclass(frozen=True)
class Comparison:
    """Per layer: closed and open paths and cut length (mm), as both readers found them."""

    layers: dict  # name -> (closed, open, length)

    def text(self) -> str:
        return "; ".join(f"{name}: {c} closed + {o} open, {length / 1000:.3f} m"
                         for name, (c, o, length) in self.layers.items())


def compare(lbrn: dict, dxf_file) -> Comparison:
    """Assert that the project ``lbrn`` (read by lbrnts) and the DXF ``dxf_file`` (read by
    ezdxf) hold the same paths: per layer the same number of closed and of open paths, the
    same total length to ``TOLERANCE``, and path by path the same points to ``TOLERANCE``
    (paths in the order each layer lists them)."""
    ours = lbrn_paths(lbrn)
    names = [c["name"] for c in sorted(lbrn["cutSettings"], key=lambda c: c["priority"])]
    theirs = dxf_paths(dxf_file, set(names))
    assert sorted({p.layer for p in theirs}) == sorted(names)
    layers = {}
    for name in names:
        a = [p for p in ours if p.layer == name]
        b = [p for p in theirs if p.layer == name]
        counts = [(sum(p.closed for p in s), sum(not p.closed for p in s)) for s in (a, b)]
        assert counts[0] == counts[1], (name, counts)
        lengths = [sum(p.length for p in s) for s in (a, b)]
        assert abs(lengths[0] - lengths[1]) <= TOLERANCE, (name, lengths)
        for p, q in zip(a, b):
            assert p.closed == q.closed and p.xy.shape == q.xy.shape, (name, p.xy, q.xy)
            assert np.abs(p.xy - q.xy).max() <= TOLERANCE, name
        layers[name] = (*counts[0], lengths[0])
    return Comparison(layers)
