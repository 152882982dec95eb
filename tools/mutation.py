"""Mutation testing, one package at a time: ``make mutation`` (or ``python tools/mutation.py
[PACKAGE ...]``) runs mutmut over each package with the tests that guard it, and writes
``build/mutation/report.json`` and ``build/mutation/report.md`` (kill rate per package, every
surviving mutant). Mutants listed in ``tests/mutation_equivalents.toml`` with a reason count as
equivalent and leave the denominator.

Each package runs in its own copy of the tracked tree under ``build/mutation/<package>/``,
where mutmut's cache stays between runs: a second run tests only the mutants of functions that
changed, ``--survivors`` re-tests only last run's survivors (after new tests were written;
it maps the tests to the functions they reach anew),
and ``--report`` runs nothing and reports what the caches hold (after a stopped run). Why
mutmut: it is maintained, pytest-native, and runs only the tests that reach a mutated function
(cosmic-ray needs a session database and a separate baseline per module for the same result).
"""

from __future__ import annotations

import argparse
import hashlib
import importlib.util
import json
import os
import shutil
import subprocess
import sys
import time
import tomllib
from math import sqrt
from dataclasses import dataclass, field
from fnmatch import fnmatch
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "build" / "mutation"
EQUIVALENTS = ROOT / "tests" / "mutation_equivalents.toml"
MUTMUT = [sys.executable, "-m", "mutmut"]
NO_MUTANT = "weavecut.no_such_module.x_no_such_function__mutmut_0"

# mutmut stops a mutant after (expected time + 1 s) x this x 2 CPU seconds, or half that in
# wall time; on a shared, loaded machine a test takes ten times its CPU time in wall time, so
# mutmut's default (15) reported mutants whose tests passed as timeouts (counted as killed)
TIMEOUT_MULTIPLIER = 60


@dataclass(frozen=True)
class Package:
    """What to mutate, the tests that guard it, and the package's own mutmut settings:
    ``deselect`` (a pytest ``-k`` expression) and ``settings`` (extra ``[tool.mutmut]`` keys,
    e.g. ``max_stack_depth`` so that a test reaching a function only through many calls is
    not run for its mutants)."""

    mutate: tuple[str, ...]
    tests: tuple[str, ...]
    deselect: str = ""
    settings: dict = field(default_factory=dict)


PACKAGES: dict[str, Package] = {
    "subdivision": Package(("src/weavecut/subdivision/*",), ("tests/subdivision",)),
    "weave": Package(("src/weavecut/weave/*",),
                     ("tests/weave", "tests/surface/test_surface_weave.py",
                      "tests/surface/test_woven_model.py")),
    # the package's own tests (mutmut runs the fastest first), test_fuzz's in-process bad-file
    # and random-input cases (not the subprocess, interrupt and million-face runs) and the snub
    # tests; no max_stack_depth: mutmut 3.8's stack walk fails on the frame of a dataclass's
    # generated __init__ (file "<string>"), which every Mesh is built through. Timeout
    # multiplier 20: the test times mutmut measures (with its tracing) are 3 to 25 times the
    # real ones here, and at 60 a mutant that loops (the reader's bisection and line pieces)
    # held a child for over ten minutes
    "mesh-core": Package(("src/weavecut/mesh.py", "src/weavecut/mesh_geometry.py",
                          "src/weavecut/mesh_io.py", "src/weavecut/readers/obj.py",
                          "src/weavecut/readers/obj_tokens.py",
                          "src/weavecut/readers/mesh_json.py", "src/weavecut/validation.py"),
                         ("tests/test_mesh.py", "tests/test_mesh_geometry.py",
                          "tests/test_mesh_io.py", "tests/test_mesh_io_rules.py",
                          "tests/test_validation.py", "tests/test_validation_rules.py",
                          "tests/test_fuzz.py", "tests/subdivision/test_snub.py"),
                         deselect="not interrupt and not hash_seeds and not a_million_faces "
                                  "and not bad_options and not read_only and not fifo",
                         settings={"timeout_multiplier": 20}),
    # the CLI tests build whole puzzle sets (drawing defaults: a dozen puzzles, 10 s each on
    # an idle machine), the figure tests a figure around a level-4 puzzle, and the random
    # stars nine puzzles (test_star_puzzles runs one star per rule instead); each function
    # is reached by a test that calls it within four calls (max_stack_depth: the colour
    # search's helpers sit four calls below colour_puzzle)
    "puzzle": Package(("src/weavecut/puzzle/*",), ("tests/puzzle",),
                      deselect="not test_cli_ and not test_a_drawing_without_cell_or_levels "
                               "and not test_the_small_pieces_warning_names_a_cell "
                               "and not test_a_star_meshed_in_hexagons "
                               "and not test_puzzle_help and not random_stars "
                               "and not test_closeup_shows and not test_pentagon_weave_uses",
                      settings={"max_stack_depth": 4}),
    # papermodel's tests cache whole books (lru_cache): mutmut's default process isolation forks
    # each mutant from the process that ran the clean suite, so a cached book built without
    # the mutant would hide it; "forkserver" forks from a process that only collected. A test
    # is run for the functions it reaches through at most 5 papermodel/layout calls (every
    # function is still reached by a test that calls it that closely); the two tests of the
    # 23 cm pentagon flower (a 30 s book) are left out: label tabs are also reached by the
    # size-refusal test, and the rest of the book by the small books' tests
    "papermodel": Package(("src/weavecut/papermodel/*",), ("tests/papermodel",),
                          deselect="not label_tab_holds_the_id and not papers_23_cm",
                          settings={"max_stack_depth": 6, "process_isolation": "forkserver"}),
    # the writers' own tests call each writer directly (every function 1 to 3 frames of
    # src/ below the test); the CLI tests reach a writer 5 to 9 frames down, so they are left
    # out, and max_stack_depth keeps any test that goes through export.write from being run
    # for the functions deep inside a writer
    "export": Package(("src/weavecut/export/*",), ("tests/export",),
                      settings={"max_stack_depth": 5}),
    # the drawing readers (the mesh-file parsers are mesh-core's); the strands commands of a
    # drawing run the paper model for 10-20 s and guard strands, not the readers (read_drawing
    # is reached by the faster tests of the same drawings)
    "readers": Package(tuple(f"src/weavecut/readers/{m}.py" for m in (
                           "__init__", "budgets", "drawing", "dxf", "outline_mesh", "pieces",
                           "rings", "svg", "tessellations")), ("tests/readers",),
                       deselect="not strands_of_a_drawing"),
    # the Drawing model and the tools every product uses; hershey_futural.py is the stroke
    # font's glyph table (data: a mutant there is a changed glyph, which the glyph tests check
    # by their own table, not worth 4000 mutants); the layout tools' own tests only (the
    # products' tests reach a layout function many calls down; the figures', the puzzle's
    # cut files' and the strips' paint tests are the nearest that reach the figure drawing,
    # the nesting and the stroke-font labels; the commands' figures, the packer, the room
    # search and the tiled pages have tests of their own), and no max_stack_depth:
    # mutmut 3.8's stack walk fails on the frame of a dataclass's generated __init__ (file
    # "<string>"), which every Drawing is built through (as for mesh-core)
    "layout": Package(tuple(f"src/weavecut/layout/{m}.py" for m in (
                          "__init__", "colour_difference", "contrast", "cutpaths", "drawing",
                          "labels", "lasersetup", "mesh_figure", "nesting", "poles",
                          "strokefont", "tiling", "weave_figure")),
                      ("tests/test_drawing.py", "tests/test_cutpaths.py",
                       "tests/test_contrast.py", "tests/test_nesting_moves.py",
                       "tests/test_tiling_clip.py", "tests/test_strokefont_glyphs.py",
                       "tests/test_strokefont_labels.py", "tests/test_pages.py",
                       "tests/puzzle/test_colour_difference.py",
                       "tests/untrusted/test_layout_guards.py",
                       "tests/papermodel/test_label_checks.py", "tests/figures",
                       "tests/puzzle/test_cut_readback.py",
                       "tests/papermodel/test_strip_paint.py", "tests/test_figure_drawings.py",
                       "tests/test_nesting_packing.py", "tests/test_nesting_room_search.py",
                       "tests/test_tiled_pages.py", "tests/test_poles.py",
                       "tests/test_label_fits.py")),
    # the kit page: its own tests build small kits in process (the CLI's build and --html are
    # a few frames above kitpage), the figures a maker reads against --json, and the
    # previews', laser settings' and cards' own tests
    "kitpage": Package(("src/weavecut/kitpage/*",),
                       ("tests/test_kitpage.py", "tests/test_figures_agree.py",
                        "tests/test_kitpage_previews.py", "tests/test_kitpage_cards.py")),
    # lengths with units and presets (the untrusted-input tests read presets and options
    # through the same functions)
    "units-presets": Package(("src/weavecut/units.py", "src/weavecut/presets.py"),
                             ("tests/test_units.py", "tests/test_lengths.py",
                              "tests/untrusted/test_preset_limits.py",
                              "tests/untrusted/test_guards.py",
                              "tests/untrusted/test_presets.py",
                              "tests/untrusted/test_options.py", "tests/test_cli_names.py",
                              "tests/papermodel/test_cutter.py")),
    "surface": Package(("src/weavecut/surface.py",), ("tests/surface",)),
    # the command line: the CLI tests run whole commands (seconds each), the printouts' and
    # models' tests read what they print and write back, the entry point's run main in
    # process (the interrupt and install tests start processes of their own, which mutmut's
    # trampoline does not reach), and the parts' tests build the option groups anew (the
    # commands build theirs at import, before any mutant is switched on)
    "cli": Package(("src/weavecut/cli/*",),
                   ("tests/test_cli.py", "tests/test_cli_names.py", "tests/test_cli_outputs.py",
                    "tests/test_cli_shell.py", "tests/test_formats_option.py",
                    "tests/test_cli_printouts.py", "tests/test_cli_models.py",
                    "tests/test_cli_parts.py", "tests/untrusted/test_entry_point.py",
                    "tests/untrusted/test_options.py", "tests/untrusted/test_recipes.py",
                    "tests/untrusted/test_confinement.py", "tests/untrusted/test_cli_guards.py",
                    "tests/untrusted/test_cli_option_guards.py"),
                   settings={"timeout_multiplier": 20}),
}


def tracked_tree(dest: Path) -> None:
    """Copy the files git tracks (and untracked, unignored ones) into ``dest``; a changed file
    gets a fresh mtime (``shutil.copy``, not ``copy2``), which is how mutmut notices it must
    mutate it again (it keeps the results of the functions whose hash did not change)."""
    files = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                           cwd=ROOT, check=True, capture_output=True, text=True).stdout.split()
    for name in files:
        src = ROOT / name
        if src.is_file():
            target = dest / name
            target.parent.mkdir(parents=True, exist_ok=True)
            if not target.exists() or target.read_bytes() != src.read_bytes():
                shutil.copy(src, target)


def configure(work: Path, package: Package) -> None:
    """Append a [tool.mutmut] table for this package to the copy's pyproject.toml."""
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    args = ["-p", "no:cacheprovider", "-x", "-q"]
    if package.deselect:
        args += ["-k", package.deselect]
    settings = {"source_paths": ["src"], "only_mutate": list(package.mutate),
                "pytest_add_cli_args_test_selection": list(package.tests),
                "pytest_add_cli_args": args,
                "also_copy": ["templates/", "examples/", "benchmarks/", "docs/", "README.md",
                              "Makefile"],
                "timeout_multiplier": TIMEOUT_MULTIPLIER, **package.settings}
    text += "\n[tool.mutmut]\n" + "".join(f"{key} = {json.dumps(value)}\n"
                                          for key, value in settings.items())
    (work / "pyproject.toml").write_text(text, encoding="utf-8")


def mutmut_run(work: Path, children: int, names: list[str]) -> subprocess.CompletedProcess:
    return subprocess.run([*MUTMUT, "run", "--max-children", str(children), *names], cwd=work,
                          capture_output=True, text=True,
                          env={**os.environ, "HYPOTHESIS_PROFILE": "mutation"})


def sample_of(status: dict[str, str], equivalents: dict[str, str], size: int) -> list[str]:
    """The ``size`` non-equivalent mutants whose names hash lowest (SHA-256): a uniform random
    sample that stays the same from run to run, and keeps the mutants of unchanged functions
    when others change (mutmut numbers mutants per function)."""
    names = sorted((m for m in status if m not in equivalents),
                   key=lambda m: hashlib.sha256(m.encode()).hexdigest())
    return sorted(names[:size])


def run_package(name: str, children: int, only: list[str], fresh: bool = False,
                sample: int = 0, equivalents: dict[str, str] | None = None) -> dict:
    """Run mutmut on one package: every mutant not yet tested, or only those named in
    ``only``, or (``sample`` > 0) those of a fixed random sample of that size not yet tested.
    ``fresh`` maps tests to functions anew (mutmut maps only tests it has not seen, so a test
    that changed would keep its old reach)."""
    work = OUT / name
    tracked_tree(work)
    if fresh:
        (work / "mutants" / "mutmut-stats.json").unlink(missing_ok=True)
    configure(work, PACKAGES[name])
    start = time.monotonic()
    if sample:
        # mutmut has no generate-only command: a run filtered to a name no mutant has
        # generates the mutants and maps the tests, then stops with "nothing matches"
        probe = mutmut_run(work, children, [NO_MUTANT])
        if "nothing matches" not in probe.stdout + probe.stderr:
            fail(name, work, probe)
        status = collect(name)["status"]
        only = [m for m in sample_of(status, equivalents or {}, sample)
                if status[m] == "not checked"]
        if not only:
            return {**collect(name), "minutes": 0.0}
    run = mutmut_run(work, children, only)
    if run.returncode:  # e.g. the tests fail without any mutant: show why, then stop
        fail(name, work, run)
    return {**collect(name), "minutes": round((time.monotonic() - start) / 60, 1)}


def fail(name: str, work: Path, run: subprocess.CompletedProcess) -> None:
    print(run.stdout[-3000:], run.stderr[-3000:], sep="\n", file=sys.stderr)
    raise SystemExit(f"mutation: mutmut failed on {name} (status {run.returncode}); "
                     f"see above, or run `mutmut run` in {work}")


def collect(name: str) -> dict:
    """The status of every mutant of a package as mutmut's cache holds it."""
    work = OUT / name
    subprocess.run([*MUTMUT, "export-cicd-stats"], cwd=work, check=True, capture_output=True)
    stats = json.loads((work / "mutants" / "mutmut-cicd-stats.json").read_text())
    listing = subprocess.run([*MUTMUT, "results", "--all", "true"], cwd=work, check=True,
                             capture_output=True, text=True).stdout
    status = dict(line.strip().rsplit(": ", 1) for line in listing.splitlines() if ": " in line)
    return {"stats": stats, "status": status}


def summarise(results: dict[str, dict], equivalents: dict[str, str]) -> dict:
    """Kill rate per package over the non-equivalent mutants tested so far; untested mutants
    (no test reaches them) count as survivors, mutants a stopped run never reached as
    ``unchecked``."""
    report = {}
    for name, result in results.items():
        status = result["status"]
        alive = sorted(m for m, s in status.items()
                       if s in ("survived", "no tests") and m not in equivalents)
        killed = sum(s in ("killed", "timeout", "segfault") for s in status.values())
        equivalent = sorted(m for m in status if m in equivalents)
        unchecked = sum(s == "not checked" for s in status.values())
        total = len(alive) + killed
        report[name] = {"mutants": len(status), "killed": killed, "equivalent": len(equivalent),
                        "unchecked": unchecked, "survived": alive,
                        "kill_rate": killed / total if total else 1.0,
                        "minutes": result.get("minutes")}
        if result.get("sample"):
            tested = [status[m] for m in sample_of(status, equivalents, result["sample"])
                      if status[m] != "not checked"]
            dead = sum(s in ("killed", "timeout", "segfault") for s in tested)
            report[name]["sample"] = {"size": result["sample"], "tested": len(tested),
                                      "killed": dead, "interval": wilson(dead, len(tested))}
    return report


def wilson(killed: int, tested: int, z: float = 1.96) -> tuple[float, float]:
    """The 95 % Wilson score interval of a package's kill rate from a sample's verdicts."""
    if not tested:
        return (0.0, 1.0)
    p, n = killed / tested, tested
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return (round(max(0.0, centre - half), 4), round(min(1.0, centre + half), 4))


def function_of(mutant: str) -> str:
    """``weavecut.weave.report.x_lineage_summary__mutmut_3`` -> ``report.lineage_summary``;
    methods (``x\u01c1Class\u01c1method``) -> ``module.Class.method``."""
    module, _, mangled = mutant.split("__mutmut_")[0].rpartition(".")
    name = mangled[2:].replace("\u01c1", ".") if mangled.startswith("x\u01c1") else mangled[2:]
    return f"{module.rpartition('.')[2]}.{name}"


def markdown(report: dict) -> str:
    rows = ["| package | mutants | equivalent | killed | survived | not yet run | kill rate "
            "| random sample: killed of tested (95 % interval) |",
            "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for name, r in report.items():
        sample = r.get("sample")
        estimate = (f"{sample['killed']} of {sample['tested']} ({100 * sample['interval'][0]:.1f}"
                    f"–{100 * sample['interval'][1]:.1f} %)" if sample else "")
        rows.append(f"| {name} | {r['mutants']} | {r['equivalent']} | {r['killed']} | "
                    f"{len(r['survived'])} | {r.get('unchecked', 0)} | "
                    f"{100 * r['kill_rate']:.1f} % | {estimate} |")
    by_function = []
    for name, r in report.items():
        counts: dict[str, int] = {}
        for m in r["survived"]:
            counts[function_of(m)] = counts.get(function_of(m), 0) + 1
        top = sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))
        by_function.append(f"- {name}: " + ", ".join(f"{f} {n}" for f, n in top))
    survivors = [f"- `{m}` ({name})" for name, r in report.items() for m in r["survived"]]
    return "\n".join(rows + ["", "Survivors by function:", *by_function, "",
                             "Surviving mutants (`mutmut show NAME` in "
                             "build/mutation/PACKAGE):", *survivors]) + "\n"


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("packages", nargs="*", metavar="PACKAGE",
                        help=f"packages to test (default: all of {', '.join(PACKAGES)})")
    parser.add_argument("--survivors", action="store_true",
                        help="re-test only the mutants that survived the last run")
    parser.add_argument("--report", action="store_true",
                        help="run nothing: report what each package's cache holds (after a "
                             "run was stopped, say)")
    parser.add_argument("--only", action="append", default=[], metavar="PATTERN",
                        help="test only the mutants whose names match PATTERN (fnmatch, "
                             "repeatable), e.g. 'weavecut.puzzle.colouring*': a slice of a "
                             "package too large for one run")
    parser.add_argument("--sample", type=int, default=0, metavar="N",
                        help="test only a fixed random sample of N mutants per package (those "
                             "not yet tested) and report the kill rate's 95 %% interval")
    parser.add_argument("--max-children", type=int, default=2,
                        help="parallel test processes (default 2: this machine's cores)")
    args = parser.parse_args(argv)
    names = args.packages or list(PACKAGES)
    unknown = sorted(set(names) - set(PACKAGES))
    if unknown:
        print(f"unknown package(s) {unknown}; choose from {sorted(PACKAGES)}", file=sys.stderr)
        return 2
    if importlib.util.find_spec("mutmut") is None:
        print("mutation: mutmut is not installed; run `make mutation` (it installs "
              "'.[mutation]') or `pip install -e '.[mutation]'`", file=sys.stderr)
        return 2
    equivalents = (tomllib.loads(EQUIVALENTS.read_text(encoding="utf-8"))
                   if EQUIVALENTS.exists() else {})
    OUT.mkdir(parents=True, exist_ok=True)
    previous = OUT / "report.json"
    results = json.loads(previous.read_text())["raw"] if previous.exists() else {}
    for name in names:
        only = list(args.only)
        if args.survivors:
            if name not in results:
                print(f"mutation: no earlier run of {name} to take survivors from",
                      file=sys.stderr)
                return 2
            only = [m for m, s in results[name]["status"].items()
                    if s in ("survived", "no tests") and m not in equivalents
                    and (not args.only or any(fnmatch(m, p) for p in args.only))]
        print(f"mutation: {name}" + (f" ({len(only)} survivors)" if args.survivors else ""),
              flush=True)
        if (args.survivors or args.only) and not only:
            continue
        sample = args.sample or results.get(name, {}).get("sample", 0)
        if args.report:
            results[name] = {**results.get(name, {}), **collect(name), "sample": sample}
            continue
        results[name] = {**run_package(name, args.max_children, only, fresh=args.survivors,
                                       sample=0 if only else args.sample,
                                       equivalents=equivalents), "sample": sample}
    # another run may have finished meanwhile: keep its packages, replace only this run's
    ran = {n: results[n] for n in names if n in results}
    results = {**(json.loads(previous.read_text())["raw"] if previous.exists() else {}), **ran}
    report = summarise({n: results[n] for n in PACKAGES if n in results}, equivalents)
    previous.write_text(json.dumps({"report": report, "raw": results}, indent=1))
    (OUT / "report.md").write_text(markdown(report))
    print(markdown(report))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
