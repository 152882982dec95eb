"""Same input, same bytes, on every machine: no BLAS or LAPACK in weave-cut's arithmetic, and a
fixed set of commands (``determinism_run.py``) writing byte-identical files under several
OpenBLAS kernels and thread counts, and with numpy's AVX-512 loops off where the CPU has them."""

from __future__ import annotations

import ast
import hashlib
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from numpy._core import _multiarray_umath as umath

from weavecut import numeric
from weavecut.surface import circumsphere

SRC = Path(__file__).resolve().parents[1] / "src" / "weavecut"
RUNNER = Path(__file__).with_name("determinism_run.py")

# numpy calls that reach BLAS or LAPACK (whose kernels differ between CPUs), and shapely's
# affinity module, which multiplies with np.matmul
BLAS_CALLS = {"dot", "matmul", "inner", "vdot", "tensordot", "outer", "kron", "einsum",
              "multi_dot", "polyfit", "cov", "corrcoef", "lstsq"}
LINALG = {"lstsq", "solve", "inv", "svd", "eig", "eigh", "eigvals", "eigvalsh", "det", "pinv",
          "qr", "cholesky", "slogdet", "matrix_power", "matrix_rank", "norm"}


def blas_uses(text: str) -> list[tuple[int, str]]:
    """(line, what) of every use of a BLAS or LAPACK entry point in Python source ``text``:
    the ``@`` operator, ``np.dot``-like calls, ``np.linalg`` (but ``norm`` along an axis, which
    numpy computes elementwise) and ``shapely.affinity``."""
    found = []
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.BinOp, ast.AugAssign)) and isinstance(node.op, ast.MatMult):
            found.append((node.lineno, "@"))
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
            name, owner = node.func.attr, node.func.value
            in_linalg = isinstance(owner, ast.Attribute) and owner.attr == "linalg"
            if in_linalg and name in LINALG and not (
                    name == "norm" and any(k.arg == "axis" for k in node.keywords)):
                found.append((node.lineno, f"linalg.{name}"))
            elif name in BLAS_CALLS and not in_linalg and not (
                    isinstance(owner, ast.Name) and owner.id == "numeric"):
                found.append((node.lineno, name))
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names = [a.name for a in node.names] + [getattr(node, "module", None) or ""]
            if any("affinity" in n for n in names):
                found.append((node.lineno, "shapely.affinity"))
    return sorted(found)


def test_the_scanner_finds_every_kind_of_blas_use():
    text = ("import numpy as np\nfrom shapely import affinity\n"
            "a = x @ y\nb = np.dot(x, y)\nc = np.linalg.svd(x)\nd = np.linalg.norm(v)\n"
            "e = np.linalg.norm(v, axis=1)\nf = np.einsum('ij,ij->i', x, y)\nx @= y\n"
            "g = numeric.dot(x, y)\n")
    assert [w for _, w in blas_uses(text)] == [
        "shapely.affinity", "@", "dot", "linalg.svd", "linalg.norm", "einsum", "@"]
    assert [n for n, _ in blas_uses(text)] == [2, 3, 4, 5, 6, 8, 9]


@pytest.mark.parametrize("path", sorted(SRC.rglob("*.py")), ids=lambda p: str(p.relative_to(SRC)))
def test_no_blas_or_lapack_in_the_code(path):
    uses = blas_uses(path.read_text(encoding="utf-8"))
    assert not uses, (f"{path.relative_to(SRC)}: {uses}: BLAS/LAPACK results differ between "
                      "CPUs; use weavecut.numeric (matmul, dot, transform, solve)")


@given(st.integers(1, 6), st.integers(1, 4), st.integers(1, 4), st.integers(0, 2**32 - 1))
def test_matmul_is_numpys_product(n, k, m, seed):
    rng = np.random.default_rng(seed)
    a, b, v = rng.normal(size=(n, k)), rng.normal(size=(k, m)), rng.normal(size=k)
    np.testing.assert_allclose(numeric.matmul(a, b), a @ b, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(numeric.matmul(a, v), a @ v, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(numeric.matmul(v, b), v @ b, rtol=1e-12, atol=1e-12)
    stacked = rng.normal(size=(3, n, k))
    np.testing.assert_allclose(numeric.matmul(stacked, b), stacked @ b, rtol=1e-12, atol=1e-12)


@given(st.floats(-360, 360), st.floats(0.1, 10), st.tuples(st.floats(-1e3, 1e3),
                                                          st.floats(-1e3, 1e3)),
       arrays(np.float64, (5, 2), elements=st.floats(-1e3, 1e3)))
def test_affine_maps_and_inverses(angle, scale, shift, xy):
    m = numeric.affine(angle, shift, scale)
    moved = numeric.transform(m)(xy)
    a = np.radians(angle)
    expected = scale * np.column_stack([np.cos(a) * xy[:, 0] - np.sin(a) * xy[:, 1],
                                        np.sin(a) * xy[:, 0] + np.cos(a) * xy[:, 1]]) + shift
    np.testing.assert_allclose(moved, expected, atol=1e-9)
    np.testing.assert_allclose(numeric.transform(numeric.affine_inverse(m))(moved), xy,
                               atol=1e-9)


@given(st.integers(1, 6), st.integers(0, 2**32 - 1))
def test_solve_agrees_with_lapack(n, seed):
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, n)) + n * np.eye(n)
    b = rng.normal(size=n)
    np.testing.assert_allclose(numeric.solve(a, b), np.linalg.solve(a, b), rtol=1e-9, atol=1e-9)


@given(arrays(np.float64, st.integers(2, 30), elements=st.floats(-1e3, 1e3)),
       st.floats(-10, 10), st.floats(-10, 10), st.integers(0, 2**32 - 1))
def test_line_fit_is_numpys_polyfit(x, slope, intercept, seed):
    if np.ptp(x) < 1e-3:
        return  # no line through points of one x
    y = slope * x + intercept + np.random.default_rng(seed).normal(size=len(x))
    np.testing.assert_allclose(numeric.line_fit(x, y), np.polyfit(x, y, 1), rtol=1e-7, atol=1e-7)


def test_solve_refuses_a_singular_system():
    with pytest.raises(ValueError, match="singular"):
        numeric.solve([[1.0, 2.0], [2.0, 4.0]], [1.0, 2.0])


@given(arrays(np.float64, 3, elements=st.floats(-1e4, 1e4)), st.floats(1e-2, 1e3),
       st.integers(0, 2**32 - 1))
def test_circumsphere_finds_a_known_sphere(centre, radius, seed):
    rng = np.random.default_rng(seed)
    d = rng.normal(size=(40, 3))
    points = centre + radius * d / np.linalg.norm(d, axis=1)[:, None]
    c, r = circumsphere(points)
    np.testing.assert_allclose(c, centre, atol=1e-6 * (radius + np.abs(centre).max()))
    assert r == pytest.approx(radius, rel=1e-6)


def test_snap_keys_ignore_last_bit_noise_but_not_a_real_difference():
    x = np.array([100.0, 0.1 + 0.2, 1e4 / 3])
    noisy = x * (1 + 4 * np.finfo(float).eps)
    assert (numeric.snap(noisy) == numeric.snap(x)).all()
    assert (numeric.snap(x + 10 * numeric.GRID) != numeric.snap(x)).all()


# OpenBLAS kernels and threads, as differing machines would choose them ("unset": the kernel
# OpenBLAS picks for this CPU); every command of determinism_run.py must write the same bytes
# under each. Three runs, each on its own kernel, that between them differ in every setting:
# kernel, 1 or 2 threads, and numpy's own SIMD loops (arctan2, arccos, exp, ...), which differ
# between CPUs with and without AVX-512: on a machine that has it, the last run is one without
# (AVX2 only). An output that depends on any one setting differs between two of the runs. (Six
# runs, every kernel with every thread count, cost twice the time and catch nothing these miss:
# the planted dependences the docstring of test_same_bytes_... names fail with these three.)
_AVX512 = [f for f in umath.__cpu_dispatch__
           if (f == "X86_V4" or f.startswith("AVX512")) and umath.__cpu_features__.get(f)]
NO_AVX512 = "-no-avx512" if _AVX512 else ""
KERNELS = {"unset-2-threads": {"OPENBLAS_CORETYPE": None, "OPENBLAS_NUM_THREADS": "2"},
           "haswell-1-thread": {"OPENBLAS_CORETYPE": "Haswell", "OPENBLAS_NUM_THREADS": "1"},
           "prescott-2-threads" + NO_AVX512: {
               "OPENBLAS_CORETYPE": "Prescott", "OPENBLAS_NUM_THREADS": "2",
               "NPY_DISABLE_CPU_FEATURES": " ".join(_AVX512) or None}}


def _run(name: str, settings: dict, root: Path) -> tuple[dict, dict]:
    """(file -> sha256, what ran it) of determinism_run.py's outputs under ``settings``."""
    env = {k: v for k, v in os.environ.items() if k not in settings}
    env.update({k: v for k, v in settings.items() if v is not None})
    out = root / name
    done = subprocess.run([sys.executable, str(RUNNER), str(out)], env=env, text=True,
                          capture_output=True, timeout=600)
    assert done.returncode == 0, f"{name}: {done.stderr[-3000:]}"
    digests = {str(p.relative_to(out)): hashlib.sha256(p.read_bytes()).hexdigest()
               for p in sorted(out.rglob("*")) if p.is_file()}
    return digests, json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_same_bytes_under_every_blas_kernel_and_thread_count(tmp_path):
    """Planted, each caught: a file that records the last bits of ``np.dot`` of two 100 000
    long vectors (OpenBLAS's kernel and threads), or of ``np.sin`` summed over them (numpy's
    AVX-512 loops)."""
    with ThreadPoolExecutor(2) as pool:  # two subprocesses at a time: the machine's cores
        runs = dict(zip(KERNELS, pool.map(lambda k: _run(k, KERNELS[k], tmp_path), KERNELS)))
    ran = {k: {(b["architecture"], b["num_threads"]) for b in info["blas"]}
           for k, (_, info) in runs.items()}
    # the settings took effect: otherwise the comparison below would prove nothing
    assert all(ran[k] for k in ran), f"numpy uses no OpenBLAS here: {ran}"
    assert len({frozenset(a for a, _ in v) for v in ran.values()}) >= 2, ran
    assert {t for v in ran.values() for _, t in v} >= {1, 2}, ran
    if _AVX512:
        assert not set(_AVX512) & set(runs["prescott-2-threads-no-avx512"][1]["simd"])
        assert set(_AVX512) <= set(runs["unset-2-threads"][1]["simd"])
    first, (files, _) = next(iter(runs.items()))
    assert len(files) >= 15
    for name, (other, _) in runs.items():
        assert other.keys() == files.keys(), name
        differ = sorted(f for f in files if files[f] != other[f])
        assert not differ, (f"{differ} differ between {first} ({sorted(ran[first])}) and "
                            f"{name} ({sorted(ran[name])})")


@given(st.integers(3, 8), st.floats(0.0, 0.3), st.integers(0, 2**32 - 1))
def test_plane_normals_are_the_least_squares_planes(k, bend, seed):
    rng = np.random.default_rng(seed)
    turn = np.linalg.qr(rng.normal(size=(3, 3)))[0]  # a random plane in space
    flat = np.column_stack([rng.normal(size=(k, 2)), bend * rng.normal(size=k)])
    x = flat @ turn.T
    x -= x.mean(axis=0)
    svd_normal = np.linalg.svd(x)[2][2]
    start = svd_normal + 0.2 * rng.normal(size=3)  # a rough guess on the right side
    if start @ svd_normal < 0.5 or np.linalg.svd(x)[1][1] < 1e-3:
        return  # not a guess near the answer, or no plane: nothing to compare
    n = numeric.plane_normals(x[None], start[None])[0]
    assert abs(np.linalg.norm(n) - 1) < 1e-12
    assert np.linalg.norm(n - svd_normal) < 1e-6
