"""A drawing's puzzle chosen with foresight (most candidates never built) is the one the full
search chooses, building every candidate: over the shipped drawings and random outlines, the
same cell, level and pieces, or the same refusal. And what ``foresee`` reads from a level
holds for every puzzle the full search builds: its piece count exactly, its smallest piece's
size and width as upper bounds."""

from __future__ import annotations

import functools
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st

from weavecut.errors import WeaveCutError
from weavecut.mesh_io import read_valid_mesh
from weavecut.puzzle import workshop
from weavecut.puzzle.foresight import foresee
from weavecut.readers.outline_mesh import mesh_outline
from weavecut.validation import check_layout

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = [ROOT / "templates" / "recipes" / "heart.svg", ROOT / "examples" / "heart.svg",
           ROOT / "examples" / "star.svg", ROOT / "examples" / "plate.dxf"]


def chosen(read_at, size, frame_width, thickness, foresight):
    """(cell, level, the pieces as WKB) or the refusal's message."""
    try:
        cell, level, puzzle = workshop.drawing_defaults(read_at, size, frame_width, thickness,
                                                        foresight=foresight)
    except WeaveCutError as exc:
        return str(exc)
    return cell, level, tuple(shapely.to_wkb(puzzle.pieces))


def same_choice(monkeypatch, read_at, size, frame_width, thickness) -> int:
    """Both searches choose alike; every puzzle the full one builds is as foreseen. The
    number of puzzles the full search built."""
    built = []
    build = workshop.build_puzzle

    def recorded(hierarchy, *args):
        puzzle = build(hierarchy, *args)
        built.append((foresee(hierarchy[-1].mesh, size, frame_width), puzzle))
        return puzzle

    monkeypatch.setattr(workshop, "build_puzzle", recorded)
    full = chosen(read_at, size, frame_width, thickness, False)
    for seen, puzzle in built:
        across, width = workshop.piece_sizes(puzzle)
        assert seen.pieces == puzzle.n_pieces
        assert seen.across >= across.min() and seen.width >= width.min(), (seen, across.min(),
                                                                            width.min())
    n_full = len(built)
    assert chosen(read_at, size, frame_width, thickness, True) == full
    return n_full


@pytest.mark.slow
@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
@pytest.mark.parametrize("size, thickness", [(500.0, 3.0), (300.0, 4.0)])
def test_the_shipped_drawings_get_the_full_searchs_choice(monkeypatch, path, size, thickness):
    @functools.cache
    def read_at(cell):  # as the puzzle command reads a drawing
        return check_layout(read_valid_mesh(path, runs=True, cell=cell), "the puzzle",
                            connected=True)

    same_choice(monkeypatch, read_at, size, 20.0, thickness)  # the star: none builds


@st.composite
def outlines(draw) -> shapely.Polygon:
    """A star-shaped outline, 60-140 mm across: 5-12 corners at random radii and turns."""
    n = draw(st.integers(5, 12))
    radii = np.array(draw(st.lists(st.floats(0.55, 1.0), min_size=n, max_size=n)))
    turns = np.sort(np.array(draw(st.lists(st.floats(0.0, 0.8), min_size=n, max_size=n))))
    angles = 2 * math.pi * (np.arange(n) + turns) / n
    across = draw(st.floats(60.0, 140.0))
    xy = across / 2 * radii[:, None] * np.column_stack([np.cos(angles), np.sin(angles)])
    return shapely.Polygon(xy)


@pytest.mark.slow
@settings(max_examples=8, deadline=None)
@given(outline=outlines(), size=st.sampled_from([200.0, 350.0, 500.0]),
       thickness=st.sampled_from([2.0, 3.0, 6.0]), frame_width=st.sampled_from([12.0, 20.0]))
def test_a_random_outline_gets_the_full_searchs_choice(outline, size, thickness, frame_width):
    @functools.cache
    def read_at(cell):
        return check_layout(mesh_outline(outline, "hex", cell, runs=True), "the puzzle",
                            connected=True)

    with pytest.MonkeyPatch.context() as monkeypatch:
        monkeypatch.setattr(workshop, "DEFAULT_FACES", (40, 20, 10, 5, 3))
        try:
            read_at(None)
        except WeaveCutError:
            return  # an outline the reader refuses: no defaults to choose
        same_choice(monkeypatch, read_at, size, frame_width, thickness)
