"""Throughput of the snub weave: tiles, strands, crossings and lineage per level of the regular
pentagon (level 8: 390,625 pentagons; target <= 1 s), and the growth against the face count.
As a peer in the same process: the loop-based zig-zag walk of the tests on the same levels.

    python benchmarks/bench_weave.py [--repeat 3]
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

from weavecut import inputs
from weavecut.subdivision import subdivide
from weavecut.weave.snub_weave import lineage, snub_weave
from zigzag import zigzag_strands  # the loop-based peer, beside this file


def best_of(fn, repeat: int):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--levels", type=int, default=8)
    args = parser.parse_args()
    hierarchy = subdivide(inputs.get("pentagon"), args.levels)
    print("level, pentagons, weave (s), lineage (s), pentagons/s, strands, zig-zag peer (s)")
    previous = None
    for t in range(1, args.levels + 1):
        mesh = hierarchy[t].mesh
        w_time, weave = best_of(lambda: snub_weave(mesh), args.repeat)
        l_time = 0.0
        if previous is not None:
            l_time, parents = best_of(
                lambda: lineage(previous, weave, hierarchy[t].parent_face), args.repeat)
            weave = replace(weave, parent_strand=parents)
        peer = ""
        if t <= 6:
            p_time, _ = best_of(lambda: zigzag_strands(hierarchy[t - 1].mesh), 1)
            peer = f"{p_time:8.3f} ({p_time / w_time:,.0f}x slower)"
        total = w_time + l_time
        print(f"{t:3d} {mesh.n_faces:>10,} {w_time:8.3f} {l_time:8.3f} "
              f"{mesh.n_faces / total:>12,.0f} {weave.n_strands:>8,} {peer}")
        previous = weave


if __name__ == "__main__":
    main()
