"""What a maker needs beside the cut files: the material, checks of the puzzle against it, the
summary, and the workshop folder's README.txt."""

from __future__ import annotations

import math
import textwrap
from collections.abc import Callable

import numpy as np
import shapely

from ..layout.lasersetup import ROLES, material  # noqa: F401 (the puzzle's API)
from .colouring import Colouring
from .files import TRAVEL_SPEED, CutResult
from .foresight import foresee
from ..errors import MeshError, TurnedOverError, WeaveCutError
from ..mesh import Mesh
from ..mesh_geometry import signed_areas
from ..subdivision import Hierarchy, subdivide
from ..text import counted
from .frame_size import diameter, extent
from .workshop_readme import frame_text, readme  # noqa: F401 (the puzzle's API)
from .pieces import KIND_NAMES, OCTAGON, Puzzle, build_puzzle

MIN_ACROSS = 15.0  # mm: a piece smaller than this is fiddly to hold and easy to lose
MIN_WIDTH_X_THICKNESS = 3.0  # a piece narrower than 3x the material thickness breaks
DEFAULT_LEVELS = (3, 2)  # levels tried for a drawing, highest first
DEFAULT_FACES = (40, 28, 20, 14, 10, 7, 5, 4, 3)  # faces of the meshed outline tried, most first
CELL_STEPS = (1.25, 1.5, 1.75, 2.0, 2.5, 3.0)  # larger cells tried for a drawing's warning
MIN_MEAN_AREA = 1.5 * MIN_ACROSS ** 2  # mm²: fewer, larger pieces are tried without building
NO_TOUCHING = "no two different paints touch on the front"  # so no smallest difference


def piece_sizes(puzzle: Puzzle) -> tuple[np.ndarray, np.ndarray]:
    """(P,) twice: every piece's size across (its largest corner distance) and its width (the
    narrow side of its minimum rotated rectangle), mm."""
    coords, index = shapely.get_coordinates(puzzle.pieces, return_index=True)
    counts = np.bincount(index, minlength=puzzle.n_pieces)
    corners = np.full((puzzle.n_pieces, counts.max(), 2), np.nan)
    corners[index, np.arange(len(index)) - np.repeat(np.cumsum(counts) - counts, counts)] = coords
    across = np.nanmax(np.linalg.norm(corners[:, :, None] - corners[:, None], axis=3),
                       axis=(1, 2))
    rect = shapely.minimum_rotated_rectangle(puzzle.pieces)
    ring = shapely.get_coordinates(shapely.get_exterior_ring(rect)).reshape(len(rect), -1, 2)
    sides = np.linalg.norm(ring[:, 1:3] - ring[:, 0:2], axis=2)
    width = sides.min(axis=1)
    return across, width


def size_warnings(puzzle: Puzzle, thickness: float,
                  read_at: Callable[[float], Mesh] | None = None,
                  cell: float | None = None) -> list[str]:
    """Warnings when pieces are too small for the material: smaller than MIN_ACROSS mm across
    or narrower than MIN_WIDTH_X_THICKNESS x ``thickness``, naming the largest level whose
    pieces all stay above both limits and, for a drawing meshed with ``cell`` (``read_at``
    meshes it with another), the smallest of a few larger cells that does."""
    limit = MIN_WIDTH_X_THICKNESS * thickness
    out = []
    across, width = piece_sizes(puzzle)
    if across.min() < MIN_ACROSS:
        out.append(f"{int((across < MIN_ACROSS).sum())} of {puzzle.n_pieces} pieces are "
                   f"smaller than {MIN_ACROSS:g} mm across (smallest {across.min():.1f} mm)")
    if width.min() < limit:
        out.append(f"{int((width < limit).sum())} of {puzzle.n_pieces} pieces are narrower "
                   f"than 3 x {thickness:g} mm material (narrowest {width.min():.1f} mm)")
    if out:
        ok = largest_good_level(puzzle, thickness)
        fixes = [f"--levels {ok}"] if ok else []
        larger = (None if read_at is None or cell is None
                  else larger_good_cell(puzzle, thickness, read_at, cell))
        if larger:
            fixes.insert(0, f"--cell {larger:g}mm")
        out.append(f"at this size, {' or '.join(fixes)} keeps every piece above both limits"
                   if fixes else "no level keeps every piece above both limits at this size; "
                   "use a larger --size")
    return out


def largest_good_level(puzzle: Puzzle, thickness: float) -> int | None:
    """The largest level below the puzzle's whose pieces, at the same frame size, are all at
    least MIN_ACROSS across and MIN_WIDTH_X_THICKNESS x ``thickness`` wide (None: none)."""
    size = extent(puzzle.outer, puzzle.measure)
    frame_width = puzzle.frame_width
    for level in range(puzzle.levels - 1, 1, -1):  # each lower level is ~4x smaller to build
        smaller = build_puzzle(puzzle.hierarchy[:level + 1], size, frame_width, puzzle.measure)
        if comfortable(smaller, thickness):
            return level
    return None


def larger_good_cell(puzzle: Puzzle, thickness: float, read_at: Callable[[float], Mesh],
                     cell: float) -> float | None:
    """The smallest of ``cell`` x CELL_STEPS (rounded to 0.1 mm) that, at the puzzle's level
    and size, keeps every piece ``comfortable`` (None: none)."""
    size = extent(puzzle.outer, puzzle.measure)
    for step in CELL_STEPS:
        larger = round(cell * step, 1)
        try:
            bigger = build_puzzle(subdivide(read_at(larger), puzzle.levels), size,
                                  puzzle.frame_width, puzzle.measure)
        except WeaveCutError:
            continue
        if comfortable(bigger, thickness):
            return larger
    return None


def comfortable(puzzle: Puzzle, thickness: float) -> bool:
    """True when every piece is at least MIN_ACROSS across and MIN_WIDTH_X_THICKNESS x
    ``thickness`` wide."""
    across, width = piece_sizes(puzzle)
    return bool(across.min() >= MIN_ACROSS and width.min() >= MIN_WIDTH_X_THICKNESS * thickness)


def drawing_defaults(read_at: Callable[[float | None], Mesh], size: float, frame_width: float,
                     thickness: float, levels: tuple[int, ...] | None = None,
                     foresight: bool = True) -> tuple[float, int, Puzzle]:
    """``(cell, levels, puzzle)`` for a drawn outline when the user gave neither: of the
    levels DEFAULT_LEVELS (highest first; a level whose pentagons turn over is passed over)
    and the cells that mesh the outline in about DEFAULT_FACES faces, the puzzle with the
    most pieces that keeps every piece ``comfortable``; else the coarsest one tried.

    Candidates are tried finest first; at each level the first comfortable one ends the
    level. With ``foresight`` a candidate is built only where what its last level says of
    it (``foresight.foresee``) leaves it open: one whose bounds fall under the limits is
    not comfortable, one with no more pieces than the best so far cannot replace it (built
    only if a later one would, to see whether it ends the level first), and both are built
    after all, coarsest first, when none is comfortable. The choice is the same either way.

    Parameters
    ----------
    read_at : the drawing meshed with a cell (mm; None: the reader's default)
    size, frame_width : mm, as for ``build_puzzle`` (``size`` is the finished width)
    thickness : mm of material
    levels : the levels to try (default DEFAULT_LEVELS)
    foresight : False builds every candidate (what the choice is checked against)
    """
    mesh = read_at(None)
    area = float(np.abs(signed_areas(mesh)).sum())
    x0, x1 = mesh.vertices[:, 0].min(), mesh.vertices[:, 0].max()
    finished = area * (size / (x1 - x0)) ** 2  # mm² of the pieces, a little less in fact
    limit = MIN_WIDTH_X_THICKNESS * thickness
    turned = []  # a TurnedOverError seen (a cell whose pentagons turn over)
    tried: list[list] = []  # [cell, level, hierarchy, puzzle, built] in the order tried

    def build(entry: list) -> Puzzle | None:
        if not entry[4]:
            entry[3:] = [_built(entry[2], size, frame_width, turned), True]
        return entry[3]

    best = None
    deepest: dict[float, Hierarchy] = {}  # a cell's levels, reused for any lower level
    for level in levels or DEFAULT_LEVELS:
        unsure = []  # this level's candidates passed over for their count
        for faces in DEFAULT_FACES:
            cell = round(math.sqrt(area / faces), 1)
            try:
                if len(deepest.get(cell, ())) <= level:
                    deepest[cell] = subdivide(read_at(cell), level)
            except TurnedOverError:
                turned.append(cell)  # at this level and cell; a coarser cell may do
                continue
            except (MeshError, shapely.errors.GEOSException):
                continue  # this cell makes sliver faces or pieces that cross themselves
            hierarchy = deepest[cell][:level + 1]
            if finished / (hierarchy[-1].mesh.n_faces / 2) < MIN_MEAN_AREA:
                continue  # far too many pieces for their room
            entry = [cell, level, hierarchy, None, False]
            tried.append(entry)
            if foresight:
                seen = foresee(hierarchy[-1].mesh, size, frame_width)
                if seen.across < MIN_ACROSS or seen.width < limit:
                    continue  # not comfortable: wanted only if none is
                if best is not None and seen.pieces <= best[2].n_pieces:
                    unsure.append(entry)
                    continue
            puzzle = build(entry)
            if puzzle is not None and comfortable(puzzle, thickness):
                if not any(build(e) is not None and comfortable(e[3], thickness)
                           for e in unsure):  # else the full search stopped there
                    if best is None or puzzle.n_pieces > best[2].n_pieces:
                        best = (cell, level, puzzle)
                break  # coarser cells only give fewer pieces
    if best is not None:
        return best
    for entry in reversed(tried):  # none comfortable: the coarsest that builds
        if build(entry) is not None:
            return entry[0], entry[1], entry[3]
    why = (" (its pentagons turn over at every one: sharp corners do this; use --mesh tri)"
           if turned else "")
    raise WeaveCutError(f"no cell and level tried makes a puzzle of this drawing at "
                        f"{size:g} mm{why}; give --cell and --levels to try others")


def _built(hierarchy: Hierarchy, size: float, frame_width: float, turned: list
           ) -> Puzzle | None:
    """The puzzle of a candidate; None where it cannot be cut (slivers, pieces that cross
    themselves, pentagons that turn over: noted in ``turned``)."""
    try:
        puzzle = build_puzzle(hierarchy, size, frame_width, "width")
    except TurnedOverError:
        turned.append(hierarchy)
        return None
    except (MeshError, shapely.errors.GEOSException):
        return None
    return puzzle if shapely.is_valid(puzzle.pieces).all() else None


def summary(puzzle: Puzzle, results: dict[str, CutResult], speed: float,
            colouring: Colouring | None = None) -> dict:
    """Pieces by type and size, frame, paints, cut length, sheets and time per mode."""
    counts = {name: int((puzzle.kinds == k).sum()) for k, name in enumerate(KIND_NAMES)}
    across, width = piece_sizes(puzzle)
    out = {"levels": puzzle.levels, "pieces": int(puzzle.n_pieces), "pieces_by_type": counts,
           "piece_across_mm": [round(float(across.min()), 1), round(float(across.max()), 1)],
           "piece_width_min_mm": round(float(width.min()), 1),
           "ring_hexagons_in_frame": int(len(puzzle.ring)),
           "frame_diagonal_mm": round(diameter(puzzle.outer), 2),
           "frame_measure": puzzle.measure,
           "frame_mm": [round(v, 1) for v in np.subtract(puzzle.outer.bounds[2:],
                                                         puzzle.outer.bounds[:2]).tolist()],
           "speed_mm_s": speed, "modes": {}}
    if colouring is not None:
        out["front_colours"] = len(colouring.front_colours)
        out["back_colours"] = len(colouring.back_colours)
        smallest = colouring.smallest_difference
        out["smallest_delta_e"] = None if smallest is None else round(smallest, 2)
        if smallest is None:
            out["smallest_delta_e_reason"] = NO_TOUCHING
        out["single_coloured_pieces"] = int(((colouring.front[:, 0] == colouring.front[:, 1])
                                             & (puzzle.kinds == OCTAGON)).sum())
    for mode, r in results.items():
        seconds = r.cut_length / speed + r.travel_length / TRAVEL_SPEED
        out["modes"][mode] = {"cut_length_m": round(r.cut_length / 1000, 3),
                              "travel_m": round(r.travel_length / 1000, 3),
                              "paths": r.n_paths, "sheets": r.n_sheets,
                              "time_min": round(seconds / 60, 1),
                              "layers": running_order(r.drawing)}
    return out


def summary_text(info: dict) -> str:
    """The summary as a few readable lines."""
    kinds = ", ".join(counted(n, k) for k, n in info["pieces_by_type"].items())
    lo, hi = info["piece_across_mm"]
    lines = [info["chosen"]["text"]] if "chosen" in info else []
    lines += [f"level {info['levels']} puzzle: {counted(info['pieces'], 'piece')} ({kinds}), {lo:g}-{hi:g} "
              f"mm across, narrowest {info['piece_width_min_mm']:g} mm; "
              f"{info['ring_hexagons_in_frame']} ring hexagons stay in the frame",
              f"frame: {frame_text(info)}" + (f", in {info['frame_parts']} dovetailed parts"
                                                if info.get("frame_parts", 1) > 1 else "")]
    if "material" in info:
        lines.append(f"material: {info['material']}, kerf {info['kerf_mm']:g} mm, sheet "
                     f"{info['sheet_mm'][0]:g} x {info['sheet_mm'][1]:g} mm")
    if "front_colours" in info:
        differ = (NO_TOUCHING if info["smallest_delta_e"] is None else
                  f"touching colours differ by CIEDE2000 >= {info['smallest_delta_e']:g}")
        lines.append(f"paints: front {info['front_colours']}, back {info['back_colours']}; "
                     f"{differ}; "
                     f"{counted(info['single_coloured_pieces'], 'single-coloured piece')} on the front")
    for mode, m in info["modes"].items():
        lines.append(f"{mode}: cut {m['cut_length_m']:.2f} m in {m['paths']} paths, travel "
                     f"{m['travel_m']:.2f} m, {counted(m['sheets'], 'sheet')}, about {m['time_min']:g} min "
                     f"at {info['speed_mm_s']:g} mm/s")
    if "files" in info:
        lines.append("files: " + ", ".join(info["files"]))
    return "\n".join(lines)


def running_order(drawing) -> list[str]:
    """The names of ``drawing``'s laser layers on any sheet, in the order they run: by role
    (engrave, score, cut: ``lasersetup.ROLES``), then in the drawing's order."""
    found = {layer.name: layer.role for sheet in drawing.sheets for layer in sheet.layers
             if layer.role in ROLES and layer.shapes}
    return sorted(found, key=lambda name: ROLES.index(found[name]))
