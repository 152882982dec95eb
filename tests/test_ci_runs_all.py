"""CI runs every test: `make test` leaves out the tests marked ``slow`` and `make test-slow`
runs just those, so `.ci/run` must run both (and the two selections must cover the suite)."""

from __future__ import annotations

import os
import re
import shlex
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _recipe(target: str) -> str:
    """The one command line of ``target`` in the Makefile, with ``$(PYTEST)`` spelled out."""
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    pytest_line = re.search(r"^PYTEST := (.+)$", makefile, re.M).group(1)
    lines = re.search(rf"^{target}: .*\n((?:\t.*\n)+)", makefile, re.M).group(1).splitlines()
    assert len(lines) == 1, lines
    return lines[0].strip().replace("$(PYTEST)", pytest_line)


def test_make_test_and_test_slow_select_the_two_halves_of_the_suite():
    """Planted: `make test-slow` with ``-m "not slow"``, or `make test` without ``-m``."""
    quick, slow = (shlex.split(_recipe(t)) for t in ("test", "test-slow"))
    assert quick[-2:] == ["-m", "not slow"] and slow[-2:] == ["-m", "slow"]
    assert quick[:-2] == slow[:-2] and "pytest" in quick


def test_make_test_latest_runs_the_two_halves_with_the_newest_releases():
    """make's own dry run of `make test-latest` (its recursive make runs under ``-n`` too):
    the pytest lines of `make test` and `make test-slow`, in that order, with .venv-latest's
    python, and no install from the lock. Planted: the suite unsplit in one pytest line;
    ``STAMP=`` left out (the lock installed into .venv-latest first)."""
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL")}
    dry = subprocess.run(["make", "-n", "--no-print-directory", "test-latest"], cwd=ROOT,
                         env=env, capture_output=True, text=True, check=True).stdout
    runs = [shlex.split(line) for line in dry.splitlines() if " -m pytest " in line]
    latest = ".venv-latest/bin/python"
    assert runs == [shlex.split(_recipe(t).replace("$(PY)", latest))
                    for t in ("test", "test-slow")]
    assert not [line for line in dry.splitlines() if " install " in line and "-c " in line]


def test_ci_runs_the_quick_and_the_slow_tests():
    """The last command of .ci/run makes both targets and keeps going after a failure, so a
    failing quick test still lets the slow ones report. Planted: ``make test`` alone."""
    last = (ROOT / ".ci" / "run").read_text(encoding="utf-8").strip().splitlines()[-1]
    words = shlex.split(last)
    assert words[0] == "make" and "--keep-going" in words
    assert {"test", "test-slow"} <= set(words[1:])
