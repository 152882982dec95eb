"""The memory guard against measured peaks (prints a table; asserts nothing).

Each case runs ``weave-cut`` in a fresh process and reads its peak resident memory
(ru_maxrss); the estimate is what the guard computes before any refinement
(:func:`weavecut.subdivision.hierarchy.hierarchy_bytes`, :func:`weavecut.analysis.levels.
memory_need`). The guard's constants were fitted to these cases; within 20 % is the aim.

    .venv/bin/python benchmarks/bench_memory.py [--quick]
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ZOOM = "0.05,0.25,0.2042,0.4042"
CASES = {
    "stats, level 9 (hierarchy)": ["stats", "pentagon", "--levels", "9", "--json"],
    "stats, level 10 (hierarchy)": ["stats", "pentagon", "--levels", "10", "--json"],
    "levels, full level 10, 2048 px": ["levels", "pentagon", "--levels", "10", "--size", "2048"],
    "levels, level 12 zoom, 2048 px": ["levels", "pentagon", "--levels", "12", "--size", "2048",
                                       "--window", ZOOM],
}
QUICK = {
    "stats, level 8 (hierarchy)": ["stats", "pentagon", "--levels", "8", "--json"],
    "levels, level 10 zoom, 1024 px": ["levels", "pentagon", "--levels", "10", "--size", "1024",
                                       "--window", ZOOM],
}
RUN = """
import resource, sys
from weavecut.cli import main
try:
    main(sys.argv[1:])
except SystemExit:
    pass
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024, file=sys.stderr)
"""


def estimate(args: list[str]) -> int:
    """The guard's estimate for a ``stats`` or ``levels`` command line on the pentagon."""
    from weavecut import inputs
    from weavecut.analysis import levels as lv
    from weavecut.subdivision import snub
    from weavecut.subdivision.hierarchy import hierarchy_bytes, sizes

    mesh = inputs.get("pentagon")
    n = int(args[args.index("--levels") + 1])
    if args[0] == "stats":
        return hierarchy_bytes(sizes(mesh, n, snub.counts))
    window = (tuple(float(v) for v in args[args.index("--window") + 1].split(","))
              if "--window" in args else None)
    size = int(args[args.index("--size") + 1])
    grid = lv.Grid.fit(lv.default_window(mesh) if window is None else window, size)
    return lv.memory_need(mesh, n, grid, windowed=window is not None)[0][-1]


def main() -> None:
    cases = QUICK if "--quick" in sys.argv else CASES
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print(f"{'case':34} {'estimate':>10} {'peak RSS':>10} {'est/peak':>9} {'seconds':>8}")
    folder = Path(tempfile.mkdtemp(prefix="bench_memory."))
    for name, args in cases.items():
        if args[0] == "levels":
            args = [*args, "-o", str(folder / "levels.png")]
        start = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", RUN, *args], capture_output=True, text=True,
                             check=True)
        seconds = time.perf_counter() - start
        peak = int(out.stderr.strip().splitlines()[-1])
        need = estimate(args)
        print(f"{name:34} {need / 2**30:8.2f} G {peak / 2**30:8.2f} G {need / peak:9.2f} "
              f"{seconds:8.1f}")
        sys.stdout.flush()
    print(json.dumps({"load_after": os.getloadavg()[0]}))


if __name__ == "__main__":
    main()
