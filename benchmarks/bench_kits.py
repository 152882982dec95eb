"""Whole kit commands, as a maker runs them, against the same commands of a frozen commit
(prints a table; asserts nothing).

    .venv/bin/python benchmarks/bench_kits.py [--repeat 3] [--base COMMIT] [--only NAME]
                                              [--also COMMIT]
    (or: make bench-kits)

Each command runs in a fresh process (interpreter start and imports included, as
``/usr/bin/time`` counts them), the frozen commit's and this checkout's alternately, ``repeat``
times each; the figure is its CPU time (user + system of the child), best and median, and the
ratio is this checkout's over the frozen one's, best to best. The frozen source is
``git archive``'d once into ``build/bench-base/<commit>/``: the code of before the kits were
made fast (``BASE``), as ``tests/subdivision/snub_oracle.py`` freezes the engine's old step.
``--only NAME`` (repeatable) runs only the kits whose name or command contains NAME
("laser", "puzzle"). ``--also COMMIT`` (repeatable) measures that commit's source too, in
the same rounds, in a column of its own (a branch's starting point beside its head).
Pages and sheets are counted in the outputs of the last run of each.
"""

from __future__ import annotations

import argparse
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from weavecut.text import counted

ROOT = Path(__file__).resolve().parents[1]
BASE = "e6bca44"  # main before the kits were made fast
PAGE = re.compile(rb"/Type /Page\b")
RUN = "import sys; from weavecut.cli import main; sys.argv[0] = 'weave-cut'; main()"
# (name, arguments, output, target ratio)
KITS = (
    ("pentagon flower paper model", ["strands", "pentagon-flower", "--size", "23cm"], "pf.pdf",
     0.2),
    ("square grid, laser card", ["strands", "square-grid", "--size", "27cm", "--laser-card"],
     "card", 0.2),
    ("square grid paper model", ["strands", "square-grid", "--size", "27cm"], "sq.pdf", 0.25),
    ("puzzle with numbers", ["puzzle", "--numbers"], "pz", 0.35),
    ("ball, level 1", ["strands", "dodecahedron", "--levels", "1", "--project", "sphere",
                       "--size", "12cm"], "ball.pdf", 0.5),
)


def frozen_source(commit: str) -> Path:
    """``src/`` of ``commit``, extracted once under build/bench-base/ with its ``templates/``
    (the presets that code reads: today's may have keys it does not know)."""
    folder = ROOT / "build" / "bench-base" / commit
    if not (folder / "src" / "weavecut").is_dir() or not (folder / "templates").is_dir():
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir(parents=True)
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", commit, "src",
                                  "templates"], check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(folder)], input=archive, check=True)
    return folder / "src"


def cpu_of(src: Path, args: list[str], out: Path) -> float:
    """CPU seconds (user + system) of one run of ``weave-cut -q ARGS -o OUT`` with ``src`` and
    the ``templates/`` beside it."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-c", RUN, "-q", *args, "-o", str(out)], check=True,
                   env={"PYTHONPATH": str(src), "PATH": "/usr/bin:/bin",
                        "WEAVECUT_TEMPLATES": str(src.parent / "templates")},
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def pages(out: Path) -> str:
    """Pages of a PDF, or the sheets and files of a kit folder ("3 pages", "1 sheet, 4
    files")."""
    if out.suffix == ".pdf":
        return counted(len(PAGE.findall(out.read_bytes())), "page")
    files = sorted(p.name for p in out.iterdir())
    sheets = [f for f in files if re.search(r"-(card|sheet|cut)-.*\.svg$", f)]
    return f"{counted(len(sheets), 'sheet')}, {counted(len(files), 'file')}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--base", default=BASE, help="the frozen commit (default %(default)s)")
    parser.add_argument("--only", action="append", default=[], metavar="NAME",
                        help="only the kits whose name or command contains NAME (repeatable)")
    parser.add_argument("--also", action="append", default=[], metavar="COMMIT",
                        help="a commit measured beside the frozen one and this checkout "
                        "(repeatable)")
    args = parser.parse_args()
    kits = [k for k in KITS if not args.only
            or any(w in f"{k[0]} {' '.join(k[1])}" for w in args.only)]
    if not kits:
        parser.error(f"no kit matches {args.only}; the kits: {', '.join(k[0] for k in KITS)}")
    also = {c: frozen_source(c) for c in args.also}
    sources = {"before": frozen_source(args.base), **also, "now": ROOT / "src"}
    extra = "".join(f" {c} | ratio |" for c in also)
    print(f"| command | before ({args.base}), CPU s best / median |{extra} now | ratio (target) | "
          f"pages before / now |\n| --- | --- |{' --- | --- |' * len(also)} --- | --- | --- |",
          flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        for name, cmd, output, target in kits:
            times: dict[str, list[float]] = {k: [] for k in sources}
            outs = {k: Path(tmp) / k / output for k in sources}
            for _ in range(args.repeat):
                for k, src in sources.items():
                    shutil.rmtree(outs[k].parent, ignore_errors=True)
                    outs[k].parent.mkdir()
                    times[k].append(cpu_of(src, cmd, outs[k]))
            best = {k: min(v) for k, v in times.items()}
            cell = {k: f"{best[k]:.2f} / {statistics.median(times[k]):.2f}" for k in times}
            beside = "".join(f" {cell[c]} | {best[c] / best['before']:.2f} |" for c in also)
            print(f"| `weave-cut {' '.join(cmd)} -o {output}` ({name}) | {cell['before']} |"
                  f"{beside} {cell['now']} | {best['now'] / best['before']:.2f} (≤ {target}) | "
                  f"{pages(outs['before'])} / {pages(outs['now'])} |", flush=True)


if __name__ == "__main__":
    main()
