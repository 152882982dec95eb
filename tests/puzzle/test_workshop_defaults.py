"""The cell and level chosen for a drawing, and the larger cell the small-pieces warning names,
checked by building every candidate apart from the code: of the candidates tried, the puzzle
with the most pieces that keeps every piece comfortable, else the coarsest. An 80 mm square
with a short list of face counts keeps it to a few small puzzles."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import pytest
import shapely

from weavecut.errors import MeshError, TurnedOverError, WeaveCutError
from weavecut.mesh_geometry import signed_areas
from weavecut.puzzle import workshop
from weavecut.puzzle.frame_size import extent
from weavecut.puzzle.pieces import build_puzzle
from weavecut.readers.outline_mesh import mesh_outline
from weavecut.subdivision import subdivide

SQUARE = shapely.box(0.0, 0.0, 80.0, 80.0)
FACES = (40, 14, 5)


@lru_cache(maxsize=None)
def read_at(cell):
    """The square meshed with ``cell`` (the same Mesh for the same cell)."""
    return mesh_outline(SQUARE, "hex", cell, runs=True)


def _candidates(size, levels):
    """(cell, level, puzzle or None) of every candidate, built one by one; None where it has
    too many pieces for its room."""
    mesh = read_at(None)
    area = float(np.abs(signed_areas(mesh)).sum())  # the square's 6400 mm², as meshed
    assert area == pytest.approx(SQUARE.area, rel=1e-6)
    wide = float(np.ptp(mesh.vertices[:, 0]))
    out = []
    for level in levels:
        for faces in FACES:
            cell = round(math.sqrt(area / faces), 1)
            hierarchy = subdivide(read_at(cell), level)
            room = area * (size / wide) ** 2 / (hierarchy[-1].mesh.n_faces / 2)
            puzzle = (build_puzzle(hierarchy, size, 12.0, "width")
                      if room >= workshop.MIN_MEAN_AREA else None)
            out.append((cell, level, puzzle))
    return out


@pytest.mark.parametrize("thickness", [2.0, 4.0, 40.0])
def test_drawing_defaults_choose_the_most_pieces_that_stay_comfortable(thickness, monkeypatch):
    monkeypatch.setattr(workshop, "DEFAULT_FACES", FACES)
    monkeypatch.setattr(workshop, "DEFAULT_LEVELS", (2,))
    size = 240.0
    cell, level, puzzle = workshop.drawing_defaults(read_at, size, 12.0, thickness)
    built = [(c, lv, p) for c, lv, p in _candidates(size, (2,)) if p is not None]
    assert built
    good = [(c, lv, p) for c, lv, p in built if workshop.comfortable(p, thickness)]
    if good:
        best = max(good, key=lambda t: t[2].n_pieces)
        assert (cell, level, puzzle.n_pieces) == (best[0], best[1], best[2].n_pieces)
        assert workshop.comfortable(puzzle, thickness)
    else:  # none comfortable: the coarsest built
        assert (cell, level) == built[-1][:2] and puzzle.n_pieces == built[-1][2].n_pieces
    assert extent(puzzle.outer, "width") == pytest.approx(size, abs=0.01)
    assert puzzle.frame_width == 12.0 and puzzle.measure == "width" and puzzle.levels == level


def test_drawing_defaults_try_the_levels_given(monkeypatch):
    monkeypatch.setattr(workshop, "DEFAULT_FACES", FACES[1:])
    cell, level, _ = workshop.drawing_defaults(read_at, 240.0, 12.0, 2.0, (2,))
    assert level == 2 and cell in [c for c, _, _ in _candidates(240.0, (2,))]


@pytest.mark.parametrize("error, why", [
    (TurnedOverError, r" \(its pentagons turn over at every one: sharp corners do this; use "
                      r"--mesh tri\)"),
    (MeshError, "")])
def test_drawing_defaults_refuse_a_drawing_no_cell_can_make(error, why, monkeypatch):
    """Every cell tried fails (pentagons that turn over, or slivers): one line that says why
    where it knows."""
    monkeypatch.setattr(workshop, "DEFAULT_FACES", FACES[1:])

    def failing(cell):
        if cell is None:
            return read_at(None)
        raise error("this cell fails")

    with pytest.raises(WeaveCutError, match=r"^no cell and level tried makes a puzzle of this "
                                            rf"drawing at 240 mm{why}; give --cell and --levels "
                                            r"to try others$"):
        workshop.drawing_defaults(failing, 240.0, 12.0, 2.0, (2,))


def test_drawing_defaults_pass_over_a_cell_that_fails_to_the_next(monkeypatch):
    """The finest cell makes slivers (a MeshError): the next coarser cells are still tried, and
    the choice is the one made without the failing cell."""
    monkeypatch.setattr(workshop, "DEFAULT_FACES", FACES)
    finest = round(math.sqrt(SQUARE.area / FACES[0]), 1)

    def slivers_at_the_finest(cell):
        if cell is not None and abs(cell - finest) < 0.05:
            raise MeshError("sliver faces")
        return read_at(cell)

    cell, level, _ = workshop.drawing_defaults(slivers_at_the_finest, 240.0, 12.0, 2.0, (2,))
    monkeypatch.setattr(workshop, "DEFAULT_FACES", FACES[1:])
    assert (cell, level) == workshop.drawing_defaults(read_at, 240.0, 12.0, 2.0, (2,))[:2]


def test_drawing_defaults_build_nothing_with_too_many_pieces_for_the_room(monkeypatch):
    """At 40 mm every candidate has less than MIN_MEAN_AREA per piece (recounted here): none
    is built, so the drawing is refused."""
    monkeypatch.setattr(workshop, "DEFAULT_FACES", FACES)
    wide = float(np.ptp(read_at(None).vertices[:, 0]))
    for faces in FACES:
        n = subdivide(read_at(round(math.sqrt(SQUARE.area / faces), 1)), 2)[-1].mesh.n_faces
        assert SQUARE.area * (40.0 / wide) ** 2 / (n / 2) < workshop.MIN_MEAN_AREA
    with pytest.raises(WeaveCutError, match=r"^no cell and level tried makes a puzzle of this "
                                            r"drawing at 40 mm; give --cell"):
        workshop.drawing_defaults(read_at, 40.0, 12.0, 2.0, (2,))


def test_the_larger_cell_named_is_the_smallest_step_that_is_comfortable():
    """A square meshed in 18 mm cells makes pieces too small at 240 mm: the cell named is the
    first of 18 mm x CELL_STEPS (rounded to 0.1 mm) whose puzzle keeps every piece
    comfortable, and the warning names it."""
    size, thickness = 240.0, 2.0
    small = build_puzzle(subdivide(read_at(18.0), 2), size, 12.0, "width")
    assert not workshop.comfortable(small, thickness)
    expected = None
    for step in workshop.CELL_STEPS:
        cell = round(18.0 * step, 1)
        if workshop.comfortable(build_puzzle(subdivide(read_at(cell), 2), size, 12.0, "width"),
                                thickness):
            expected = cell
            break
    assert expected == 22.5
    assert workshop.larger_good_cell(small, thickness, read_at, 18.0) == expected
    lines = workshop.size_warnings(small, thickness, read_at, 18.0)
    assert lines[-1] == f"at this size, --cell {expected:g}mm keeps every piece above both limits"
    # no cell given: the warning names no cell; a thickness nothing suits: no cell either
    assert "--cell" not in workshop.size_warnings(small, thickness)[-1]
    assert workshop.larger_good_cell(small, 40.0, read_at, 18.0) is None


def test_size_warnings_count_the_small_and_the_narrow_pieces():
    small = build_puzzle(subdivide(read_at(14.0), 2), 240.0, 12.0, "width")
    across, width = workshop.piece_sizes(small)
    thickness = 2.0
    lines = workshop.size_warnings(small, thickness)
    n = small.n_pieces
    expected = []
    if (across < 15.0).any():
        expected.append(f"{int((across < 15.0).sum())} of {n} pieces are smaller than 15 mm "
                        f"across (smallest {across.min():.1f} mm)")
    if (width < 3 * thickness).any():
        expected.append(f"{int((width < 3 * thickness).sum())} of {n} pieces are narrower than "
                        f"3 x {thickness:g} mm material (narrowest {width.min():.1f} mm)")
    assert expected and lines[:-1] == expected
    assert lines[-1] == ("no level keeps every piece above both limits at this size; use a "
                         "larger --size")
