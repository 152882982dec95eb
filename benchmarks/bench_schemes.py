"""Throughput of weave-cut's classic schemes against peer libraries, in one process.

Run: ``.venv/bin/python benchmarks/bench_schemes.py`` (peers from ``pip install -e .[bench]``;
missing peers are skipped). Inputs: a flat triangle grid of 125k triangles (Loop, butterfly:
two steps to 2M faces; sqrt(3): two steps to 1.125M faces) and a 125k-quad grid
(Catmull-Clark: two steps to 2M faces). Every library starts from plain (V, 3) / (F, k)
arrays, so weave-cut's time includes building its Mesh and topology. Best and median of
``REPEATS`` runs; the ratio "weave-cut x" compares best with best and median with median.
Prints a table and the load average; asserts nothing.
"""

from __future__ import annotations

import os
import statistics
import time

import numpy as np

from weavecut.mesh import Mesh
from weavecut.subdivision import butterfly, catmull_clark, loop, sqrt3
from weavecut.subdivision.hierarchy import keep_freed_memory

REPEATS = 5


def grid(n: int, m: int, quads: bool):
    x, y = np.meshgrid(np.arange(n + 1, dtype=float), np.arange(m + 1, dtype=float))
    v = np.column_stack([x.ravel(), y.ravel()])
    idx = np.arange((n + 1) * (m + 1), dtype=np.int32).reshape(m + 1, n + 1)
    a, b, c, d = (idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, 1:].ravel(),
                  idx[1:, :-1].ravel())
    if quads:
        return v, np.column_stack([a, b, c, d])
    return v, np.stack([np.column_stack([a, b, c]), np.column_stack([a, c, d])], 1).reshape(-1, 3)


def ours(step, levels):
    def run(v, f):
        k = f.shape[1]
        mesh = Mesh(v, np.arange(0, f.size + 1, k), f.reshape(-1))
        for _ in range(levels):
            mesh = step(mesh).mesh
        return mesh.n_faces
    return run


def xyz(v):
    return np.column_stack([v, np.zeros(len(v))])


def peers():
    out = {}
    try:
        from compas_cgal import subdivision as cg
        out["compas_cgal"] = {
            "loop": lambda v, f: len(cg.mesh_subdivide_loop((xyz(v), f), k=2)[1]),
            "sqrt3": lambda v, f: len(cg.mesh_subdivide_sqrt3((xyz(v), f), k=2)[1]),
            "catmull-clark": lambda v, f: len(cg.mesh_subdivide_catmull_clark((xyz(v), f), k=2)[1]),
        }
    except ImportError:
        pass
    try:
        import igl
        out["libigl"] = {"loop": lambda v, f: len(igl.loop(xyz(v), f.astype(np.int64), 2)[1])}
    except ImportError:
        pass
    try:
        import vtk

        from vtk_peer import subdivided

        def vtk_run(cls):
            return lambda v, f: subdivided(cls, xyz(v), f, 2).GetNumberOfCells()
        out["vtk"] = {"loop": vtk_run(vtk.vtkLoopSubdivisionFilter),
                      "butterfly": vtk_run(vtk.vtkButterflySubdivisionFilter)}
    except ImportError:
        pass
    try:
        import pymeshlab

        def ml_run(filt, **kw):
            def run(v, f):
                ms = pymeshlab.MeshSet()
                ms.add_mesh(pymeshlab.Mesh(xyz(v), f.astype(np.int32)))
                getattr(ms, filt)(iterations=2, threshold=pymeshlab.PercentageValue(0), **kw)
                return ms.current_mesh().face_number()
            return run
        out["pymeshlab"] = {"loop": ml_run("meshing_surface_subdivision_loop"),
                            "butterfly": ml_run("meshing_surface_subdivision_butterfly")}
    except ImportError:
        pass
    try:
        import trimesh
        out["trimesh"] = {"loop": lambda v, f: len(
            trimesh.remesh.subdivide_loop(xyz(v), f.astype(np.int64), iterations=2)[1])}
    except ImportError:
        pass
    return out


def timed(fn, v, f):
    """(best, median) seconds of ``REPEATS`` runs, and the face count."""
    times, n = [], None
    for _ in range(REPEATS):
        t = time.perf_counter()
        n = fn(v, f)
        times.append(time.perf_counter() - t)
    return min(times), statistics.median(times), n


def measure() -> tuple[bool, list[dict]]:
    """Whether freed memory is kept, and one row per scheme and library: best and median
    seconds and faces (``error`` instead when a peer failed)."""
    kept = keep_freed_memory()  # as the command line runs; the setting holds for the peers too
    tri = grid(250, 250, quads=False)      # 125,000 triangles
    quad = grid(500, 250, quads=True)      # 125,000 quads
    cases = [("loop", tri, ours(loop.step, 2)), ("butterfly", tri, ours(butterfly.step, 2)),
             ("sqrt3", tri, ours(sqrt3.step, 2)),
             ("catmull-clark", quad, ours(catmull_clark.step, 2))]
    rows = []
    for name, (v, f), fn in cases:
        for lib, run in [("weave-cut", fn), *((lib, schemes[name])
                                               for lib, schemes in peers().items()
                                               if name in schemes)]:
            try:
                best, median, n = timed(run, v, f)
            except Exception as exc:  # a peer's API drift must not stop the table
                rows.append({"scheme": name, "library": lib, "error": str(exc)})
                continue
            rows.append({"scheme": name, "library": lib, "faces": n, "best": best,
                         "median": median})
    return kept, rows


def main() -> int:
    kept, rows = measure()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; freed memory "
          f"kept in the process: {kept}")
    print(f"{'scheme':14s} {'library':12s} {'faces':>9s} {'best s':>8s} {'median s':>8s} "
          f"{'Mfaces/s':>9s} {'weave-cut x (best, median)':>27s}")
    for r in rows:
        name = r["scheme"] if r["library"] == "weave-cut" else ""
        if "error" in r:
            print(f"{name:14s} {r['library']:12s} failed: {r['error']}")
            continue
        if r["library"] == "weave-cut":
            mine = r
        ratio = ("" if r is mine else
                 f"{r['best'] / mine['best']:13.2f}x {r['median'] / mine['median']:6.2f}x")
        print(f"{name:14s} {r['library']:12s} {r['faces']:9d} {r['best']:8.3f} "
              f"{r['median']:8.3f} {r['faces'] / r['best'] / 1e6:9.2f} {ratio}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
