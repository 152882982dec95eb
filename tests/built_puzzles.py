"""Pentagon puzzles (and their paint) built once per process, for the tests that check what is
made from a puzzle (cuts, guides, frame parts, the summary) rather than the pieces or the paint
themselves. Under mutmut the main process builds them during its stats run, before it forks a
child per mutant, so a child tests its mutant without rebuilding the puzzle; the tests that
guard ``build_puzzle`` and ``colour_puzzle`` call them in the test (tests/puzzle/
test_puzzle_oracles.py, test_colouring_recount.py)."""

from __future__ import annotations

from functools import lru_cache

from weavecut import inputs
from weavecut.puzzle.colouring import Colouring, colour_puzzle, palette_names
from weavecut.puzzle.pieces import Puzzle, build_puzzle
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette


@lru_cache(maxsize=None)
def pentagon_puzzle(levels: int, size: float = 300.0) -> Puzzle:
    """The puzzle of the built-in pentagon at ``levels``, ``size`` mm diagonal."""
    return build_puzzle(subdivide(inputs.get("pentagon"), levels), size=size)


@lru_cache(maxsize=None)
def pentagon_paint(levels: int, size: float = 300.0) -> Colouring:
    """Its paint in the "puzzle" palette, with the palette's family names."""
    pal = palette("puzzle")
    return colour_puzzle(pentagon_puzzle(levels, size), pal, palette_names("puzzle", pal))


@lru_cache(maxsize=None)
def heart_puzzle() -> tuple[Puzzle, Colouring]:
    """The heart-puzzle recipe's puzzle (templates/recipes/heart-puzzle.toml: heart.svg in
    39 mm cells, level 2, 30 cm wide, a 15 mm frame) and its paint."""
    from pathlib import Path

    from weavecut.mesh_io import read_valid_mesh

    svg = Path(__file__).parents[1] / "templates" / "recipes" / "heart.svg"
    puzzle = build_puzzle(subdivide(read_valid_mesh(str(svg), cell=39.0, runs=True), 2),
                          size=300.0, frame_width=15.0, measure="width")
    pal = palette("puzzle")
    return puzzle, colour_puzzle(puzzle, pal, palette_names("puzzle", pal))
