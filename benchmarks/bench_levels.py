"""Level-image throughput (prints a table; not a test).

    .venv/bin/python benchmarks/bench_levels.py [--quick] [--pyramid]

Cases: the pentagon at level 9 over 2048 x 2048 pixels (target <= 10 s) and a level-12 zoom
window of about 1/100 of the pentagon's area (target <= 30 s and <= 4 GiB peak). Each case runs
in a fresh subprocess so that its peak resident memory (ru_maxrss) is its own.

Then a DeepZoom pyramid (``weave-cut levels --tiles``): its full-resolution tiles rendered by
one process and by two, in tiles per second (all tiles, and the full-resolution ones that do
the refinement).
"""

from __future__ import annotations

import json
import subprocess
import sys
import time

CASES = {
    "pentagon level 9, 2048 px": dict(levels=9, size=2048, window=None),
    "pentagon level 12 zoom, 2048 px": dict(levels=12, size=2048,
                                            window=(0.05, 0.25, 0.2042, 0.4042)),
}
PYRAMID = dict(levels=10, size=2048, tile_size=256)
QUICK_PYRAMID = dict(levels=9, size=1024, tile_size=256)
QUICK = {
    "pentagon level 7, 512 px": dict(levels=7, size=512, window=None),
    "pentagon level 9 zoom, 512 px": dict(levels=9, size=512, window=(0.05, 0.25, 0.2042, 0.4042)),
}


def run_case(levels: int, size: int, window) -> dict:
    import resource

    from weavecut import inputs
    from weavecut.analysis import levels as lv
    from weavecut.mesh_geometry import signed_areas

    mesh = inputs.get("pentagon")
    start = time.perf_counter()
    image, grid = lv.level_image(mesh, levels, size, window)
    png = lv.png_bytes(lv.colour(image))
    seconds = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    area = None
    if window is not None:
        x0, y0, x1, y1 = window
        area = (x1 - x0) * (y1 - y0) / float(signed_areas(mesh).sum())
    return {"seconds": seconds, "peak_bytes": peak, "pixels": int(image.size),
            "set": int((image != lv.UNSET).sum()), "deepest": int(image[image != lv.UNSET].max()),
            "png_bytes": len(png), "area_fraction": area}


def pyramid_rate(levels: int, size: int, tile_size: int, jobs: int) -> dict:
    """The counts and seconds of one DeepZoom pyramid of the pentagon written by ``jobs``
    processes, with the CPU seconds of this process and its workers (``cpu``)."""
    import tempfile

    from weavecut import inputs
    from weavecut.analysis import deepzoom
    from weavecut.analysis import levels as lv

    mesh = inputs.get("pentagon")
    grid = lv.Grid.fit(lv.default_window(mesh), size)
    with tempfile.TemporaryDirectory() as folder:
        cpu = _cpu()
        r = deepzoom.write_pyramid(mesh, levels, grid, folder, tile_size=tile_size, jobs=jobs)
        return {**r, "cpu": _cpu() - cpu}


def pyramid(levels: int, size: int, tile_size: int) -> None:
    """Tiles per second of the DeepZoom pyramid with one and with two processes."""
    import os

    for jobs in (1, 2):
        r = pyramid_rate(levels, size, tile_size, jobs)
        if jobs == 1:
            print(f"\nDeepZoom pyramid, pentagon level {levels}, {r['width']} x {r['height']} "
                  f"px, {tile_size}-px tiles (load {os.getloadavg()[0]:.1f} on "
                  f"{os.cpu_count()} cores):")
        print(f"  {jobs} process(es): {r['tiles']:,} tiles in {r['seconds']:.1f} s = "
              f"{r['tiles'] / r['seconds']:.1f} tiles/s; {r['full_resolution_tiles']:,} "
              f"full-resolution tiles in {r['render_seconds']:.1f} s = "
              f"{r['full_resolution_tiles'] / r['render_seconds']:.2f} tiles/s; CPU "
              f"{r['cpu']:.1f} s = {r['cpu'] / r['full_resolution_tiles']:.2f} s per "
              f"full-resolution tile")


def _cpu() -> float:
    """CPU seconds of this process and its finished children (the pool's workers)."""
    import resource

    return sum(resource.getrusage(who).ru_utime + resource.getrusage(who).ru_stime
               for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))


def main() -> None:
    if len(sys.argv) > 1 and sys.argv[1] == "--case":
        print(json.dumps(run_case(**json.loads(sys.argv[2]))))
        return
    if "--pyramid" in sys.argv:
        pyramid(**(QUICK_PYRAMID if "--quick" in sys.argv else PYRAMID))
        return
    cases = QUICK if "--quick" in sys.argv else CASES
    print(f"{'case':36} {'seconds':>8} {'peak RSS':>10} {'pixels set':>12} {'deepest':>8} "
          f"{'area':>7}")
    for name, case in cases.items():
        out = subprocess.run([sys.executable, __file__, "--case", json.dumps(case)],
                             capture_output=True, text=True, check=True)
        r = json.loads(out.stdout)
        area = f"{r['area_fraction']:.4f}" if r["area_fraction"] else "all"
        print(f"{name:36} {r['seconds']:8.2f} {r['peak_bytes'] / 2**30:8.2f} GiB "
              f"{r['set']:12,} {r['deepest']:8} {area:>7}")
    pyramid(**(QUICK_PYRAMID if "--quick" in sys.argv else PYRAMID))


if __name__ == "__main__":
    main()
