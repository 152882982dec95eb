"""The workshop figures a maker reads: the material, the summary, its text and README.txt.

Oracles apart from the code: pieces counted by their corners (an octagon has 8, an enneagon 9),
sizes from every corner pair, paints recounted from the colouring, times from length / speed,
and the largest good level found by building each lower level and measuring it."""

from __future__ import annotations

import itertools
from functools import lru_cache

import numpy as np
import pytest
import shapely

from weavecut import inputs, presets
from weavecut.layout.lasersetup import Operation, laser
from weavecut.puzzle import files as pf
from weavecut.puzzle import workshop
from weavecut.puzzle.colouring import UNPAINTED, colour_puzzle
from weavecut.puzzle.frame_size import diameter
from weavecut.text import counted
from weavecut.puzzle.pieces import OCTAGON, build_puzzle
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette

from tests.built_puzzles import pentagon_puzzle


@pytest.fixture(scope="module")
def hierarchy():
    return subdivide(inputs.get("pentagon"), 4)


@lru_cache(maxsize=None)
def _small():
    puzzle = pentagon_puzzle(3)
    colouring = colour_puzzle(puzzle, palette("puzzle"))
    results = {"shared": pf.shared_cut(puzzle, laser()),
               "separate": pf.separate_cut(puzzle, laser(), 0.2, (400.0, 300.0))}
    return puzzle, colouring, results


@pytest.fixture
def small():
    """A level-3 puzzle, its colouring and both cuts, made once per process: these tests
    check the summary and README made from them (the cuts and paint have their own tests)."""
    return _small()


def _summary(small) -> dict:
    """The summary at 7 mm/s (not a default), made in every test: mutmut maps a test to the
    functions it calls itself, not to what a shared fixture called."""
    puzzle, colouring, results = small
    return workshop.summary(puzzle, results, 7.0, colouring)


def test_material_reads_the_preset_in_mm(tmp_path):
    mat = workshop.material("poplar-3mm")
    doc = presets.load("materials", "poplar-3mm")
    assert mat == {"name": "poplar-3mm", "description": doc["description"], "thickness": 3.0,
                   "kerf": 0.15, "sheet": (800.0, 500.0), "cut_speed": 20.0,
                   "operations": {"cut": Operation(20.0, 100.0, 1),
                                  "score": Operation(100.0, 20.0, 1),
                                  "engrave": Operation(150.0, 15.0, 1)}}
    # a material file without a name or description is called by its path
    path = tmp_path / "own.toml"
    path.write_text('thickness = "0.4cm"\nkerf = "0.2mm"\nsheet = "300x200mm"\n'
                    "cut_speed = 12\n", encoding="utf-8")
    own = workshop.material(str(path))
    assert own["name"] == own["description"] == str(path)
    # without operation tables: the cut at cut_speed, score and engrave 5 x faster
    assert own["operations"] == {"cut": Operation(12.0, 60.0, 1),
                                 "score": Operation(60.0, 20.0, 1),
                                 "engrave": Operation(60.0, 15.0, 1)}
    named = tmp_path / "named.toml"
    named.write_text('name = "my birch"\ndescription = "birch, 4 mm"\n' + path.read_text(),
                     encoding="utf-8")
    assert (workshop.material(str(named))["name"],
            workshop.material(str(named))["description"]) == ("my birch", "birch, 4 mm")
    assert (own["thickness"], own["kerf"], own["sheet"], own["cut_speed"]) == (
        4.0, 0.2, (300.0, 200.0), 12.0)


def test_summary_counts_pieces_by_their_corners(small):
    puzzle, info = small[0], _summary(small)
    corners = shapely.get_num_coordinates(puzzle.pieces) - 1
    assert info["pieces_by_type"] == {"octagon": int((corners == 8).sum()),
                                      "enneagon": int((corners == 9).sum())}
    assert info["pieces"] == len(puzzle.pieces) == sum(info["pieces_by_type"].values())
    assert info["levels"] == 3 and info["ring_hexagons_in_frame"] == len(puzzle.ring)


def test_summary_sizes_are_measured_corner_to_corner(small):
    puzzle, info = small[0], _summary(small)
    across = [max(np.hypot(*(np.subtract(a, b))) for a, b in itertools.combinations(
        np.asarray(p.exterior.coords)[:-1], 2)) for p in puzzle.pieces]
    assert info["piece_across_mm"] == [round(min(across), 1), round(max(across), 1)]
    outer = np.asarray(puzzle.outer.exterior.coords)[:-1]
    diagonal = max(np.hypot(*(np.subtract(a, b))) for a, b in itertools.combinations(outer, 2))
    assert info["frame_diagonal_mm"] == round(diagonal, 2) == 300.0
    assert info["frame_mm"] == [round(float(np.ptp(outer[:, 0])), 1),
                                round(float(np.ptp(outer[:, 1])), 1)]
    # the narrowest piece: no piece is narrower than its width between parallel lines
    # (the narrow side of the smallest rectangle round it is at least that), none wider than
    # it is across
    widths = []
    for p in puzzle.pieces:
        hull = np.asarray(p.convex_hull.exterior.coords)
        edges = np.diff(hull, axis=0)
        normal = np.column_stack([-edges[:, 1], edges[:, 0]]) / np.hypot(*edges.T)[:, None]
        reach = (hull[:-1] @ normal.T).max(axis=0) - (hull[:-1] @ normal.T).min(axis=0)
        widths.append(reach.min())
    assert round(min(widths), 1) - 0.05 <= info["piece_width_min_mm"] <= min(across)
    assert info["piece_width_min_mm"] == round(info["piece_width_min_mm"], 1)
    assert info["piece_width_min_mm"] == pytest.approx(min(widths), abs=0.5)


def test_summary_modes_time_is_cut_over_speed_plus_travel(small):
    results, info = small[2], _summary(small)
    assert info["speed_mm_s"] == 7.0 and set(info["modes"]) == {"shared", "separate"}
    for mode, r in results.items():
        m = info["modes"][mode]
        minutes = (r.cut_length / 7.0 + r.travel_length / pf.TRAVEL_SPEED) / 60
        # the laser layers the files hold, in the order the laser runs them
        run = [name for role in ("engrave", "score", "cut") for name in dict.fromkeys(
            layer.name for sheet in r.drawing.sheets for layer in sheet.layers
            if layer.role == role)]
        assert m == {"cut_length_m": round(r.cut_length / 1000, 3),
                     "travel_m": round(r.travel_length / 1000, 3), "paths": r.n_paths,
                     "sheets": r.n_sheets, "time_min": round(minutes, 1), "layers": run}
    assert info["modes"]["shared"]["sheets"] == 1


def test_summary_paints_are_recounted_from_the_colouring(small):
    puzzle, colouring, _ = small
    info = _summary(small)
    front = {c for pair in colouring.front.tolist() for c in pair} - {UNPAINTED}
    back = set(colouring.back.tolist()) - {UNPAINTED}
    assert (info["front_colours"], info["back_colours"]) == (len(front), len(back))
    single = sum(a == b for (a, b), kind in zip(colouring.front.tolist(), puzzle.kinds.tolist())
                 if kind == OCTAGON)
    assert info["single_coloured_pieces"] == single > 0
    assert info["smallest_delta_e"] == round(colouring.smallest_difference, 2) > 0
    assert "front_colours" not in workshop.summary(puzzle, {}, 7.0)


def _info(small) -> dict:
    """The summary as the command completes it, with a split frame and a warning."""
    info = _summary(small)
    info.update(material="birch, 3 mm", kerf_mm=0.17, sheet_mm=[400.0, 300.0], frame_parts=3,
                warnings=["pieces 7, 9 are too small for 3 mm digits"],
                files=["README.txt", "puzzle-back-guide-a4.pdf", "puzzle-shared-cut.dxf"])
    return info


def test_summary_text_states_every_figure(small):
    info = _info(small)
    text = workshop.summary_text(info)
    kinds = info["pieces_by_type"]
    lo, hi = info["piece_across_mm"]
    assert text.splitlines()[0] == (
        f"level 3 puzzle: {info['pieces']} pieces ({kinds['octagon']} octagons, "
        f"{kinds['enneagon']} enneagons), {lo:g}-{hi:g} mm across, narrowest "
        f"{info['piece_width_min_mm']:g} mm; {info['ring_hexagons_in_frame']} ring hexagons "
        "stay in the frame")
    w, h = info["frame_mm"]
    assert text.splitlines()[1] == (f"frame: 300 mm diagonal, {w:g} x {h:g} mm, in 3 dovetailed "
                                    "parts")
    assert "material: birch, 3 mm, kerf 0.17 mm, sheet 400 x 300 mm" in text.splitlines()
    assert (f"paints: front {info['front_colours']}, back {info['back_colours']}; touching "
            f"colours differ by CIEDE2000 >= {info['smallest_delta_e']:g}; "
            f"{info['single_coloured_pieces']} single-coloured pieces on the front"
            in text.splitlines())
    for mode, m in info["modes"].items():
        assert (f"{mode}: cut {m['cut_length_m']:.2f} m in {m['paths']} paths, travel "
                f"{m['travel_m']:.2f} m, {counted(m['sheets'], 'sheet')}, about {m['time_min']:g} min at "
                "7 mm/s") in text.splitlines()
    assert text.splitlines()[-1] == ("files: README.txt, puzzle-back-guide-a4.pdf, "
                                     "puzzle-shared-cut.dxf")
    # a frame in one piece says nothing of parts; without material or files: pieces, frame,
    # paints and the modes
    bare = workshop.summary_text(_summary(small))
    assert bare.splitlines()[1] == f"frame: 300 mm diagonal, {w:g} x {h:g} mm"
    assert "material" not in bare and "files" not in bare
    assert len(bare.splitlines()) == 3 + len(info["modes"])
    assert workshop.summary_text({**_summary(small), "frame_parts": 1}) == bare
    two = workshop.summary_text({**_summary(small), "frame_parts": 2})
    assert two.splitlines()[1].endswith(" mm, in 2 dovetailed parts")


def test_readme_names_the_files_layers_and_figures(small):
    info = _info(small)
    text = workshop.readme(info, "letter")
    lines = text.splitlines()
    assert lines[0] == "weave-cut jigsaw puzzle: workshop folder"
    assert "Material: birch, 3 mm, kerf 0.17 mm." in lines
    w, h = info["frame_mm"]
    assert f"Frame: 300 mm diagonal, {w:g} x {h:g} mm." in lines
    lo, hi = info["piece_across_mm"]
    assert f"Pieces: {info['pieces']}, {lo:g}-{hi:g} mm across." in lines
    assert (f"Paints: {info['front_colours']} on the front, {info['back_colours']} on the back "
            "(the same paints).") in lines
    for mode, m in info["modes"].items():
        assert (f"{mode.capitalize()} cut: {counted(m['sheets'], 'sheet')}, {m['cut_length_m']:.1f} m of "
                f"cutting, about {m['time_min']:g} min at 7 mm/s.") in lines
    # the printed guides are named for the page asked for; every file is listed once
    assert "puzzle-front-guide-letter.pdf" in text and "-a4.pdf -" not in text
    files = lines[lines.index("Files:") + 1:]
    assert files == [f"  {name}" for name in info["files"]] and text.endswith("\n")
    warnings = lines[lines.index("Warnings:") + 1:lines.index("Files:")]
    assert warnings == ["  - pieces 7, 9 are too small for 3 mm digits", ""]
    # the laser layers, in the order they are cut, as the cut drawings name them
    shared = [layer.name for layer in small[2]["shared"].drawing.sheets[0].layers]
    separate = [layer.name for layer in small[2]["separate"].drawing.sheets[0].layers]
    named = [name for name in dict.fromkeys(shared + separate) if name in text]
    assert named == list(dict.fromkeys(shared + separate))
    n = info["modes"]["separate"]["sheets"]
    assert f"puzzle-separate-sheet-1{f'..{n}' if n > 1 else ''}.svg / .dxf" in text
    assert f"nested on {counted(n, 'sheet')}" in text
    assert "The frame comes in 3 parts" in text
    assert "Rerun with\n  --kerf if it differs from 0.17 mm." in text
    # without a split frame, warnings or a shared cut, the README says so
    plain = workshop.readme({**info, "frame_parts": 1, "warnings": [], "files": [],
                             "modes": {"separate": info["modes"]["separate"]}}, "a4")
    assert "The frame comes in" not in plain and "puzzle-shared-cut" not in plain
    assert "Warnings:\n  none\n" in plain


@pytest.mark.parametrize("size, frame, level, thickness, expected", [
    (500.0, 20.0, 3, 3.0, 2),   # the puzzle itself is fine: the answer is still below it
    (500.0, 60.0, 4, 7.0, 2),   # level 3 is too narrow for 21 mm with this wide frame
    (300.0, 20.0, 4, 5.0, 2),   # level 3 is large enough across but narrower than 15 mm
    (300.0, 20.0, 4, 1.0, 3),
    (150.0, 20.0, 4, 6.0, None),  # even level 2 is narrower than 18 mm
])
def test_largest_good_level_builds_and_measures_each_lower_level(hierarchy, size, frame, level,
                                                                  thickness, expected):
    puzzle = build_puzzle(hierarchy[:level + 1], size, frame)
    good = []
    for lower in range(2, level):
        across, width = workshop.piece_sizes(build_puzzle(hierarchy[:lower + 1], size, frame))
        if across.min() >= 15.0 and width.min() >= 3 * thickness:
            good.append(lower)
    assert (max(good) if good else None) == expected
    assert workshop.largest_good_level(puzzle, thickness) == expected


def test_a_piece_exactly_at_a_limit_is_good(hierarchy, monkeypatch):
    """"at least MIN_ACROSS across and MIN_WIDTH_X_THICKNESS x thickness wide": the limits
    themselves pass (measured on level 2 as it is rebuilt: at the frame's measured size)."""
    puzzle = build_puzzle(hierarchy[:4], 300.0)
    lower = build_puzzle(hierarchy[:3], diameter(puzzle.outer), puzzle.frame_width)
    across, width = workshop.piece_sizes(lower)
    monkeypatch.setattr(workshop, "MIN_ACROSS", float(across.min()))
    monkeypatch.setattr(workshop, "MIN_WIDTH_X_THICKNESS", float(width.min()))
    assert workshop.largest_good_level(puzzle, 1.0) == 2
    assert workshop.size_warnings(lower, 1.0) == []


def test_the_frame_diagonal_is_given_to_the_hundredth(hierarchy):
    puzzle = build_puzzle(hierarchy[:3], 250.123)
    assert workshop.summary(puzzle, {}, 7.0)["frame_diagonal_mm"] == 250.12
