"""The guard audit: each guard of the front ends and of the checkers of untrusted input disabled
once, and whether some test fails (README, "Mutation testing"; #34).

A guard is an ``if`` whose body starts by refusing: ``raise``, a call to ``fail``, ``_refuse``
or ``error`` (click's ``self.fail`` makes a ``BadParameter``), or a ``return`` of an error (an
HTTP status or response, a problem string a schema checker returns); or an ``assert``. A guard
is disabled by making its condition ``False`` (an ``assert`` ``True``) in a copy of ``src/``.

    python tests/hand_audit/guards.py list                 # the guards found
    python tests/hand_audit/guards.py run                  # every guard (about an hour)
    python tests/hand_audit/guards.py run cli/recipe.py    # those whose file starts so

Each guard first runs the test files that quote its message (a literal of 8 characters or more
from the ``raise`` or ``return``); a guard those do not catch is then disabled together with
the others not caught, the whole suite runs once, and each such guard runs the tests that
failed there, alone. A guard still not caught is reported MISSED. Not collected by pytest.
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


def disabled(src: Path, chosen: list[Guard]) -> None:
    """Make each chosen guard's condition False (an assert's True) in the copy ``src``."""
    by_file: dict[str, list[Guard]] = {}
    for g in chosen:
        by_file.setdefault(g.file, []).append(g)
    for file, gs in by_file.items():
        path = src / "weavecut" / file
        lines = path.read_text(encoding="utf-8").splitlines(keepends=True)
        for g in sorted(gs, key=lambda g: g.span, reverse=True):
            l0, c0, l1, c1 = g.span
            head, tail = lines[l0 - 1][:c0], lines[l1 - 1][c1:]
            word = "True" if g.shape == "assert" else "False"
            new = f"({word}" + "\n" * (l1 - l0) + ")"  # the same lines: tracebacks still match
            lines[l0 - 1:l1] = [head + new + tail]
        path.write_text("".join(lines), encoding="utf-8")


def pytest(chosen: list[Guard], tests: list[str], whole: bool = False) -> tuple[int, list[str]]:
    """Run ``tests`` on a copy of src/ with ``chosen`` disabled: (status, failed node ids)."""
    with tempfile.TemporaryDirectory(prefix="guard-audit-") as tmp:
        src = Path(tmp) / "src"
        shutil.copytree(ROOT / "src", src, ignore=shutil.ignore_patterns("__pycache__"))
        disabled(src, chosen)
        env = {**os.environ, "PYTHONPATH": str(src), "PYTHONDONTWRITEBYTECODE": "1"}
        args = ["-n", "2", "-rf"] if whole else ["-x", "-rf"]
        try:
            done = subprocess.run([sys.executable, "-m", "pytest", "-q", "--tb=no", "-p",
                                   "no:randomly", "-p", "no:cacheprovider", *args, *tests],
                                  cwd=ROOT, env=env, capture_output=True, text=True,
                                  timeout=3600 if whole else 900)
        except subprocess.TimeoutExpired:  # a guard whose absence hangs a test is caught
            return 1, ["(timed out)"]
    failed = sorted({line.split()[1] for line in done.stdout.splitlines()
                     if line.startswith("FAILED ")})
    failed = [f.split(" - ")[0] for f in failed]
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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("action", choices=("list", "run"))
    parser.add_argument("only", nargs="*", help="guards whose file (relative to "
                        "src/weavecut) or file:line starts so")
    args = parser.parse_args()
    chosen = [g for g in guards() if not args.only or any(g.name.startswith(o)
                                                           for o in args.only)]
    if args.action == "list":
        for g in chosen:
            print(f"{g.name:32} {g.shape:15} {g.condition}")
        print(f"{len(chosen)} guards")
        return
    caught: dict[str, str] = {}
    for g in chosen:
        tests = quoting_tests(g)
        if tests:
            status, failed = pytest([g], tests)
            if status:
                caught[g.name] = failed[0] if failed else "?"
                print(f"caught  {g.name}: {caught[g.name]}", flush=True)
    left = [g for g in chosen if g.name not in caught]
    if left:
        print(f"{len(left)} guards not caught by the tests that quote them: the whole suite "
              "with all of them disabled", flush=True)
        _, failed = pytest(left, [], whole=True)
        for g in left:
            if failed:
                status, one = pytest([g], failed)
                if status:
                    caught[g.name] = one[0] if one else "?"
                    print(f"caught  {g.name}: {caught[g.name]}", flush=True)
                    continue
            print(f"MISSED  {g.name} ({g.shape}): {g.condition}", flush=True)
    print(f"\n{len(caught)} of {len(chosen)} guards caught")


if __name__ == "__main__":
    main()
