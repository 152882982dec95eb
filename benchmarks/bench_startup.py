"""Start-up time: ``weave-cut --help`` and ``weave-cut COMMAND --help`` for every command,
against ``python -c "import numpy"`` on the same machine (the floor of anything weave-cut
does). Each is the best of ``--repeat`` fresh processes, wall and CPU time; a CPU-time ratio
above ``--limit`` fails (CPU time, because a busy machine stretches the wall time of short
processes more than that of long ones).

The target is 0.3 s where numpy takes 0.12 s, a ratio of 2.5; the limit leaves some room.
Run as a regression check: exit status 1 names what got slower.

    python benchmarks/bench_startup.py [--repeat 7] [--limit 3.0]
"""

from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import time
from pathlib import Path

COMMANDS = ("inputs", "subdivide", "stats", "weave", "puzzle", "strands", "fractal", "levels",
            "convexity", "figure", "findings", "build")


def weave_cut() -> list[str]:
    """The console script beside this Python, or ``python -m weavecut``."""
    script = Path(sys.executable).with_name("weave-cut")
    return [str(script)] if script.exists() else [sys.executable, "-m", "weavecut"]


def best(argv: list[str], repeat: int) -> tuple[float, float]:
    """The least wall and the least CPU time (s, user + system) of ``repeat`` runs of
    ``argv``; the two apart show what a busy machine adds to the wall time."""
    runs = []
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        runs.append((wall, after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime))
    walls, cpus = zip(*runs)
    return min(walls), min(cpus)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--limit", type=float, default=3.0,
                        help="largest allowed CPU-time ratio to 'import numpy'")
    args = parser.parse_args()
    numpy, numpy_cpu = best([sys.executable, "-c", "import numpy"], args.repeat)
    print(f"python -c 'import numpy': {numpy:.3f} s (cpu {numpy_cpu:.3f} s)")
    print(f"{'command':28} {'s':>7} {'ratio':>6} {'cpu s':>7} {'ratio':>6}")
    slow = []
    for words in [["--help"], *([c, "--help"] for c in COMMANDS)]:
        seconds, cpu = best(weave_cut() + words, args.repeat)
        name = "weave-cut " + " ".join(words)
        print(f"{name:28} {seconds:7.3f} {seconds / numpy:6.2f} {cpu:7.3f} {cpu / numpy_cpu:6.2f}")
        if cpu / numpy_cpu > args.limit:
            slow.append(name)
    if slow:
        print(f"slower than {args.limit:g} x import numpy: {', '.join(slow)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
