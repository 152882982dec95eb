"""Write the peer fixtures once: Loop and butterfly of small meshes by libigl and vtk.

Run with an interpreter that has the peers (not weave-cut's venv), from this folder:
    python -m venv /tmp/peers && /tmp/peers/bin/pip install numpy vtk libigl
    /tmp/peers/bin/python make_fixtures.py
It reads the meshes from ``inputs.json`` and writes one ``<peer>-<scheme>.json`` per run, with
every coordinate as Python writes a float (repr: the double itself, no rounding).
"""

from __future__ import annotations

import json
import sys
from importlib import metadata
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parents[2] / "benchmarks"))
from vtk_peer import subdivided  # noqa: E402  (the benchmark runs vtk the same way)


def xyz(v):
    return np.column_stack([v, np.zeros(len(v))]).astype(np.float64)


def igl_loop(v, f):
    import igl
    nv, nf = igl.loop(xyz(v), np.asarray(f, dtype=np.int64), 1)
    return nv, nf


def vtk_run(cls):
    def run(v, f):
        from vtk.util.numpy_support import vtk_to_numpy
        out = subdivided(cls, xyz(v), f, 1)
        nv = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)
        conn = vtk_to_numpy(out.GetPolys().GetConnectivityArray()).reshape(-1, 3)
        return nv, conn, str(out.GetPoints().GetData().GetDataTypeAsString())
    return run


def main() -> None:
    import vtk
    meshes = json.loads((HERE / "inputs.json").read_text())
    runs = {("libigl", "loop"): igl_loop,
            ("vtk", "loop"): vtk_run(vtk.vtkLoopSubdivisionFilter),
            ("vtk", "butterfly"): vtk_run(vtk.vtkButterflySubdivisionFilter)}
    versions = {"libigl": metadata.version("libigl"), "vtk": metadata.version("vtk"),
                "numpy": metadata.version("numpy"), "python": sys.version.split()[0]}
    for (peer, scheme), run in runs.items():
        out = {"peer": peer, "scheme": scheme, "versions": versions, "meshes": []}
        for mesh in meshes:
            got = run(np.array(mesh["vertices"]), mesh["faces"])
            nv, nf = got[0], got[1]
            out["meshes"].append({"name": mesh["name"], "vertices": nv[:, :2].tolist(),
                                  "faces": np.asarray(nf).tolist(),
                                  "precision": got[2] if len(got) > 2 else "double"})
        (HERE / f"{peer}-{scheme}.json").write_text(json.dumps(out, indent=None) + "\n")


if __name__ == "__main__":
    main()
