"""Write the peer fixtures once: classic schemes of small meshes by libigl, vtk and pymeshlab.

Run with an interpreter that has the peers (not weave-cut's venv), from this folder:
    python -m venv /tmp/peers && /tmp/peers/bin/pip install numpy vtk libigl
    /tmp/peers/bin/python make_fixtures.py libigl vtk
    python -m venv /tmp/pml && /tmp/pml/bin/pip install numpy pymeshlab==2025.7
    /tmp/pml/bin/python make_fixtures.py pymeshlab
(the peers named on the command line are written, the others left as they are). It reads the meshes from ``inputs.json`` and writes one ``<peer>-<scheme>.json`` per run, with
every coordinate as Python writes a float (repr: the double itself, no rounding).
"""

from __future__ import annotations

import json
import sys
from importlib import metadata
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent


def xyz(v):
    return np.column_stack([v, np.zeros(len(v))]).astype(np.float64)


def igl_loop(v, f):
    import igl
    nv, nf = igl.loop(xyz(v), np.asarray(f, dtype=np.int64), 1)
    return nv, nf


def vtk_run(cls):
    def run(v, f):
        from vtk.util.numpy_support import vtk_to_numpy
        sys.path.insert(0, str(HERE.parents[2] / "benchmarks"))
        from vtk_peer import subdivided  # the benchmark runs vtk the same way
        out = subdivided(cls, xyz(v), f, 1)
        nv = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)
        conn = vtk_to_numpy(out.GetPolys().GetConnectivityArray()).reshape(-1, 3)
        return nv, conn, str(out.GetPoints().GetData().GetDataTypeAsString())
    return run


def vtk_filter(name):
    def run(v, f):
        import vtk
        return vtk_run(getattr(vtk, name))(v, f)
    return run


def meshlab_run(filter_name, split_all=True, **params):
    """One step of a MeshLab filter; ``threshold=0`` so that every edge is split (MeshLab's
    default leaves edges shorter than 1 % of the bounding box); polygonal faces are read back
    as MeshLab keeps them (Catmull-Clark's quads)."""
    def run(v, f):
        import pymeshlab
        ms = pymeshlab.MeshSet(verbose=False)
        ms.add_mesh(pymeshlab.Mesh(xyz(v), np.asarray(f, dtype=np.int32)))
        if split_all:
            params["threshold"] = pymeshlab.PercentageValue(0)
        getattr(ms, filter_name)(iterations=1, **params)
        out = ms.current_mesh()
        return out.vertex_matrix(), [p.tolist() for p in out.polygonal_face_list()]
    return run


RUNS = {("libigl", "loop"): igl_loop,
        ("vtk", "loop"): vtk_filter("vtkLoopSubdivisionFilter"),
        ("vtk", "butterfly"): vtk_filter("vtkButterflySubdivisionFilter"),
        ("pymeshlab", "loop"): meshlab_run("meshing_surface_subdivision_loop", loopweight="Loop"),
        ("pymeshlab", "butterfly"): meshlab_run("meshing_surface_subdivision_butterfly"),
        ("pymeshlab", "catmull-clark"): meshlab_run("meshing_surface_subdivision_catmull_clark",
                                                    split_all=False)}


def main(peers: list[str]) -> None:
    meshes = json.loads((HERE / "inputs.json").read_text())
    versions = {p: metadata.version(p) for p in peers}
    versions |= {"numpy": metadata.version("numpy"), "python": sys.version.split()[0]}
    for (peer, scheme), run in RUNS.items():
        if peer not in peers:
            continue
        out = {"peer": peer, "scheme": scheme, "versions": versions, "meshes": []}
        for mesh in meshes:
            got = run(np.array(mesh["vertices"]), mesh["faces"])
            nv, nf = got[0], got[1]
            out["meshes"].append({"name": mesh["name"], "vertices": nv[:, :2].tolist(),
                                  "faces": np.asarray(nf).tolist(),
                                  "precision": got[2] if len(got) > 2 else "double"})
        (HERE / f"{peer}-{scheme}.json").write_text(json.dumps(out, indent=None) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:] or ["libigl", "vtk"])
