"""Mutation testing, one package at a time: ``make mutation`` (or ``python tools/mutation.py
[PACKAGE ...]``) runs mutmut over each package with the tests that guard it, and writes
``build/mutation/report.json`` and ``build/mutation/report.md`` (kill rate per package, every
surviving mutant). Mutants listed in ``tests/mutation_equivalents.toml`` with a reason count as
equivalent and leave the denominator.

Each package runs in its own copy of the tracked tree under ``build/mutation/<package>/``, so a
run can be repeated per package and mutmut's own cache is kept between runs. Why mutmut: it is
maintained, pytest-native, and runs only the tests that reach a mutated function, which keeps a
whole run within an hour on two cores (cosmic-ray needs a session database and a separate
baseline per module for the same result).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "build" / "mutation"
EQUIVALENTS = ROOT / "tests" / "mutation_equivalents.toml"

# package -> (files to mutate, tests that guard them)
PACKAGES: dict[str, tuple[list[str], list[str]]] = {
    "subdivision": (["src/weavecut/subdivision/*"], ["tests/subdivision"]),
    "weave": (["src/weavecut/weave/*"], ["tests/weave"]),
    "mesh-core": (["src/weavecut/mesh.py", "src/weavecut/mesh_io.py",
                   "src/weavecut/validation.py"],
                  ["tests/test_mesh.py", "tests/test_mesh_io.py", "tests/test_validation.py",
                   "tests/test_fuzz.py"]),
    "puzzle": (["src/weavecut/puzzle/*"], ["tests/puzzle"]),
    "papermodel": (["src/weavecut/papermodel/*"], ["tests/papermodel"]),
    "export": (["src/weavecut/export/*"], ["tests/export", "tests/test_cli.py"]),
}


def tracked_tree(dest: Path) -> None:
    """Copy the files git tracks (and untracked, unignored ones) into ``dest``."""
    files = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                           cwd=ROOT, check=True, capture_output=True, text=True).stdout.split()
    for name in files:
        src = ROOT / name
        if src.is_file():
            target = dest / name
            target.parent.mkdir(parents=True, exist_ok=True)
            if not target.exists() or target.read_bytes() != src.read_bytes():
                shutil.copy2(src, target)


def configure(work: Path, mutate: list[str], tests: list[str]) -> None:
    """Append a [tool.mutmut] table for this package to the copy's pyproject.toml."""
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    quoted = ", ".join
    text += ("\n[tool.mutmut]\nsource_paths = [\"src\"]\n"
             f"only_mutate = [{quoted(json.dumps(m) for m in mutate)}]\n"
             f"pytest_add_cli_args_test_selection = [{quoted(json.dumps(t) for t in tests)}]\n"
             "pytest_add_cli_args = [\"-p\", \"no:cacheprovider\", \"-x\", \"-q\"]\n"
             "also_copy = [\"templates/\", \"examples/\"]\n")
    (work / "pyproject.toml").write_text(text, encoding="utf-8")


def run_package(name: str, children: int) -> dict:
    mutate, tests = PACKAGES[name]
    work = OUT / name
    tracked_tree(work)
    configure(work, mutate, tests)
    mutmut = [sys.executable, "-m", "mutmut"]
    subprocess.run([*mutmut, "run", "--max-children", str(children)], cwd=work, check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run([*mutmut, "export-cicd-stats"], cwd=work, check=True,
                   capture_output=True)
    stats = json.loads((work / "mutants" / "mutmut-cicd-stats.json").read_text())
    listing = subprocess.run([*mutmut, "results", "--all", "true"], cwd=work, check=True,
                             capture_output=True, text=True).stdout
    status = dict(line.strip().rsplit(": ", 1) for line in listing.splitlines() if ": " in line)
    return {"stats": stats, "status": status}


def summarise(results: dict[str, dict], equivalents: dict[str, str]) -> dict:
    """Kill rate per package over non-equivalent mutants; untested mutants count as survivors."""
    report = {}
    for name, result in results.items():
        status = result["status"]
        alive = sorted(m for m, s in status.items()
                       if s in ("survived", "no tests") and m not in equivalents)
        killed = sum(s in ("killed", "timeout", "segfault") for s in status.values())
        equivalent = sorted(m for m in status if m in equivalents)
        total = len(status) - len(equivalent)
        report[name] = {"mutants": len(status), "killed": killed, "equivalent": len(equivalent),
                        "survived": alive, "kill_rate": killed / total if total else 1.0}
    return report


def markdown(report: dict) -> str:
    rows = ["| package | mutants | equivalent | killed | survived | kill rate |",
            "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for name, r in report.items():
        rows.append(f"| {name} | {r['mutants']} | {r['equivalent']} | {r['killed']} | "
                    f"{len(r['survived'])} | {100 * r['kill_rate']:.1f} % |")
    survivors = [f"- `{m}` ({name})" for name, r in report.items() for m in r["survived"]]
    return "\n".join(rows + ["", "Surviving mutants (`mutmut show NAME` in "
                             "build/mutation/PACKAGE):", *survivors]) + "\n"


def main(argv: list[str]) -> int:
    names = argv or list(PACKAGES)
    unknown = sorted(set(names) - set(PACKAGES))
    if unknown:
        print(f"unknown package(s) {unknown}; choose from {sorted(PACKAGES)}", file=sys.stderr)
        return 2
    equivalents = (tomllib.loads(EQUIVALENTS.read_text(encoding="utf-8"))
                   if EQUIVALENTS.exists() else {})
    OUT.mkdir(parents=True, exist_ok=True)
    previous = OUT / "report.json"
    results = json.loads(previous.read_text())["raw"] if previous.exists() else {}
    for name in names:
        print(f"mutation: {name}", flush=True)
        results[name] = run_package(name, children=2)
    report = summarise({n: results[n] for n in PACKAGES if n in results}, equivalents)
    previous.write_text(json.dumps({"report": report, "raw": results}, indent=1))
    (OUT / "report.md").write_text(markdown(report))
    print(markdown(report))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
