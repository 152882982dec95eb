"""A CLI that answers at once: ``--help`` of the group and of every command loads none of the
heavy libraries, and a command loads its own module only. (How long that takes is measured
by benchmarks/bench_startup.py, not here.)"""

from __future__ import annotations

import pytest

from tests.fresh import modules_after

HEAVY = ("shapely", "scipy", "ezdxf", "reportlab", "PIL", "svgwrite")
COMMANDS = ("inputs", "subdivide", "stats", "weave", "puzzle", "strands", "fractal", "levels",
            "convexity", "figure", "findings", "build", "worker", "serve")


def loaded_after(*args: str) -> set[str]:
    """The modules a fresh interpreter holds after ``weave-cut ARGS``."""
    return modules_after("import contextlib, io\n"
                         "from weavecut.cli import main\n"
                         "with contextlib.redirect_stdout(io.StringIO()), "
                         "contextlib.suppress(SystemExit):\n"
                         f"    main({list(args)!r})\n")


@pytest.mark.parametrize("args", [["--help"], *([c, "--help"] for c in COMMANDS)],
                         ids=lambda a: " ".join(a))
def test_help_loads_no_heavy_library(args):
    heavy = {m.split(".")[0] for m in loaded_after(*args)} & set(HEAVY)
    assert not heavy


def test_a_command_loads_its_own_module_only():
    modules = loaded_after("weave", "--help")
    assert "weavecut.cli.weave_command" in modules
    assert not {"weavecut.cli.puzzle_command", "weavecut.cli.strands_command",
                "weavecut.cli.analysis_commands"} & modules


def test_a_whole_puzzle_loads_no_masked_arrays(tmp_path):
    """numpy.ma (15 ms) comes with a plain ``np.unique``; the puzzle's writers, its 3-D model
    included, ask for distinct values without it (``numeric.distinct``)."""
    modules = modules_after("from weavecut.cli import main\nimport contextlib\n"
                            "with contextlib.suppress(SystemExit):\n"
                            f"    main(['-q', 'puzzle', '--levels', '2', '--numbers', '-o', "
                            f"{str(tmp_path / 'pz')!r}])\n")
    assert "weavecut.export.gltf" in modules and "numpy.ma" not in modules


def _threads_after_numpy(**env: str) -> int:
    """The threads of a fresh interpreter that loaded the CLI, then numpy (OpenBLAS starts
    its pool on import), with ``env`` for OpenBLAS's own variable (absent where not given)."""
    import os
    import subprocess
    import sys

    clean = {k: v for k, v in os.environ.items()
             if k not in ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS")}
    code = ("import os, weavecut.cli, numpy\n"
            "print(len(os.listdir('/proc/self/task')))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, env={**clean, **env}).stdout
    return int(out)


@pytest.mark.skipif(not __import__("os").path.isdir("/proc/self/task"), reason="Linux only")
def test_the_cli_runs_blas_on_one_thread_unless_asked():
    """OpenBLAS's pool of a thread per core spins after each call: CPU burnt for arrays far
    too small to share. The CLI asks for one thread; a caller's own setting is kept."""
    assert _threads_after_numpy() == 1
    if (__import__("os").cpu_count() or 1) >= 2:
        assert _threads_after_numpy(OPENBLAS_NUM_THREADS="2") == 2


def test_a_paper_model_and_a_ball_load_no_masked_arrays(tmp_path):
    """numpy.ma (6 ms) comes with np.median, a plain np.unique and np.isin: the paper models
    ask numeric.median, distinct and among instead (the flower's crossings, labels, woven
    model; the ball's hull)."""
    for args in (["strands", "pentagon-flower", "--size", "23cm", "-o", "pf.pdf"],
                 ["strands", "dodecahedron", "--levels", "1", "--project", "sphere", "--size",
                  "12cm", "-o", "ball.pdf"]):
        args[-1] = str(tmp_path / args[-1])
        modules = modules_after("from weavecut.cli import main\nimport contextlib\n"
                                "with contextlib.suppress(SystemExit):\n"
                                f"    main(['-q', *{args!r}])\n")
        assert "weavecut.papermodel.book" in modules and "numpy.ma" not in modules, args
