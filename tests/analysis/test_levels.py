"""The level image and the windowed refinement behind deep zooms."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut import inputs
from weavecut.analysis import levels as lv
from weavecut.errors import WeaveCutError


def _as_set(points):
    return np.unique(np.ascontiguousarray(points).view(np.complex128).ravel())


def _assert_window_exact(mesh, levels, window, **options):
    grid = lv.Grid.fit(window, 1)
    full = list(lv.refine_full(mesh, levels, **options))
    windowed = list(lv.refine_window(mesh, levels, window, **options))
    assert len(windowed) == levels + 1
    for t, (a, b) in enumerate(zip(full, windowed)):
        expected, got = _as_set(a[grid.inside(a)]), _as_set(b)
        assert len(got) == len(b), f"level {t}: duplicate vertices"
        assert np.array_equal(expected, got), f"level {t}: {len(expected)} vs {len(got)}"
    return windowed


@pytest.mark.parametrize("window", [(0.2, 0.1, 0.4, 0.3), (-0.1, -0.1, 0.1, 0.1),
                                    (-0.95, -0.85, -0.6, -0.5)])
def test_windowed_refinement_equals_full_inside_window_level8(window):
    """Bit-for-bit equal vertex sets at every level 0..8 (including one window on the boundary
    and one around the fixed centre)."""
    windowed = _assert_window_exact(inputs.get("pentagon"), 8, window)
    assert len(windowed[-1]) > 1000


@pytest.mark.parametrize("spec,options", [
    ("square-grid:3x3", {}), ("tiling-8-4:2x2", {"centre": "area"}),
    ("triangulated-ngon:8", {"chirality": "right"}), ("pentagon", {"smooth": False})])
def test_windowed_refinement_other_inputs_level7(spec, options):
    _assert_window_exact(inputs.get(spec), 7, (0.1, -0.3, 0.5, 0.1), **options)


@settings(max_examples=10, deadline=None)
@given(st.floats(-1.0, 0.8), st.floats(-0.9, 0.8), st.floats(0.02, 0.4))
def test_windowed_refinement_random_windows(x0, y0, side):
    _assert_window_exact(inputs.get("pentagon"), 6, (x0, y0, x0 + side, y0 + side))


def test_window_clear_of_the_mesh_yields_nothing():
    _assert_window_exact(inputs.get("pentagon"), 6, (0.75, 0.75, 1.0, 1.0))


def test_too_small_halo_is_refused_not_silently_wrong():
    with pytest.raises(WeaveCutError, match="not exact"):
        list(lv.refine_window(inputs.get("pentagon"), 6, (0.2, 0.1, 0.4, 0.3), halo=0.0))


def test_windowed_image_equals_full_image_crop():
    mesh = inputs.get("pentagon")
    full, grid = lv.level_image(mesh, 7, 400)
    # a window made of whole pixels of the full grid
    x0, _, _, y1 = grid.window
    c0, r0, n = 150, 120, 80
    window = (x0 + c0 * grid.pixel, y1 - (r0 + n) * grid.pixel,
              x0 + (c0 + n) * grid.pixel, y1 - r0 * grid.pixel)
    part, sub = lv.level_image(mesh, 7, n, window)
    assert part.shape == (n, n)
    crop = full[r0:r0 + n, c0:c0 + n]
    # pixels away from the window's edge (where float rounding of the two grids can differ)
    assert np.array_equal(part[1:-1, 1:-1], crop[1:-1, 1:-1])
    assert (part != lv.UNSET).sum() > 0.5 * n * n


@pytest.mark.parametrize("spec", ["pentagon", "tiling-8-4", "triangulated-ngon:24"])
def test_level0_image_marks_exactly_the_input_vertex_pixels(spec):
    mesh = inputs.get(spec)
    image, grid = lv.level_image(mesh, 0, 257)
    x0, _, _, y1 = grid.window
    cols = np.floor((mesh.vertices[:, 0] - x0) / grid.pixel).astype(int)
    rows = np.floor((y1 - mesh.vertices[:, 1]) / grid.pixel).astype(int)
    expected = np.full(image.shape, lv.UNSET, dtype=np.uint8)
    expected[rows, cols] = 0
    assert np.array_equal(image, expected)


def test_levels_only_get_later_and_fill_the_pentagon():
    mesh = inputs.get("pentagon")
    img5, _ = lv.level_image(mesh, 5, 128)
    img7, _ = lv.level_image(mesh, 7, 128)
    set5 = img5 != lv.UNSET
    assert np.array_equal(img7[set5], img5[set5])   # a pixel's level never changes later
    assert (img7 != lv.UNSET).sum() > (img5 != lv.UNSET).sum()
    assert set(np.unique(img7[img7 != lv.UNSET])) == set(range(8))


def test_png_round_trip(tmp_path):
    from PIL import Image

    image, _ = lv.level_image(inputs.get("pentagon"), 4, 64)
    rgb = lv.colour(image)
    path = tmp_path / "levels.png"
    lv.write_png(path, rgb)
    back = np.asarray(Image.open(path).convert("RGB"))
    assert np.array_equal(back, rgb)
    assert lv.png_bytes(rgb) == path.read_bytes()
    assert tuple(rgb[image == lv.UNSET][0]) == lv.BACKGROUND
