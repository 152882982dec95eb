"""Throughput of the pentagon snub engine (prints tables; asserts nothing).

1. Per level: the regular pentagon to level 9 and the 8-4 mesh to level 7: time of the first
   (cold) step, faces per second, the step's peak memory (tracemalloc).
2. The step from level 8 to 9 (1,953,125 pentagons), each case in a fresh process: best,
   median and worst of ``--repeat`` steps (each on a fresh copy of level 8 that carries only
   what the previous step left on it, as in a chain), the first (cold) step, page faults per
   step, peak memory; with glibc's default allocator and with freed memory kept in the
   process (:func:`weavecut.subdivision.hierarchy.keep_freed_memory`). The in-process peers
   are :func:`naive_step`, the snub step as a first numpy version would write it, and the
   direct step the speed work started from (``tests/subdivision/snub_oracle.py``), run alternately on
   the same level 8 (ratio = weave-cut / naive, best to best and median to median).
3. Peers on a triangle grid with the same number of output faces: trimesh's 1-to-4 midpoint
   subdivision, CGAL's Loop (compas_cgal) and libigl's Loop, when installed.

    python benchmarks/bench_snub.py [--repeat 7] [--quick]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np

from weavecut import inputs
from weavecut.mesh import Mesh, Topology
from weavecut.subdivision import snub
from weavecut.subdivision.hierarchy import keep_freed_memory

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the test oracle, below


def naive_step(vertices, offsets, indices):
    """The snub step (left, vertex centres, smoothed) written the first way numpy suggests:
    the parent's edges by sorting, Z points per edge, faces stacked from gathers, child face
    centres by a (F', 5) gather, every vertex moved to the mean of its faces' centres by
    bincounts over the child's corners, outer vertices found by sorting the child's edges.
    Returns (vertices, faces)."""
    n_v, n_h = len(vertices), len(indices)
    sizes = np.diff(offsets)
    face = np.repeat(np.arange(len(sizes)), sizes)
    nxt = np.arange(1, n_h + 1)
    nxt[offsets[1:] - 1] = offsets[:-1]
    a = indices.astype(np.int64)
    b = a[nxt]
    key, he = np.unique(np.minimum(a, b) * n_v + np.maximum(a, b), return_inverse=True)
    u, w = np.divmod(key, n_v)
    d = vertices[w] - vertices[u]
    perp = np.column_stack([-d[:, 1], d[:, 0]]) * np.sqrt(3.0)
    z = np.stack([vertices[u] + (5 * d + perp) / 14, vertices[u] + (9 * d - perp) / 14], 1)
    centres = np.add.reduceat(vertices[a], offsets[:-1]) / sizes[:, None]
    new = np.concatenate([vertices, z.reshape(-1, 2), centres])
    side = (a > b).astype(np.int64)
    x = n_v + 2 * he + side
    y = n_v + 2 * he + 1 - side
    faces = np.stack([n_v + 2 * len(key) + face, x, y, b, x[nxt]], axis=1)
    face_centres = new[faces].mean(axis=1)
    corners = faces.ravel()
    n = len(new)
    count = np.bincount(corners, minlength=n)
    sums = np.stack([np.bincount(corners, weights=np.repeat(face_centres[:, c], 5), minlength=n)
                     for c in (0, 1)], axis=1)
    ends = faces[:, [1, 2, 3, 4, 0]].ravel()
    edge_keys, uses = np.unique(np.minimum(corners, ends) * n + np.maximum(corners, ends),
                                return_counts=True)
    outer = np.zeros(n, dtype=bool)
    outer[np.concatenate(np.divmod(edge_keys[uses == 1], n))] = True
    new[~outer] = sums[~outer] / count[~outer, None]
    return new, faces


def as_left_by_chain(mesh: Mesh) -> Mesh:
    """A copy of ``mesh`` carrying only the arrays the step that made it left on it."""
    t = mesh.topology
    topo = Topology(t.edges, t.half_edge_edge, t.half_edge_side)
    topo.__dict__.update({k: v for k, v in t.__dict__.items()
                          if k not in ("edges", "half_edge_edge", "half_edge_side")})
    out = Mesh.trusted(mesh.vertices, mesh.face_offsets, mesh.face_indices, topo)
    if "face_degree" in mesh.__dict__:
        out.__dict__["face_degree"] = mesh.__dict__["face_degree"]
    return out


def faults() -> int:
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt


def step_case(keep: bool, repeat: int, naive_repeat: int) -> dict:
    """Step 8 -> 9 in this (fresh) process; see the module docstring."""
    kept = keep_freed_memory() if keep else False
    level8 = inputs.get("pentagon")
    for _ in range(8):
        level8 = snub.step(level8).mesh
    times, cpu, flts = [], [], []
    for _ in range(repeat + 1):
        parent = as_left_by_chain(level8)
        f0, c0, t0 = faults(), time.process_time(), time.perf_counter()
        child = snub.step(parent)
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
        flts.append(faults() - f0)
        del child, parent
    tracemalloc.start()
    snub.step(as_left_by_chain(level8))
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    from tests.subdivision import snub_oracle  # the direct step the speed work started from

    peers = {"naive": lambda m: naive_step(m.vertices, m.face_offsets, m.face_indices),
             "direct": snub_oracle.step}
    out = {"kept": kept, "cold": times[0], "warm": times[1:], "cpu": cpu[1:], "faults": flts,
           "peak": peak, "faces": 5 * level8.n_faces}
    for _ in range(naive_repeat):  # alternating, so that both see the same load
        for name, run in peers.items():
            parent = as_left_by_chain(level8)
            c0, t0 = time.process_time(), time.perf_counter()
            run(parent)
            out.setdefault(name, []).append(time.perf_counter() - t0)
            out.setdefault(f"{name}_cpu", []).append(time.process_time() - c0)
            del parent
    return out


def table(name: str, levels: int) -> None:
    mesh = inputs.get(name)
    print(f"\n{name}: level, faces, cold time (s), faces/s, step peak (MiB)")
    for t in range(1, levels + 1):
        t0 = time.perf_counter()
        level = snub.step(mesh).mesh
        dt = time.perf_counter() - t0
        tracemalloc.start()
        snub.step(mesh)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        mesh = level
        print(f"  {t:2d} {mesh.n_faces:>10,} {dt:8.3f} {mesh.n_faces / dt:>12,.0f} "
              f"{peak / 2**20:9.1f}")


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


def peers(n_out: int, repeat: int) -> tuple[dict[str, float], int]:
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


def report(name: str, r: dict) -> float:
    warm, cpu = r["warm"], r["cpu"]
    ours_best, ours_med = min(warm), statistics.median(warm)
    naive_best, naive_med = min(r["naive"]), statistics.median(r["naive"])
    print(f"  {name:20s} wall {ours_best:6.3f} {ours_med:6.3f} {max(warm):6.3f} {r['cold']:6.3f} "
          f"{statistics.median(r['faults'][1:]):>7,.0f} {r['faults'][0]:>7,} "
          f"{r['peak'] / 2**30:6.3f}   {naive_best:6.2f} {ours_best / naive_best:5.2f} "
          f"{ours_med / naive_med:5.2f}")
    print(f"  {'':20s} cpu  {min(cpu):6.3f} {statistics.median(cpu):6.3f} {max(cpu):6.3f} "
          f"{'':6s} {'':7s} {'':7s} {'':6s}   {min(r['naive_cpu']):6.2f} "
          f"{min(cpu) / min(r['naive_cpu']):5.2f} "
          f"{statistics.median(cpu) / statistics.median(r['naive_cpu']):5.2f}")
    return ours_best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--quick", action="store_true", help="only the step 8 -> 9")
    parser.add_argument("--case", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.case:
        print(json.dumps(step_case(**json.loads(args.case))))
        return
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print("\nstep 8 -> 9 of the pentagon, seconds (each case in a fresh process; wall clock, and"
          " the process's CPU time, which waiting for a busy machine does not inflate):")
    print(f"  {'allocator':20s}      {'best':>6s} {'median':>6s} {'worst':>6s} {'cold':>6s} "
          f"{'faults':>7s} {'cold':>7s} {'GiB':>6s}   {'naive':>6s} {'ratio best, median'}")
    best = None
    for name, keep in (("glibc default", False), ("freed memory kept", True)):
        case = json.dumps({"keep": keep, "repeat": args.repeat, "naive_repeat": 3})
        out = subprocess.run([sys.executable, __file__, "--case", case], capture_output=True,
                             text=True, check=True)
        r = json.loads(out.stdout)
        best = report(name, r)
    print(f"  load average after: {os.getloadavg()[0]:.1f}")
    if args.quick:
        return
    table("pentagon", 9)
    table("tiling-8-4", 7)
    found, n = peers(1_953_125, args.repeat)
    ours = 1_953_125 / best
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
