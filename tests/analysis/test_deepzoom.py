"""The DeepZoom pyramid: tiles rendered on their own equal the single image, lower levels are
the level image at half resolution, the files are what a viewer reads."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from PIL import Image

from weavecut import inputs
from weavecut.analysis import deepzoom as dz
from weavecut.analysis import levels as lv
from weavecut.cli import main


def _read(folder, level, shape, tile):
    """The pyramid level as one RGB array, from its tiles (checking every tile's size)."""
    h, w = shape
    out = np.zeros((h, w, 3), dtype=np.uint8)
    for c, r, tw, th in dz.tile_rects(w, h, tile):
        rgb = np.asarray(Image.open(folder / f"levels_files/{level}/{c // tile}_{r // tile}.png")
                         .convert("RGB"))
        assert rgb.shape == (th, tw, 3)
        out[r:r + th, c:c + tw] = rgb
    return out


@pytest.mark.parametrize("window", [None, (0.1, -0.3, 0.45, 0.1)])
def test_stitched_tiles_equal_the_single_image_at_every_level(tmp_path, window):
    mesh = inputs.get("pentagon")
    image, grid = lv.level_image(mesh, 6, 150, window)
    summary = dz.write_pyramid(mesh, 6, grid, tmp_path, tile_size=64, jobs=1)
    sizes = dz.pyramid_sizes(grid.width, grid.height)
    assert sizes[0] == (1, 1) and sizes[-1] == (grid.width, grid.height)
    assert summary["tiles"] == sum(len(dz.tile_rects(w, h, 64)) for w, h in sizes)
    level = image
    for lev in range(len(sizes) - 1, -1, -1):
        assert np.array_equal(_read(tmp_path, lev, level.shape, 64), lv.colour(level)), lev
        level = dz.halve(level)
    root = ET.parse(tmp_path / "levels.dzi").getroot()
    ns = "{http://schemas.microsoft.com/deepzoom/2008}"
    assert root.tag == f"{ns}Image" and root.get("TileSize") == "64"
    assert root.get("Overlap") == "0" and root.get("Format") == "png"
    size = root.find(f"{ns}Size")
    assert (int(size.get("Width")), int(size.get("Height"))) == (grid.width, grid.height)


def test_half_resolution_is_the_level_image_on_the_coarser_grid():
    """The 2 x 2 minimum equals painting the same refinement on pixels twice as large."""
    mesh = inputs.get("pentagon")
    fine = lv.Grid.fit((-1.0, -1.0, 1.0, 1.0), 128)
    coarse = lv.Grid(fine.window, 64, 64, 2 * fine.pixel)
    points = list(lv.refine_full(mesh, 5))
    assert np.array_equal(dz.halve(lv.paint(fine, (0, 0, 128, 128), points)),
                          lv.paint(coarse, (0, 0, 64, 64), points))


def test_processes_write_the_same_bytes_as_one(tmp_path):
    mesh = inputs.get("tiling-8-4:2x2")
    _, grid = lv.level_image(mesh, 1, 90)
    dz.write_pyramid(mesh, 4, grid, tmp_path / "one", tile_size=32, jobs=1)
    dz.write_pyramid(mesh, 4, grid, tmp_path / "two", tile_size=32, jobs=2)
    files = sorted(p.relative_to(tmp_path / "one") for p in (tmp_path / "one").rglob("*.png"))
    assert len(files) > 10
    for f in files + [tmp_path / "one" / "levels.dzi"]:
        f = f if f.is_absolute() else tmp_path / "one" / f
        assert f.read_bytes() == (tmp_path / "two" / f.relative_to(tmp_path / "one")).read_bytes()


def test_cli_writes_a_pyramid_and_refuses_what_would_not_fit(tmp_path, capsys):
    with pytest.raises(SystemExit) as done:
        main(["levels", "pentagon", "--levels", "4", "--size", "100", "--tiles",
              str(tmp_path / "p"), "--tile-size", "32", "-j", "1"])
    assert done.value.code == 0
    assert (tmp_path / "p" / "levels.dzi").is_file()
    assert (tmp_path / "p" / "levels_files" / "0" / "0_0.png").is_file()
    for args in (["--levels", "14", "--window", "-2,-2,2,2", "-o", str(tmp_path / "z.png")],
                 ["--levels", "14", "--size", "400000", "--tiles", str(tmp_path / "q")]):
        with pytest.raises(SystemExit) as done:
            main(["levels", "pentagon", *args])
        assert done.value.code == 1
        assert "GiB of memory" in capsys.readouterr().err
    assert not (tmp_path / "z.png").exists() and not (tmp_path / "q").exists()
