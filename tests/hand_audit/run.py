"""The hand audit: plausible bugs a developer could write, kept as patches, and whether the
suite catches each (README, "Mutation testing").

Two sets of patches: ``audit/`` holds the hand audit proper (20 bugs written over the
products without looking at which tests exist, the README's figure); ``planted/`` the bugs
planted once to watch the virtual assembly, the writers' hole, the kit page's links and the
figures' units tests fail (each caught by the test written for it).

Each ``NN-name.patch`` starts with a header (``area:``, ``bug:``, ``tests:``, the tests
that guard that code, space-separated pytest paths or node ids) followed by a unified diff
against ``src/``. For each patch this copies ``src/`` to a temporary folder, applies the patch
there (the worktree is never touched), runs the named tests against the copy and reports
caught (a test failed) or missed. Run it from the repository's root::

    python tests/hand_audit/run.py                    # every patch of both sets
    python tests/hand_audit/run.py audit              # the hand audit only
    python tests/hand_audit/run.py audit/03 planted/1 # the patches whose paths start so
    python tests/hand_audit/run.py --all-tests audit/17   # a missed bug, whole suite

It is not collected by pytest (no test_ prefix): each patch costs one pytest run.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def header(patch: Path) -> dict[str, str]:
    """The ``key: value`` lines before the diff."""
    out = {}
    for line in patch.read_text(encoding="utf-8").splitlines():
        if line.startswith(("diff ", "--- ")):
            break
        key, sep, value = line.partition(":")
        if sep and key.strip() in ("area", "bug", "tests"):
            out[key.strip()] = value.strip()
    return out


def name(patch: Path) -> str:
    return f"{patch.parent.name}/{patch.name}"


def run(patch: Path, all_tests: bool) -> tuple[bool, str]:
    """(caught, the last lines pytest printed) for one patch."""
    info = header(patch)
    with tempfile.TemporaryDirectory(prefix="hand-audit-") as tmp:
        src = Path(tmp) / "src"
        shutil.copytree(ROOT / "src", src, ignore=shutil.ignore_patterns("__pycache__"))
        applied = subprocess.run(["patch", "-p1", "--batch", "--quiet", "-d", tmp,
                                  "-i", str(patch)], capture_output=True, text=True)
        if applied.returncode:
            raise SystemExit(f"{patch.name}: does not apply\n{applied.stdout}{applied.stderr}")
        tests = ["tests"] if all_tests else info["tests"].split()
        env = {**os.environ, "PYTHONPATH": str(src), "PYTHONDONTWRITEBYTECODE": "1"}
        done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:randomly",
                               "-p", "no:cacheprovider", *(["-n", "2"] if all_tests else []),
                               *tests], cwd=ROOT, env=env, capture_output=True, text=True)
    tail = "\n".join(done.stdout.strip().splitlines()[-3:])
    if done.returncode not in (0, 1):
        raise SystemExit(f"{patch.name}: pytest could not run (status {done.returncode})\n"
                         f"{done.stdout[-2000:]}{done.stderr[-2000:]}")
    return done.returncode == 1, tail


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("only", nargs="*", help="run the patches whose paths (audit/NN-...) "
                        "start so")
    parser.add_argument("--all-tests", action="store_true",
                        help="run the whole suite instead of each patch's tests")
    args = parser.parse_args()
    patches = sorted(p for p in HERE.glob("*/*.patch")
                     if not args.only or any(name(p).startswith(o) for o in args.only))
    areas: dict[tuple[str, str], list[int]] = {}
    for p in patches:
        patch, info = p, header(p)
        hit, tail = run(patch, args.all_tests)
        area = areas.setdefault((p.parent.name, info.get("area", "?")), [0, 0])
        area[0] += hit
        area[1] += 1
        first = next((line for line in tail.splitlines() if line.startswith("FAILED")), "")
        print(f"{'caught' if hit else 'MISSED'}  {name(patch)}: {info.get('bug', '')}"
              + (f"\n        {first}" if first else ""), flush=True)
    for group in sorted({g for g, _ in areas}):
        mine = {a: cn for (g, a), cn in areas.items() if g == group}
        print(f"\n{group}: {sum(c for c, _ in mine.values())} of "
              f"{sum(n for _, n in mine.values())} caught; "
              + ", ".join(f"{a} {c}/{n}" for a, (c, n) in sorted(mine.items())))


if __name__ == "__main__":
    main()
