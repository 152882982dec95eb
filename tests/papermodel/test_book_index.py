"""The strand book's small promises: the page index names runs of strips ("A1-A4, B2"), the
size figures convert between tile size, model width and strip width, thin strips warn or are
refused, module prints drop the copy letter, and the paper's presets."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from weavecut import inputs
from weavecut.papermodel.book import (
    MIN_STRIP,
    WARN_STRIP,
    SizeError,
    check_strip_width,
    preset_for,
    tile_size_for,
    tile_size_width,
)
from weavecut.papermodel.modules import plan_modules
from weavecut.papermodel.strips import octagon_size, strip_width
from weavecut.papermodel.wording import page_index
from weavecut.subdivision import subdivide
from weavecut.weave.snub_weave import snub_weaves


def _book(pages: dict[int, list[str]]):
    pieces = tuple((n, SimpleNamespace(label=label)) for n, labels in pages.items()
                   for label in labels)
    return SimpleNamespace(strip_pages=tuple(pages), pieces=pieces)


def test_page_index_joins_consecutive_strips_into_runs():
    """Whole strips in runs; a part of a split strip by itself, so page 1 says which page
    holds which part (issue 29: "A10" on p. 3 and p. 7 said neither)."""
    book = _book({3: ["A2", "A1", "A3", "A4", "B2", "X1", "A10 1/2"],
                  4: ["A10 2/2", "B9", "B10", "B11", "C1", "X2", "X3"]})
    assert page_index(book) == ("p. 3: A1-A4, A10 1/2, B2, X1; p. 4: A10 2/2, B9-B11, C1, "
                                "X2-X3")
    assert page_index(_book({5: ["AA1", "AA2", "Z3"]})) == "p. 5: AA1-AA2, Z3"
    assert page_index(_book({})) == ""


@pytest.fixture(scope="module")
def grid():
    return snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2))[-1]


def test_tile_size_and_model_width_convert_both_ways():
    wide = snub_weaves(subdivide(inputs.get("square-grid:3x2"), 2))[-1]  # wider than high
    width = float(np.ptp(wide.mesh.vertices[:, 0]))
    assert width > float(np.ptp(wide.mesh.vertices[:, 1])) * 1.2
    for tile in (12.0, 20.0, 31.5):
        model = tile_size_width(wide, tile)
        assert model == pytest.approx(tile / octagon_size(wide) * width, rel=1e-12)
        assert tile_size_for(wide, model) == pytest.approx(tile, rel=1e-12)


def test_strips_under_8_mm_are_refused_and_under_11_mm_warned(grid):
    ratio = strip_width(grid) / octagon_size(grid)
    ok = WARN_STRIP / ratio * 1.01
    assert check_strip_width(grid, ok) == (pytest.approx(ok * ratio), ())
    thin = (MIN_STRIP + WARN_STRIP) / 2 / ratio
    width, warnings = check_strip_width(grid, thin)
    assert width == pytest.approx(9.5)
    assert warnings == ("strips are 9.5 mm wide: thin strips tear easily; 11 mm or more is "
                        "easier to weave",)
    exact = MIN_STRIP / ratio  # 8 mm itself is allowed
    assert check_strip_width(grid, exact)[0] == pytest.approx(MIN_STRIP)
    need = math.ceil(MIN_STRIP / ratio * 2) / 2
    size = math.ceil(tile_size_width(grid, need) / 10)
    with pytest.raises(SizeError) as err:
        check_strip_width(grid, 6.0 / ratio)
    assert str(err.value) == (f"strips would be 6.0 mm wide and tear (paper section 5.2): "
                              f"use --tile-size {need:g}mm or more (--size {size}cm or more)")
    assert check_strip_width(grid, need)[0] >= MIN_STRIP


def test_presets_are_the_papers_two_models_and_a_default():
    assert preset_for("square-grid") == {"levels": 2, "turn": np.pi / 4,
                                         "palette": "maritime-12"}
    assert preset_for("square-grid:3x3") == preset_for("square-grid")
    assert preset_for("pentagon-flower")["levels"] == 3
    assert preset_for("pentagon-flower")["turn"] == 0.0
    other = preset_for("hex-grid:2")
    assert other == {"levels": 2, "turn": 0.0, "palette": "maritime-12"}
    other["levels"] = 9  # a copy: the defaults stay
    assert preset_for("hex-grid")["levels"] == 2


def test_plan_of_the_grid_has_four_copies_of_six(grid):
    plan = plan_modules(grid)
    assert plan.copies.shape == (4, 6) and not len(plan.extras)


def _flat_strands_jobs():
    """(recipe, job) of every shipped recipe's and example's flat paper model (not a ball)."""
    import tomllib
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    for path in sorted([*root.glob("templates/recipes/*.toml"), *root.glob("examples/*.toml")]):
        for job in tomllib.loads(path.read_text()).get("job", []):
            if job.get("command") == "strands" and "project" not in job:
                yield pytest.param(path, job, id=f"{path.stem}:{job['output']}")


@pytest.mark.parametrize("path, job", list(_flat_strands_jobs()))
def test_a_shipped_paper_model_does_not_warn_of_thin_strips(path, job):
    """Issue 29: the pentagon kit (paper, Silhouette, card) warned "strips are 11.1 mm wide"
    at every build. Every shipped flat recipe's strips are ``WARN_STRIP`` wide or more."""
    from weavecut.mesh_io import read_valid_mesh
    from weavecut.units import to_mm

    spec = job["input"]
    if spec.endswith((".svg", ".obj", ".json")):
        mesh = read_valid_mesh(str(path.parent / spec),
                               **({"cell": to_mm(job["cell"])} if "cell" in job else {}))
    else:
        mesh = inputs.get(spec)
    levels = job.get("levels", preset_for(spec)["levels"])
    weave = snub_weaves(subdivide(mesh, levels))[-1]
    tile = (to_mm(job["tile-size"]) if "tile-size" in job
            else tile_size_for(weave, to_mm(job["size"])) if "size" in job else 20.0)
    width, warnings = check_strip_width(weave, tile)
    assert warnings == () and width >= WARN_STRIP, (width, warnings)
