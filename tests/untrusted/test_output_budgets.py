"""Outputs with a bound: files, pages, pixels and bytes are counted before the work and refused
in one line with the numbers, before any file is written; the memory guard and the writers
heed the process's own limits (``ulimit -v``, ``ulimit -f``) and the free disk space.

The refused inputs would take minutes and gigabytes if they were not refused (1.3 million
tiles, 8,066 pages, a 3.6 GB picture): the real process limits of the subprocess tests hold
them, and every refusal is also checked at its bound, where one more file, page or pixel
tips it over."""

from __future__ import annotations

import os
import re
import resource
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import weavecut
from weavecut import budget
from weavecut.analysis import deepzoom as dz
from weavecut.errors import ExportError, TooLargeError
from weavecut.export import png
from weavecut.layout import tiling
from weavecut.layout.drawing import Drawing, Layer, Polylines, Sheet
from weavecut.manifest import MANIFEST

from .helpers import files_under, refused, run

GIB = 1 << 30


# -- the reported cases ----------------------------------------------------------------------

@pytest.mark.parametrize("args, needles", [
    # 1.3 million tile files; they were being written one by one
    (["levels", "pentagon", "--levels", "3", "--size", "16384", "--tile-size", "16", "--tiles",
      "{d}/t"], ["16,384 x 15,741 px pyramid in 16-pixel tiles makes 1,343,546 files",
                 "at most 100,000", "--tile-size"]),
    # a kilometre-wide weave tiled on A4: 20 million pages (8 mm margins, which save pages)
    (["weave", "square-grid", "--levels", "2", "--size", "999999mm", "-o", "{d}/x.pdf"],
     ["1,000,019 x 1,000,019 mm drawing 1:1 on 210 x 297 mm paper makes 20,060,585 pages",
      "at most 500", "--page"]),
    # 20 m: 8,066 pages (about a minute of clipping, and an 11 MB file)
    (["weave", "square-grid", "--levels", "2", "--size", "20m", "-o", "{d}/x.pdf"],
     ["20,020 x 20,020 mm", "makes 8,066 pages; at most 500"]),
    (["subdivide", "pentagon", "--size", "20m", "-o", "{d}/x.pdf"], ["pages; at most 500"]),
    (["weave", "square-grid", "--levels", "2", "--size", "20m", "--page", "a3", "-o",
      "{d}/x.pdf"], ["on 297 x 420 mm paper", "pages; at most 500"]),
])
def test_reported_outputs_are_refused_before_any_file(tmp_path, args, needles):
    _one_line(_limited(tmp_path, [a.format(d=tmp_path) for a in args]), *needles)
    assert files_under(tmp_path) == set()


# -- tile pyramids: files, file size, disk --------------------------------------------------

PYRAMID = ["levels", "pentagon", "--levels", "2", "--size", "70", "--tile-size", "16", "-j", "1"]


def test_pyramid_files_counted_to_the_file(tmp_path, monkeypatch):
    """At exactly the limit the pyramid is written, and has that many files; one fewer
    allowed and nothing is written."""
    files = dz.pyramid_files(70, 67, 16)
    monkeypatch.setattr(budget, "MAX_FILES", files - 1)
    refused(run(*PYRAMID, "--tiles", tmp_path / "no"), f"makes {files:,} files",
            f"at most {files - 1:,}")
    assert not (tmp_path / "no").exists()
    monkeypatch.setattr(budget, "MAX_FILES", files)
    assert run(*PYRAMID, "--tiles", tmp_path / "yes").exit_code == 0
    assert len(files_under(tmp_path / "yes") - {MANIFEST}) == files


@given(width=st.integers(1, 3000), height=st.integers(1, 3000),
       tile=st.sampled_from([16, 17, 100, 256, 4096]))
def test_pyramid_files_are_the_tiles_of_every_level(width, height, tile):
    sizes = dz.pyramid_sizes(width, height)
    assert dz.pyramid_files(width, height, tile) == 1 + sum(
        len(dz.tile_rects(w, h, tile)) for w, h in sizes)


@given(width=st.integers(1, 300), height=st.integers(1, 300))
def test_png_bound_holds_for_noise(width, height):
    """The bound is for any pixels; random ones do not compress."""
    rgb = np.random.default_rng(width * 1000 + height).integers(0, 256, (height, width, 3),
                                                                dtype=np.uint8)
    assert len(png.with_text(_png(rgb), [])) <= dz.png_bound(width, height)


def _png(rgb):
    from weavecut.analysis.levels import png_bytes

    return png_bytes(rgb)


def test_pyramid_larger_than_the_free_disk_is_refused(tmp_path, monkeypatch):
    class Usage:
        free = 100_000

    monkeypatch.setattr(budget.shutil, "disk_usage", lambda path: Usage)
    pixels = sum(w * h for w, h in dz.pyramid_sizes(70, 67))
    files = dz.pyramid_files(70, 67, 16)
    refused(run(*PYRAMID, "--tiles", tmp_path / "t"),
            f"a 70 x 67 px pyramid in 16-pixel tiles ({files} files) takes about "
            f"{pixels + 4096 * files:,} bytes on disk; 100,000 bytes is free in {tmp_path}")
    assert files_under(tmp_path) == set()


# -- printer pages ----------------------------------------------------------------------------

def _sheet(width: float, height: float) -> Sheet:
    line = Polylines(np.array([[0.0, 0.0], [width, height]]), np.array([0, 2]))
    return Sheet(width, height, (Layer("cut", "cut", (line,)),))


@given(sizes=st.lists(st.tuples(st.floats(10, 1500), st.floats(10, 1500)), min_size=1,
                      max_size=3),
       limit=st.integers(1, 12))
def test_pages_are_counted_before_tiling_to_the_page(sizes, limit):
    """Refused exactly when the pages it would make are more than the limit, and the
    message gives their number."""
    drawing = Drawing(tuple(_sheet(w, h) for w, h in sizes), "t")
    pages = len(tiling.on_pages(drawing, (210.0, 297.0)).sheets)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(budget, "MAX_PAGES", limit)
        if pages <= limit:
            assert len(tiling.on_pages(drawing, (210.0, 297.0)).sheets) == pages
            return
        with pytest.raises(TooLargeError, match=f"makes {pages:,} pages; at most {limit}"):
            tiling.on_pages(drawing, (210.0, 297.0))


def test_tiling_alone_is_bounded(monkeypatch):
    """The puzzle's painting guides call ``tile`` directly."""
    monkeypatch.setattr(tiling, "_clip_layer", lambda *a: pytest.fail("tiled anyway"))
    with pytest.raises(TooLargeError, match="makes 8,066 pages; at most 500"):
        tiling.tile(Drawing((_sheet(20020, 20020),), "t"))


# -- PNG pixels and memory --------------------------------------------------------------------

def test_stacked_png_sheets_are_bounded(monkeypatch):
    """Every sheet fits, the stack does not: refused before any is drawn."""
    drawing = Drawing((_sheet(100, 100),) * 3, "t")  # 590 px square each, 10 px apart
    monkeypatch.setattr(png, "MAX_PIXELS", 590 * (3 * 590 + 20))
    assert len(png.render(drawing)) > 0
    monkeypatch.setattr(png, "MAX_PIXELS", 590 * (3 * 590 + 20) - 1)
    monkeypatch.setattr(png, "_sheet", lambda *a: pytest.fail("drawn anyway"))
    with pytest.raises(ExportError, match=r"3 sheets at 150 dpi stacked are too large for PNG "
                                          r"\(590 x 1790 px\)"):
        png.render(drawing)


def test_png_memory_is_checked_before_drawing(monkeypatch):
    monkeypatch.setattr(budget, "available_memory", lambda: 200 << 20)
    monkeypatch.setattr(budget, "address_space_room", lambda: None)
    monkeypatch.setattr(png, "_sheet", lambda *a: pytest.fail("drawn anyway"))
    with pytest.raises(TooLargeError, match=r"a 5905 x 5905 px PNG needs about 1.1 GiB of "
                                            r"memory; 200 MiB is available"):
        png.render(Drawing((_sheet(1000, 1000),), "t"))


# -- the memory guard: the lower of free memory and the address-space room ------------------

@pytest.mark.parametrize("free, room, expect", [
    (8 * GIB, None, (8 * GIB, "is available")),
    (8 * GIB, GIB, (GIB, "is left under this process's address-space limit (ulimit -v)")),
    (GIB, 8 * GIB, (GIB, "is available")),
])
def test_memory_limit_is_the_lower_one_and_says_which(monkeypatch, free, room, expect):
    monkeypatch.setattr(budget, "available_memory", lambda: free)
    monkeypatch.setattr(budget, "address_space_room", lambda: room)
    assert budget.memory_limit() == expect


def test_address_space_room_reads_the_limit_and_the_mapped_memory(monkeypatch):
    monkeypatch.setattr(budget.resource, "getrlimit", lambda _: (4 * GIB, 8 * GIB))
    status = Path("/proc/self/status").read_text()
    mapped = {k: int(re.search(rf"^{k}:\s+(\d+) kB", status, re.M).group(1)) * 1024
              for k in ("VmSize", "VmRSS")}
    room = budget.address_space_room()
    # the process's mapping changes a little between the two reads
    assert abs(room - (4 * GIB - mapped["VmSize"] + mapped["VmRSS"])) < 64 << 20
    monkeypatch.setattr(budget.resource, "getrlimit",
                        lambda _: (budget.resource.RLIM_INFINITY,) * 2)
    assert budget.address_space_room() is None


# -- the process's own limits, for real ------------------------------------------------------

def _limited(tmp_path, args, **limits) -> subprocess.CompletedProcess:
    """``weave-cut ARGS`` in ``tmp_path`` under the given resource limits (bytes), stopped
    with its worker processes after two minutes (what is refused takes far longer)."""
    def apply():
        for name, value in limits.items():
            resource.setrlimit(getattr(resource, f"RLIMIT_{name}"), (value, value))

    env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1",
           "PYTHONPATH": str(Path(weavecut.__file__).parents[1]),  # this weavecut, from anywhere
           "OPENBLAS_NUM_THREADS": "1"}  # its buffers per core would count against ulimit -v
    with subprocess.Popen([sys.executable, "-m", "weavecut", *args], cwd=tmp_path, env=env,
                          preexec_fn=apply, start_new_session=True, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True) as proc:
        try:
            out, err = proc.communicate(timeout=120)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
            pytest.fail(f"not refused: weave-cut {' '.join(args)} still ran after 120 s")
    return subprocess.CompletedProcess(proc.args, proc.returncode, out, err)


def _one_line(proc, *needles) -> str:
    assert proc.returncode == 1, (proc.returncode, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("Error: "), proc.stderr
    for needle in needles:
        assert needle in lines[0], (needle, lines[0])
    return lines[0]


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="reads /proc")
@pytest.mark.parametrize("args, needles", [
    # a hierarchy of 2.3 GiB
    (["stats", "pentagon", "--levels", "10", "--json"],
     ["level 10 has 9,765,625 faces and needs about 2.3 GiB", "level 9 would fit"]),
    # a 16,384-pixel level image
    (["levels", "pentagon", "--levels", "9", "--size", "16384", "-o", "x.png"], ["level 9"]),
    # the PNG writer: 3.6 GB peak for an 11,338-pixel picture
    (["weave", "square-grid", "--levels", "2", "--size", "1900mm", "-o", "x.png"],
     ["a 11338 x 11338 px PNG needs about 3.8 GiB"]),
])
def test_address_space_limit_is_heeded(tmp_path, args, needles):
    proc = _limited(tmp_path, args, AS=GIB)
    _one_line(proc, *needles, "left under this process's address-space limit (ulimit -v)")
    assert files_under(tmp_path) == set()


@pytest.mark.parametrize("args, needles", [
    # a tile of 4,096 pixels may take 50 MB: refused before the first tile
    (["levels", "pentagon", "--levels", "3", "--size", "8192", "--tile-size", "4096",
      "--tiles", "t"], ["a 4096 x 4096 px tile can take up to 50,361,346 bytes",
                        "file-size limit (ulimit -f) of 1,048,576 bytes", "--tile-size"]),
    # one file: refused before the temporary file is made
    (["subdivide", "pentagon", "--levels", "7", "-o", "x.svg"],
     ["x.svg takes", "file-size limit (ulimit -f) of 1,048,576 bytes"]),
])
def test_file_size_limit_is_heeded(tmp_path, args, needles):
    _one_line(_limited(tmp_path, args, FSIZE=1 << 20), *needles)
    assert files_under(tmp_path) == set()


def test_file_size_limit_lets_what_fits_through(tmp_path):
    proc = _limited(tmp_path, ["subdivide", "pentagon", "--levels", "2", "-o", "x.svg"],
                    FSIZE=1 << 20)
    assert proc.returncode == 0, proc.stderr
    assert files_under(tmp_path) == {"x.svg", MANIFEST}
