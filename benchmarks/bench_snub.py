"""Throughput of the pentagon snub engine: the regular pentagon to level 9 and the 8-4 mesh to
level 7, per level: time, faces per second, peak memory of the step.

The step from level 8 to 9 is also repeated (best of N) and compared with a peer run in the
same process on the same number of output faces: trimesh's vectorised 1-to-4 midpoint
subdivision (a numpy peer), and CGAL's Loop (compas_cgal) or libigl's Loop when installed.

    python benchmarks/bench_snub.py [--repeat 3]
"""

from __future__ import annotations

import argparse
import time
import tracemalloc

import numpy as np

from weavecut import inputs
from weavecut.subdivision import snub


def timed_step(mesh):
    """(child mesh, seconds of the first, cold run, peak bytes of a second, traced run)."""
    t0 = time.perf_counter()
    level = snub.step(mesh)
    dt = time.perf_counter() - t0
    tracemalloc.start()
    snub.step(mesh)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return level.mesh, dt, peak


def table(name: str, levels: int) -> object:
    mesh = inputs.get(name)
    print(f"\n{name}: level, faces, cold time (s), faces/s, step peak (MiB)")
    for t in range(1, levels + 1):
        mesh, dt, peak = timed_step(mesh)
        print(f"  {t:2d} {mesh.n_faces:>10,} {dt:8.3f} {mesh.n_faces / dt:>12,.0f} "
              f"{peak / 2**20:9.1f}")
    return mesh


def best_of(fn, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def triangle_grid(n_faces: int):
    side = int(np.sqrt(n_faces / 2))
    x, y = np.meshgrid(np.arange(side + 1.0), np.arange(side + 1.0))
    v = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    i, j = np.meshgrid(np.arange(side), np.arange(side))
    v0 = (j * (side + 1) + i).ravel()
    f = np.concatenate([np.column_stack([v0, v0 + 1, v0 + side + 2]),
                        np.column_stack([v0, v0 + side + 2, v0 + side + 1])])
    return v, f


def peers(n_out: int, repeat: int) -> dict[str, float]:
    """Seconds each available peer takes to make about ``n_out`` faces in one 1-to-4 step."""
    v, f = triangle_grid(n_out // 4)
    out = {}
    try:
        import trimesh.remesh
        out["trimesh subdivide (numpy)"] = best_of(lambda: trimesh.remesh.subdivide(v, f),
                                                   repeat)
    except ImportError:
        pass
    try:
        from compas_cgal.subdivision import mesh_subdivide_loop
        out["CGAL Loop (compas_cgal)"] = best_of(
            lambda: mesh_subdivide_loop((v, f.astype(np.int32)), 1), repeat)
    except ImportError:
        pass
    try:
        import igl
        out["libigl Loop"] = best_of(lambda: igl.loop(v, f.astype(np.int64), 1), repeat)
    except ImportError:
        pass
    return out, len(f) * 4


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    table("pentagon", 8)
    level8 = inputs.get("pentagon")
    for _ in range(8):
        level8 = snub.step(level8).mesh
    mesh9, dt, peak = timed_step(level8)
    print(f"  {9:2d} {mesh9.n_faces:>10,} {dt:8.3f} {mesh9.n_faces / dt:>12,.0f} "
          f"{peak / 2**20:9.1f}")
    best = best_of(lambda: snub.step(level8), args.repeat)
    ours = mesh9.n_faces / best
    print(f"\nstep 8 -> 9, best of {args.repeat}: {best:.3f} s, {ours:,.0f} faces/s "
          f"(target <= 0.5 s, <= 1 GiB peak; measured peak {peak / 2**30:.2f} GiB)")
    del mesh9
    table("tiling-8-4", 7)
    found, n = peers(1_953_125, args.repeat)
    if found:
        print(f"\npeers, one 1-to-4 step to {n:,} faces (same process):")
        for name, seconds in found.items():
            rate = n / seconds
            print(f"  {name:28s} {seconds:7.3f} s {rate:>12,.0f} faces/s   "
                  f"weave-cut snub / peer = {ours / rate:.2f}")
    else:
        print("\nno peer installed (pip install '.[bench]')")


if __name__ == "__main__":
    main()
