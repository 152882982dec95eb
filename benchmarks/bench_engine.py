"""The engine at scale, before and after its speed work, as one table (prints; asserts
nothing).

    .venv/bin/python benchmarks/bench_engine.py          (or: make bench-engine)

Every heavy case runs in a fresh process, so that its peak memory and first (cold) step are
its own; the peers of a ratio run in the same process as weave-cut, alternately:

- snub step 8 -> 9 of the pentagon (1,953,125 pentagons), with glibc's default allocator
  (cold: fresh pages every step) and with freed memory kept (warm, as the command line
  runs): wall best / median / worst, CPU best / median, the first step, page faults, peak
  (tracemalloc), ratios to the naive numpy step and to the direct step the speed work started from
  (``bench_snub.py``);
- ``weave-cut stats pentagon --levels 9 --json``: wall and CPU, peak RSS;
- OBJ read and validation of a million faces (``bench_mesh_io.py``'s two files);
- the memory guard's estimate against the measured peak RSS: full level 10 and the
  level-12 windowed zoom (``bench_memory.py``);
- the classic schemes against their fastest peer (``bench_schemes.py``, peers from
  ``pip install -e '.[bench]'``);
- the DeepZoom tile pyramid of level 10 at 2048 px in 256-px tiles on 2 processes, tiles/s.

"before" is the measurement on the quiet machine before the speed work (2026-11). It took 42 minutes under a load
of 21-26 on the project's 2-core machine (wall clock inflated 5-10 times over the CPU time);
about 5 minutes are expected when it is quiet. The total is printed.
"""

from __future__ import annotations

import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import bench_memory  # noqa: E402
import bench_mesh_io  # noqa: E402

BEFORE = {
    "snub": "best 0.30-0.34, median 0.36-0.39, worst 0.6-1.0 s; 0.54-0.56 GiB",
    "stats": "5.0-5.5 s, 1.43 GiB",
    "obj": "about 6 s",
    "validate": "about 13 s",
    "schemes": "Loop 1.9-2.0x, butterfly 2.6-2.75x (README: 4.6x), sqrt3 3.0-3.2x, CC 2.8-3.4x",
}
ROWS: list[tuple[str, str, str]] = []


def row(what: str, now: str, before: str = "") -> None:
    ROWS.append((what, before, now))
    print(f"  {what}: {now}", flush=True)


def python(*args: str, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, check=True,
                          cwd=HERE.parent, **kwargs)


def children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def cli(args: list[str]) -> tuple[float, float, int]:
    """Wall and CPU seconds and peak RSS of ``weave-cut ARGS`` in a fresh process."""
    cpu, start = children_cpu(), time.perf_counter()
    out = python("-c", bench_memory.RUN, *args)
    wall, cpu = time.perf_counter() - start, children_cpu() - cpu
    return wall, cpu, int(out.stderr.strip().splitlines()[-1])


def snub(repeat: int) -> None:
    print("snub step 8 -> 9 (seconds; ratio = weave-cut / peer in the same process)")
    for name, keep in (("cold (glibc default)", False), ("warm (freed memory kept)", True)):
        case = json.dumps({"keep": keep, "repeat": repeat, "naive_repeat": 3})
        r = json.loads(python(str(HERE / "bench_snub.py"), "--case", case).stdout)
        wall, cpu = r["warm"], r["cpu"]
        ratios = ", ".join(
            f"{peer} {min(cpu) / min(r[peer + '_cpu']):.2f} / "
            f"{statistics.median(cpu) / statistics.median(r[peer + '_cpu']):.2f}"
            for peer in ("naive", "direct"))
        row(f"snub step, {name}",
            f"wall {min(wall):.3f} / {statistics.median(wall):.3f} / {max(wall):.3f} "
            f"(first step {r['cold']:.3f}); CPU {min(cpu):.3f} / {statistics.median(cpu):.3f}; "
            f"{statistics.median(r['faults'][1:]):,.0f} page faults; peak "
            f"{r['peak'] / 2**30:.3f} GiB; CPU ratio best / median: {ratios}",
            BEFORE["snub"] if not keep else "")


def stats(repeat: int) -> None:
    runs = [cli(["stats", "pentagon", "--levels", "9", "--json"]) for _ in range(repeat)]
    wall, cpu, peak = zip(*runs)
    row("stats pentagon --levels 9 --json",
        f"wall {min(wall):.2f} / {statistics.median(wall):.2f} s, CPU {min(cpu):.2f} s, "
        f"peak RSS {max(peak) / 2**30:.2f} GiB", BEFORE["stats"])


def mesh_io(repeat: int) -> None:
    from weavecut import inputs
    from weavecut.mesh import Mesh
    from weavecut.mesh_io import read_mesh, write_mesh
    from weavecut.subdivision import subdivide
    from weavecut.validation import validate

    meshes = {"1000 x 1000 grid": inputs.get("square-grid:1000x1000"),
              "snub pentagons, 17-digit coordinates": subdivide(
                  inputs.get("square-grid:100x100"), 3)[-1].mesh}
    with tempfile.TemporaryDirectory() as folder:
        for name, mesh in meshes.items():
            path = Path(folder) / "m.obj"
            write_mesh(mesh, path)
            wall, cpu = bench_mesh_io.best_of(lambda: read_mesh(path), repeat)
            row(f"OBJ read, {mesh.n_faces:,} faces, {name} "
                f"({path.stat().st_size / 2**20:.0f} MiB)",
                f"wall {wall:.2f} s, CPU {cpu:.2f} s", BEFORE["obj"])
            wall, cpu = bench_mesh_io.best_of(
                lambda: validate(Mesh(mesh.vertices, mesh.face_offsets, mesh.face_indices)),
                repeat)
            row(f"validation, {name}", f"wall {wall:.2f} s, CPU {cpu:.2f} s", BEFORE["validate"])


def memory_guard() -> None:
    with tempfile.TemporaryDirectory() as folder:
        for name in ("levels, full level 10, 2048 px", "levels, level 12 zoom, 2048 px"):
            args = [*bench_memory.CASES[name], "-o", str(Path(folder) / "levels.png")]
            wall, cpu, peak = cli(args)
            need = bench_memory.estimate(args)
            row(f"memory guard, {name}", f"estimate {need / 2**30:.2f} GiB, peak RSS "
                f"{peak / 2**30:.2f} GiB: {need / peak:.2f} of it ({wall:.0f} s)")


def schemes() -> None:
    out = python("-c", "import json, sys; sys.path.insert(0, 'benchmarks'); import bench_schemes;"
                 " print(json.dumps(bench_schemes.measure()[1]))")
    rows = [r for r in json.loads(out.stdout) if "error" not in r]
    for name in dict.fromkeys(r["scheme"] for r in rows):
        mine = next(r for r in rows if r["scheme"] == name and r["library"] == "weave-cut")
        peers = [r for r in rows if r["scheme"] == name and r is not mine]
        if not peers:
            row(f"{name} against peers", "no peer installed")
            continue
        fastest = min(peers, key=lambda r: r["best"])
        row(f"{name} ({mine['faces']:,} faces) against the fastest peer",
            f"{fastest['library']} {fastest['best']:.3f} s, weave-cut {mine['best']:.3f} s: "
            f"{fastest['best'] / mine['best']:.2f}x faster (median "
            f"{fastest['median'] / mine['median']:.2f}x)",
            BEFORE["schemes"] if name == "loop" else "")


def pyramid() -> None:
    code = ("import json, sys; sys.path.insert(0, 'benchmarks'); import bench_levels as b;"
            " print(json.dumps(b.pyramid_rate(**b.PYRAMID, jobs=2)))")
    r = json.loads(python("-c", code).stdout)
    row("DeepZoom pyramid, level 10, 2048 px, 256-px tiles, 2 processes",
        f"{r['tiles']} tiles in {r['seconds']:.1f} s = {r['tiles'] / r['seconds']:.1f} tiles/s; "
        f"{r['full_resolution_tiles']} full-resolution tiles at "
        f"{r['full_resolution_tiles'] / r['render_seconds']:.2f} tiles/s")


def main() -> None:
    start = time.perf_counter()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores", flush=True)
    snub(repeat=7)
    stats(repeat=3)
    mesh_io(repeat=3)
    memory_guard()
    schemes()
    pyramid()
    print(f"\nthe engine at scale, load average {os.getloadavg()[0]:.1f} at the end, "
          f"{(time.perf_counter() - start) / 60:.1f} minutes:\n")
    print("| what | before the speed work | now |\n| --- | --- | --- |")
    for what, before, now in ROWS:
        print(f"| {what} | {before} | {now} |")


if __name__ == "__main__":
    main()
