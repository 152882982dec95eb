"""Redraw the README's images (``make docs``).

Every image is the Drawing a weave-cut command makes (run in this process, its files caught
before they are written), rasterised at a width fit for a README; a LightBurn project is drawn
by its independent reader instead (lbrnts's SVG of the written .lbrn2, rasterised by
rsvg-convert: ``tests/lightburn``, installed with ``npm ci --prefix tests/lightburn``). The PNG records a digest of
that Drawing (``drawing-sha256``: geometry, styles, layers and sizes, rounded to 0.1 µm, not
the metadata), so ``tests/test_docs.py`` can tell, without drawing a pixel, when the code
draws an image differently from the picture in the README.

    python docs/make_docs.py [IMAGE ...]      # all images, or the ones named (paths)
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import hashlib
import shlex
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from weavecut import __version__, export
from weavecut.cli import cli
from weavecut.export import png
from weavecut.fileio import write_atomic
from weavecut.layout.drawing import Drawing

ROOT = Path(__file__).resolve().parents[1]


@dataclass(frozen=True)
class Image:
    """``args`` make the file ``caught`` (``{out}`` is a scratch folder); its sheet ``sheet``
    becomes a PNG ``width`` pixels wide (a .lbrn2 as lbrnts draws it)."""

    args: tuple[str, ...]
    caught: str
    width: int
    sheet: int = 0


HEART_PUZZLE = ("puzzle", "templates/recipes/heart.svg", "--cell", "39mm", "-n", "2", "--size",
                "30cm", "--frame", "15mm", "--material", "birch-plywood-3mm", "--numbers",
                "--mode", "shared", "-o", "{out}")  # the heart-puzzle recipe

IMAGES = {
    "docs/pentagon-level4.png": Image(
        ("subdivide", "pentagon", "-n", "4", "--earlier-levels", "-o", "{out}/p.svg"),
        "p.svg", 480),
    "docs/square-grid-weaving.png": Image(
        ("figure", "square-grid-weaving", "-o", "{out}/f.svg"), "f.svg", 560),
    "examples/previews/voronoi-level3.png": Image(
        ("subdivide", "examples/voronoi-patch.json", "-n", "3", "-o", "{out}/v.svg"),
        "v.svg", 320),
    "examples/previews/voronoi-weave-level2.png": Image(
        ("weave", "examples/voronoi-patch.json", "-n", "2", "--outline-level", "1",
         "--palette", "okabe-ito", "-o", "{out}/w.svg"), "w.svg", 320),
    "examples/previews/house-weave-level2.png": Image(
        ("weave", "examples/house.obj", "-n", "2", "--style", "ribbons", "--crossings",
         "-o", "{out}/h.svg"), "h.svg", 320),
    "examples/previews/heart-weave-level2.png": Image(
        ("weave", "examples/heart.svg", "--cell", "10mm", "-n", "2", "--outline-level", "1",
         "-o", "{out}/h.svg"), "h.svg", 320),
    "examples/previews/star-weave-level2.png": Image(
        ("weave", "examples/star.svg", "-n", "2", "--outline-level", "1", "--palette", "puzzle",
         "-o", "{out}/s.svg"), "s.svg", 320),
    "examples/previews/tiles-level2.png": Image(
        ("subdivide", "examples/tiles.svg", "-n", "2", "-o", "{out}/t.svg"), "t.svg", 320),
    "examples/previews/star-paper-model.png": Image(
        ("strands", "examples/star.svg", "--cell", "10mm", "-n", "1", "--tile-size", "21mm",
         "-o", "{out}/s.svg"), "s.svg", 331),
    "docs/scheme-weaves.png": Image(
        ("figure", "scheme-weaves", "-o", "{out}/s.svg"), "s.svg", 800),
    "docs/square-grid-paper-model.png": Image(
        ("strands", "square-grid", "-o", "{out}/s.svg"), "s.svg", 360),
    "docs/ball-assembly.png": Image(
        ("strands", "dodecahedron", "-n", "1", "--project", "sphere", "--size", "12cm",
         "-o", "{out}/b.svg"), "b.svg", 360),
    "docs/ball-strips.png": Image(
        ("strands", "dodecahedron", "-n", "1", "--project", "sphere", "--size", "12cm",
         "-o", "{out}/b.svg"), "b.svg", 360, sheet=1),
    "docs/puzzle-front.png": Image(
        ("puzzle", "--mode", "shared", "-o", "{out}"), "puzzle-front-guide.svg", 520),
    "docs/puzzle-back.png": Image(
        ("puzzle", "--mode", "shared", "-o", "{out}"), "puzzle-back-guide.svg", 520),
    "docs/puzzle-colour-key.png": Image(
        ("puzzle", "--mode", "shared", "-o", "{out}"), "puzzle-front-guide-a4.pdf", 420),
    "docs/puzzle-split-sheet.png": Image(
        ("puzzle", "--mode", "separate", "--sheet", "600x400mm", "--numbers", "-o", "{out}"),
        "puzzle-separate-sheet-1.dxf", 520),
    "examples/previews/heart-puzzle-front.png": Image(
        HEART_PUZZLE, "puzzle-front-guide.svg", 400),
    "examples/previews/heart-puzzle-cut.png": Image(HEART_PUZZLE, "puzzle-shared-cut.dxf", 400),
    "docs/lightburn-heart.png": Image(
        (*HEART_PUZZLE, "--formats", "lbrn2"), "puzzle-shared-cut.lbrn2", 480),
    "docs/puzzle-closeup.png": Image(
        ("figure", "jigsaw-closeup", "-o", "{out}/j.svg"), "j.svg", 640),
}


def drawing(image: Image) -> Drawing:
    """The sheet of ``image`` as its command draws it now (nothing is written but scratch)."""
    whole = _run(image.args)[image.caught]
    return dataclasses.replace(whole, sheets=(whole.sheets[image.sheet],), metadata=())


@functools.lru_cache(maxsize=None)
def _run(args: tuple[str, ...]) -> dict[str, Drawing]:
    """The Drawings a command writes, by file name (commands that make two images run once);
    the laser settings a project is written with go to ``JOBS[args]``."""
    caught: dict[str, Drawing] = {}
    with tempfile.TemporaryDirectory() as out, contextlib.chdir(ROOT), \
            _catch(caught, JOBS.setdefault(args, {})):
        argv = [a.format(out=out) for a in args]
        cli.main(args=["-q", *argv], prog_name="weave-cut", standalone_mode=False)
    return caught


JOBS: dict[tuple[str, ...], dict] = {}


@contextlib.contextmanager
def _catch(caught: dict[str, Drawing], jobs: dict):
    """``export.write`` keeps the Drawing (and the LaserJob) by file name instead of writing
    it."""
    write = export.write

    def keep(d, path, file_format=None, job=None):
        caught[Path(path).name] = d
        jobs[Path(path).name] = job

    export.write = keep
    try:
        yield
    finally:
        export.write = write


def digest(drawing: Drawing) -> str:
    """SHA-256 of everything a Drawing draws: title, sheets, layers, shapes and styles, floats
    rounded to 4 decimals (0.1 µm) so the digest does not hang on the last bit."""
    h = hashlib.sha256()
    _feed(h, dataclasses.replace(drawing, metadata=()))
    return h.hexdigest()


def _feed(h, value) -> None:
    if dataclasses.is_dataclass(value):
        h.update(type(value).__name__.encode())
        for f in dataclasses.fields(value):
            _feed(h, getattr(value, f.name))
    elif isinstance(value, np.ndarray):
        a = np.round(value, 4) + 0.0 if value.dtype.kind == "f" else value
        h.update(f"{a.dtype.kind}{a.shape}".encode() + np.ascontiguousarray(a).tobytes())
    elif isinstance(value, (tuple, list)):
        h.update(b"(")
        for item in value:
            _feed(h, item)
        h.update(b")")
    elif isinstance(value, float):
        h.update(f"{value:.4f}".encode())
    else:
        h.update(repr(value).encode())


def make(path: str) -> None:
    image = IMAGES[path]
    d = drawing(image)
    sheet = d.sheets[0]
    if image.caught.endswith(".lbrn2"):
        data = _lbrnts_png(d, JOBS[image.args][image.caught], image.width)
    else:
        data = png.render(d, dpi=image.width / (sheet.width / 25.4))
    command = "weave-cut " + shlex.join(a.format(out=".") for a in image.args)
    write_atomic(ROOT / path, png.with_text(data, [
        ("generator", f"weave-cut {__version__}"), ("command", command),
        ("drawing-sha256", digest(d))]))
    print(f"{path}: {command}")


def _lbrnts_png(d: Drawing, job, width: int) -> bytes:
    """The LightBurn project of ``d`` as lbrnts draws it (its SVG), rasterised by rsvg-convert."""
    with tempfile.TemporaryDirectory() as tmp:
        project, picture = Path(tmp) / "p.lbrn2", Path(tmp) / "p.svg"
        export.write(d, project, job=job)
        reader = ROOT / "tests" / "lightburn"
        subprocess.run(["node", str(reader / "read.mjs"), "--svg", str(project), str(picture)],
                       check=True, cwd=reader)
        return subprocess.run(["rsvg-convert", "-w", str(width), str(picture)], check=True,
                              capture_output=True).stdout


if __name__ == "__main__":
    for name in sys.argv[1:] or IMAGES:
        make(name)
