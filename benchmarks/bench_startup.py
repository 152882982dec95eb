"""Start-up time: ``weave-cut --help`` and ``weave-cut COMMAND --help`` for every command,
against ``python -c "import numpy"`` on the same machine (the floor of anything weave-cut
does). Each is the best of ``--repeat`` fresh processes; a ratio above ``--limit`` fails.

The target is 0.3 s where numpy takes 0.12 s, a ratio of 2.5; the limit leaves some room for
a busy machine. Run as a regression check: exit status 1 names what got slower.

    python benchmarks/bench_startup.py [--repeat 7] [--limit 3.0]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

COMMANDS = ("inputs", "subdivide", "stats", "weave", "puzzle", "strands", "fractal", "levels",
            "convexity", "figure", "build")


def weave_cut() -> list[str]:
    """The console script beside this Python, or ``python -m weavecut``."""
    script = Path(sys.executable).with_name("weave-cut")
    return [str(script)] if script.exists() else [sys.executable, "-m", "weavecut"]


def best(argv: list[str], repeat: int) -> float:
    """Wall time (s) of the fastest of ``repeat`` runs of ``argv``."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--limit", type=float, default=3.0,
                        help="largest allowed ratio to 'import numpy'")
    args = parser.parse_args()
    numpy = best([sys.executable, "-c", "import numpy"], args.repeat)
    print(f"python -c 'import numpy': {numpy:.3f} s")
    print(f"{'command':28} {'s':>7} {'ratio':>6}")
    slow = []
    for words in [["--help"], *([c, "--help"] for c in COMMANDS)]:
        seconds = best(weave_cut() + words, args.repeat)
        ratio = seconds / numpy
        name = "weave-cut " + " ".join(words)
        print(f"{name:28} {seconds:7.3f} {ratio:6.2f}")
        if ratio > args.limit:
            slow.append(name)
    if slow:
        print(f"slower than {args.limit:g} x import numpy: {', '.join(slow)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
