"""Time the default puzzle (level 4 pentagon, 50 cm frame, poplar-3mm): levels, geometry, colours,
numbers, both cut modes (frame split to the sheet), guides and colour keys, files, stage by
stage, in CPU seconds. Target for the whole set: <= 3 s. Prints; asserts nothing about time.

    python benchmarks/bench_puzzle.py [--levels 4] [--repeat 3]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from weavecut import export, inputs
from weavecut.layout.lasersetup import laser
from weavecut.puzzle import files as pf
from weavecut.puzzle import workshop
from weavecut.puzzle.colouring import colour_puzzle
from weavecut.puzzle.frame import split_frame
from weavecut.puzzle.guides import colour_key, guide, printed
from weavecut.puzzle.pieces import build_puzzle
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette


def run(levels: int, folder: Path) -> dict[str, float]:
    times: dict[str, float] = {}

    def stage(name, fn):  # CPU time of this process: on a shared machine wall time says little
        t0 = time.process_time()
        out = fn()
        times[name] = time.process_time() - t0
        return out

    mat = workshop.material("poplar-3mm")
    hierarchy = stage("levels", lambda: subdivide(inputs.get("pentagon"), levels))
    puzzle = stage("geometry", lambda: build_puzzle(hierarchy, 500.0))
    colouring = stage("colours", lambda: colour_puzzle(puzzle, palette("puzzle")))
    numbers = stage("numbers", lambda: pf.piece_numbers(puzzle))
    las = laser()
    shared = stage("shared cut", lambda: pf.shared_cut(puzzle, las, numbers))
    parts = stage("frame split", lambda: split_frame(puzzle.frame, puzzle.outer, (600, 400),
                                                     5.0, mat["kerf"]))
    separate = stage("separate cut", lambda: pf.separate_cut(
        puzzle, las, mat["kerf"], (600, 400), numbers=numbers, frame_parts=parts))
    guides = stage("guides", lambda: [
        (guide(puzzle, colouring, s, numbers), colour_key(puzzle, colouring, s))
        for s in ("front", "back")])

    def write_all():
        for fmt in ("svg", "dxf"):
            export.write(shared.drawing, folder / f"shared.{fmt}")
            for n, one in enumerate(pf.split_sheets(separate.drawing)):
                export.write(one, folder / f"sheet-{n}.{fmt}")
        for side, (g, key) in zip(("front", "back"), guides):
            export.write(g, folder / f"{side}.svg")
            export.write(printed(g, key, (210.0, 297.0)), folder / f"{side}.pdf")

    stage("write files", write_all)
    times["total"] = sum(times.values())
    times["_pieces"] = puzzle.n_pieces
    times["_cut_m"] = (shared.cut_length / 1000, separate.cut_length / 1000)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", type=int, default=4)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    best: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(args.repeat):
            times = run(args.levels, Path(tmp))
            for k, v in times.items():
                best[k] = v if k.startswith("_") else min(best.get(k, float("inf")), v)
    shared_m, separate_m = best["_cut_m"]
    print(f"puzzle level {args.levels}: {best['_pieces']} pieces, cut {shared_m:.2f} m shared, "
          f"{separate_m:.2f} m separate (best of {args.repeat})")
    for k, v in best.items():
        if not k.startswith("_"):
            print(f"  {k:14} {v:6.3f} s")
    print(f"  target <= 3 s: {'met' if best['total'] <= 3.0 else 'MISSED'}")


if __name__ == "__main__":
    main()
