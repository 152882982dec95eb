"""The guard audit: each guard of the front ends and of the checkers of untrusted input disabled
once, and whether some test fails (README, "Mutation testing"; #34).

A guard is an ``if`` whose body starts by refusing: ``raise``, a call to ``fail``, ``_refuse``
or ``error`` (click's ``self.fail`` makes a ``BadParameter``), or a ``return`` of an error (an
HTTP status or response, a problem string a schema checker returns); or an ``assert``. A guard
is disabled by making its condition ``False`` (an ``assert`` ``True``) in a copy of ``src/``.

    python tests/hand_audit/guards.py list                      # the guards found
    python tests/hand_audit/guards.py run --map COV cli/recipe.py   # those of one file

``--map`` names a combined coverage data file of the whole suite measured with
``dynamic_context = test_function`` (measuring only the files above keeps it near the suite's
own time; a ``sitecustomize`` calling ``coverage.process_startup()`` covers xdist's workers):
each guard then runs, with ``-x``, the tests that reach its condition, those that quote its
message (a literal of 8 characters or more) first; a guard no in-process test reaches is
MISSED at once. Without ``--map`` a guard runs only the tests that quote its message. A
guard is caught when a test fails (or hangs past 15 minutes) without it. Not collected by
pytest.
"""

from __future__ import annotations

import argparse
import ast
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
SRC = ROOT / "src" / "weavecut"
# where guards are looked for: the front ends whole, and the checkers of untrusted input whose
# guards are not written as ``if ...: raise`` (those were audited one at a time before)
FILES = ("cli/*.py", "web/*.py", "schema.py", "readers/svg.py", "kitpage/viewer.py")
REFUSING_CALLS = ("fail", "_refuse", "error", "abort")
ERROR_WORDS = ("Response", "status", "error", "problem", "refuse")


@dataclass(frozen=True)
class Guard:
    file: str  # relative to src/weavecut
    line: int
    shape: str
    condition: str
    span: tuple[int, int, int, int]  # the condition's lines and columns, as ast gives them
    quotes: tuple[str, ...]  # literals of its message, to find the tests that quote it

    @property
    def name(self) -> str:
        return f"{self.file}:{self.line}"


def _shape(body: list[ast.stmt]) -> str | None:
    first = body[0]
    if isinstance(first, ast.Raise):
        return "raise"
    if isinstance(first, ast.Expr) and isinstance(first.value, ast.Call):
        func = ast.unparse(first.value.func).split(".")[-1]
        if func in REFUSING_CALLS:
            return f"call {func}"
    if isinstance(first, ast.Return) and first.value is not None:
        value = first.value
        if isinstance(value, ast.JoinedStr) or (isinstance(value, ast.Constant)
                                                 and isinstance(value.value, str)):
            return "return problem"
        text = ast.unparse(value)
        if any(w in text for w in ERROR_WORDS) or re.search(r"\b[45]\d\d\b", text):
            return "return error"
    return None


def _quotes(node: ast.AST) -> tuple[str, ...]:
    found = []
    for sub in ast.walk(node):
        if isinstance(sub, ast.Constant) and isinstance(sub.value, str):
            found += [p.strip() for p in re.split(r"[{}\n]", sub.value) if len(p.strip()) >= 8]
    return tuple(dict.fromkeys(found))


def guards(files: tuple[str, ...] = FILES) -> list[Guard]:
    out = []
    for pattern in files:
        for path in sorted(SRC.glob(pattern)):
            tree = ast.parse(path.read_text(encoding="utf-8"))
            for node in ast.walk(tree):
                if isinstance(node, ast.If) and (shape := _shape(node.body)):
                    test, said = node.test, node.body[0]
                elif isinstance(node, ast.Assert):
                    shape, test, said = "assert", node.test, node
                else:
                    continue
                out.append(Guard(str(path.relative_to(SRC)), node.lineno, shape,
                                 ast.unparse(test)[:100],
                                 (test.lineno, test.col_offset, test.end_lineno,
                                  test.end_col_offset), _quotes(said)))
    return sorted(out, key=lambda g: (g.file, g.line))


def disabled(chosen: list[Guard]) -> dict[Path, str]:
    """The files of ``src/weavecut`` with each chosen guard's condition False (an assert's
    True), by path relative to ``src``."""
    by_file: dict[str, list[Guard]] = {}
    for g in chosen:
        by_file.setdefault(g.file, []).append(g)
    out = {}
    for file, gs in by_file.items():
        lines = (SRC / file).read_text(encoding="utf-8").splitlines(keepends=True)
        for g in sorted(gs, key=lambda g: g.span, reverse=True):
            l0, c0, l1, c1 = g.span
            head, tail = lines[l0 - 1][:c0], lines[l1 - 1][c1:]
            word = "True" if g.shape == "assert" else "False"
            new = f"({word}" + "\n" * (l1 - l0) + ")"  # the same lines: tracebacks still match
            lines[l0 - 1:l1] = [head + new + tail]
        out[Path("weavecut") / file] = "".join(lines)
    return out


class Copy:
    """One copy of ``src/`` for the whole run (its bytecode is kept between runs): each run
    writes the changed files, and puts the originals back after."""

    def __init__(self) -> None:
        self._tmp = tempfile.TemporaryDirectory(prefix="guard-audit-")
        self.src = Path(self._tmp.name) / "src"
        shutil.copytree(ROOT / "src", self.src, ignore=shutil.ignore_patterns("__pycache__"))

    def pytest(self, chosen: list[Guard], tests: list[str],
               parallel: bool = False) -> tuple[int, list[str]]:
        """Run ``tests`` with ``chosen`` disabled: (status, failed node ids)."""
        changed = disabled(chosen)
        for rel, text in changed.items():
            (self.src / rel).write_text(text, encoding="utf-8")
        env = {**os.environ, "PYTHONPATH": str(self.src)}
        args = ["-n", "2", "-x", "-rf"] if parallel else ["-x", "-rf"]
        try:
            done = subprocess.run([sys.executable, "-m", "pytest", "-q", "--tb=no", "-p",
                                   "no:randomly", "-p", "no:cacheprovider", *args, *tests],
                                  cwd=ROOT, env=env, capture_output=True, text=True,
                                  timeout=900)
        except subprocess.TimeoutExpired:  # a guard whose absence hangs a test is caught
            return 1, ["(timed out)"]
        finally:
            for rel in changed:
                shutil.copy(ROOT / "src" / rel, self.src / rel)
        failed = [line.split()[1] for line in done.stdout.splitlines()
                  if line.startswith("FAILED ")]
        if done.returncode == 2 and "stopping after 1 failures" in done.stdout:
            return 1, failed  # xdist's -x: interrupted at the first failure
        if done.returncode not in (0, 1):
            raise SystemExit(f"pytest could not run (status {done.returncode})\n"
                             f"{done.stdout[-2000:]}{done.stderr[-2000:]}")
        return done.returncode, failed


def quoting_tests(g: Guard) -> list[str]:
    """The tests that quote one of the guard's message literals: the test functions whose
    text holds it, or the whole file when only its case tables do."""
    found = []
    for path in sorted((ROOT / "tests").rglob("*.py")):
        if "hand_audit" in path.parts:
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        if not any(q in text for q in g.quotes):
            continue
        name = str(path.relative_to(ROOT))
        funcs = []
        for node in ast.parse(text).body:
            inner = node.body if isinstance(node, ast.ClassDef) else [node]
            prefix = f"{node.name}::" if isinstance(node, ast.ClassDef) else ""
            funcs += [f"{name}::{prefix}{f.name}" for f in inner
                      if isinstance(f, ast.FunctionDef) and f.name.startswith("test")
                      and any(q in ast.get_source_segment(text, f) for q in g.quotes)]
        found += funcs or [name]
    return found


def reaching_tests(data_file: Path) -> dict[tuple[str, int], set[str]]:
    """(file relative to src/weavecut, line) -> the pytest node ids of the tests that ran it,
    from a coverage data file measured with ``dynamic_context = test_function``."""
    import coverage

    data = coverage.CoverageData(basename=str(data_file))
    data.read()
    out: dict[tuple[str, int], set[str]] = {}
    node_of: dict[str, str | None] = {}
    for measured in data.measured_files():
        if "/src/weavecut/" not in measured:
            continue
        rel = measured.split("/src/weavecut/", 1)[1]
        for line, contexts in data.contexts_by_lineno(measured).items():
            for context in contexts:
                if context not in node_of:
                    node_of[context] = _node_id(context)
                if node_of[context]:
                    out.setdefault((rel, line), set()).add(node_of[context])
    return out


def _node_id(context: str) -> str | None:
    """``tests.web.test_jobs.Class.test_x`` -> ``tests/web/test_jobs.py::Class::test_x``."""
    parts = context.split(".")
    for n in range(len(parts) - 1, 0, -1):
        path = ROOT.joinpath(*parts[:n]).with_suffix(".py")
        if path.is_file():
            return "::".join([str(path.relative_to(ROOT)), *parts[n:]])
    return None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("action", choices=("list", "run"))
    parser.add_argument("--map", metavar="COVERAGE_FILE",
                        help="a combined coverage data file of the suite, measured with "
                        "dynamic_context = test_function: each guard runs the tests that "
                        "reach it (without: the tests that quote its message)")
    parser.add_argument("--tests", action="append", default=[], metavar="TEST",
                        help="a test to run first for every guard (repeatable): the tests "
                        "written for the guards a run missed")
    parser.add_argument("only", nargs="*", help="guards whose file (relative to "
                        "src/weavecut) or file:line starts so")
    args = parser.parse_args()
    found = guards()
    chosen = ([g for o in args.only for g in found if g.name.startswith(o)] if args.only
              else found)  # in the order asked
    chosen = list(dict.fromkeys(chosen))
    if args.action == "list":
        for g in chosen:
            print(f"{g.name:32} {g.shape:15} {g.condition}")
        print(f"{len(chosen)} guards")
        return
    reach = reaching_tests(Path(args.map)) if args.map else None
    copy = Copy()
    caught: dict[str, str] = {}
    for g in chosen:
        quoting = quoting_tests(g)
        tests = [*args.tests, *quoting]
        if reach is not None:
            reached = sorted({t for line in range(g.span[0], g.span[2] + 1)
                              for t in reach.get((g.file, line), ())})
            # the tests that quote the message first (-x stops at the first failure)
            tests = [*args.tests, *(t for t in quoting
                                    if any(t.startswith(r.split("::")[0]) for r in reached))]
            tests += [t for t in reached if t not in tests]
            tests = tests or quoting  # reached only by tests outside the map's run
            if not tests:
                print(f"MISSED  {g.name} ({g.shape}): {g.condition}  [no test reaches it]",
                      flush=True)
                continue
        status, failed = (copy.pytest([g], tests, parallel=len(tests) > 40) if tests
                          else (0, []))
        if status:
            caught[g.name] = failed[0] if failed else "?"
            print(f"caught  {g.name}: {caught[g.name]}", flush=True)
        else:
            print(f"MISSED  {g.name} ({g.shape}): {g.condition}  [{len(tests)} tests run]",
                  flush=True)
    print(f"\n{len(caught)} of {len(chosen)} guards caught")


if __name__ == "__main__":
    main()
