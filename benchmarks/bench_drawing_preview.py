"""The preview of a puzzle of a drawing given no cell or levels (what the web app draws for an
upload): CPU seconds in one warm process, the defaults chosen with foresight (``workshop.
drawing_defaults``: most candidates never built) and by the full search (every candidate
built), run alternately, with the ratio. Prints; asserts nothing about time.

    python benchmarks/bench_drawing_preview.py [--repeat 5] [DRAWING ...]
"""

from __future__ import annotations

import argparse
import functools
import statistics
import tempfile
import time
from pathlib import Path

from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.puzzle import workshop

ROOT = Path(__file__).resolve().parents[1]


def preview(drawing: Path, folder: Path, foresight: bool) -> float:
    """CPU seconds of ``puzzle DRAWING --preview`` in this process."""
    chosen = functools.partial(ORIGINAL, foresight=foresight)
    workshop.drawing_defaults = chosen
    try:
        t0 = time.process_time()
        result = CliRunner().invoke(cli, ["puzzle", str(drawing), "--preview", "-o",
                                          str(folder / "look"), "--force"])
        spent = time.process_time() - t0
    finally:
        workshop.drawing_defaults = ORIGINAL
    assert result.exit_code == 0, result.output
    return spent


ORIGINAL = workshop.drawing_defaults


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("drawings", nargs="*", type=Path,
                        default=[ROOT / "templates" / "recipes" / "heart.svg"])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    print("| drawing | full search, CPU s best / median | foresight | ratio |")
    print("| --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as tmp:
        for drawing in args.drawings:
            preview(drawing, Path(tmp), True)  # warm: imports, fonts, caches
            runs = {True: [], False: []}
            for _ in range(args.repeat):
                for foresight in (False, True):
                    runs[foresight].append(preview(drawing, Path(tmp), foresight))
            full, fast = (min(runs[False]), statistics.median(runs[False])), \
                (min(runs[True]), statistics.median(runs[True]))
            print(f"| {drawing.name} | {full[0]:.2f} / {full[1]:.2f} | {fast[0]:.2f} / "
                  f"{fast[1]:.2f} | {fast[1] / full[1]:.2f} |")


if __name__ == "__main__":
    main()
