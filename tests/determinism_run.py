"""Run a fixed set of weave-cut commands in this one process and write their outputs into a
folder: ``python tests/determinism_run.py OUT``. The maths kernels (OpenBLAS's core type and
threads, numpy's SIMD targets) are chosen by the environment before numpy loads; the
cross-machine test (``test_determinism.py``) runs this under several and compares the folders
byte for byte. Prints what ran it (numpy's BLAS and its kernel, numpy's SIMD features) as JSON.

The set covers each kind of output: woven balls at two levels and the cube (surfaces in space,
where an SVD and a least-squares fit used to decide), both flat paper models, the puzzle (with
its LightBurn projects), a drawing input (SVG, DXF) and classic schemes.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"  # named alike in every run
COMMANDS = (
    ("ball-1.svg", "strands", "dodecahedron", "--levels", "1", "--project", "sphere",
     "--size", "12cm"),
    ("ball-2.pdf", "strands", "dodecahedron", "--levels", "2", "--project", "sphere"),
    ("cube.svg", "strands", "cube", "--levels", "2", "--project", "sphere"),
    ("woven-ball.obj", "weave", "dodecahedron", "--levels", "2", "--project", "sphere"),
    ("square-grid.pdf", "strands", "square-grid", "--size", "27cm"),
    ("pentagon-flower.svg", "strands", "pentagon-flower", "--size", "23cm"),
    ("puzzle", "puzzle", "--levels", "3", "--size", "30cm", "--numbers", "--formats",
     "svg,dxf,lbrn2"),
    ("heart.svg", "weave", str(EXAMPLES / "heart.svg"), "--cell", "10mm", "--levels", "2",
     "--outline-level", "1"),
    ("plate.dxf", "subdivide", str(EXAMPLES / "plate.dxf"), "--levels", "2"),
    ("loop.svg", "subdivide", "triangle-grid", "--scheme", "loop", "--levels", "3"),
    ("catmull-clark.dxf", "subdivide", "square-grid", "--scheme", "catmull-clark",
     "--levels", "3"),
)


def kernels() -> dict:
    """What does the arithmetic in this process: numpy's BLAS libraries and kernels, and the
    SIMD features numpy dispatches to."""
    import numpy as np
    import threadpoolctl
    from numpy._core import _multiarray_umath as umath

    return {"numpy": np.__version__,
            "blas": [{k: info.get(k) for k in ("internal_api", "version", "architecture",
                                                "num_threads")}
                     for info in threadpoolctl.threadpool_info()],
            "simd": sorted(f for f in umath.__cpu_dispatch__ if umath.__cpu_features__.get(f))}


def run(out: Path) -> None:
    from weavecut.cli.app import cli

    out.mkdir(parents=True, exist_ok=True)
    os.chdir(out)  # outputs named alike in every run: files record the command that made them
    for name, *args in COMMANDS:
        argv = ["-q", *args, "-o", name]
        sys.argv = ["weave-cut", *argv]  # the command line the files record
        cli.main(args=argv, prog_name="weave-cut", standalone_mode=False)


if __name__ == "__main__":
    run(Path(sys.argv[1]).resolve())
    print(json.dumps(kernels()))
