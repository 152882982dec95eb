"""The drawings of `subdivide -o x.svg` and `weave -o x.svg`, read from the drawing itself:
everything on the sheet inside its margins, the final level's every edge cut once, the Z middle
edges exactly the edges the two pentagons of a tile share (found from the faces, not from the
half-edge numbering), drawn to stand out; a part laid flat by its long side whatever its turn;
a label upright unless turned; a laser job with its material's operations; CIEDE2000 against a
per-pair transcription of Sharma, Wu and Dalal (2005) where the hue difference passes -180
degrees. The layout mutation package's figure survivors (#34)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from weavecut import inputs
from weavecut.layout.colour_difference import ciede2000
from weavecut.layout.labels import centred_text
from weavecut.layout.lasersetup import laser_job, material
from weavecut.layout.mesh_figure import mesh_drawing
from weavecut.layout.nesting import upright_angles
from weavecut.layout.weave_figure import middle_edge_lines, weave_drawing
from weavecut.subdivision import subdivide
from weavecut.weave.snub_weave import snub_weaves

SIZE, MARGIN = 120.0, 10.0


@pytest.fixture(scope="module")
def levels():
    return subdivide(inputs.get("pentagon"), 2)


def _points(layer) -> np.ndarray:
    return np.concatenate([shape.coords for shape in layer.shapes])


def _inside_margins(sheet) -> None:
    assert max(sheet.width, sheet.height) == pytest.approx(SIZE + 2 * MARGIN)
    for layer in sheet.layers:
        xy = _points(layer)
        assert (xy >= MARGIN - 1e-5).all() and (xy[:, 0] <= sheet.width - MARGIN + 1e-5).all()
        assert (xy[:, 1] <= sheet.height - MARGIN + 1e-5).all(), layer.name


def _segments(layer) -> set[frozenset]:
    out = set()
    for shape in layer.shapes:
        for line in shape.lines():
            out |= {frozenset((tuple(p), tuple(q))) for p, q in zip(line[:-1], line[1:])}
    return out


@pytest.mark.parametrize("earlier", [False, True])
def test_a_subdivision_drawing_fits_its_sheet_and_cuts_every_edge_once(levels, earlier):
    meshes = [lv.mesh for lv in levels]
    sheet = mesh_drawing(meshes, SIZE, MARGIN, earlier=earlier).sheets[0]
    _inside_margins(sheet)
    names = [layer.name for layer in sheet.layers]
    assert names == [*(["level-0", "level-1"] if earlier else []), "cut-1-inner", "cut-2-outline"]
    inner, outline = (_segments(layer) for layer in sheet.layers[-2:])
    assert not inner & outline
    assert len(inner) + len(outline) == len(meshes[-1].topology.edges)


def test_a_weave_drawing_fits_its_sheet_and_its_middle_edges_stand_out(levels):
    weaves = snub_weaves(levels)
    colours = ["#1f77b4"] * weaves[-1].n_strands
    sheet = weave_drawing(weaves, colours, SIZE, MARGIN, middle_edges=True).sheets[0]
    _inside_margins(sheet)
    layers = {layer.name: layer for layer in sheet.layers}
    assert list(layers) == ["tiles", "tile-outlines", "middle-edges"]
    middle, outlines = layers["middle-edges"].shapes[0], layers["tile-outlines"].shapes[0]
    assert middle.style.stroke not in (None, outlines.style.stroke)
    assert middle.style.stroke_width > outlines.style.stroke_width


def test_ribbons_are_under_half_as_wide_as_a_step_between_crossings(levels):
    """Drawn as ribbons, a strand (with its casing) stays under half the step between two of
    its crossings (the median piece of its centre line): neighbouring strands keep a gap."""
    weaves = snub_weaves(levels)
    sheet = weave_drawing(weaves, ["#1f77b4"] * weaves[-1].n_strands, SIZE, MARGIN,
                          ribbons=True).sheets[0]
    _inside_margins(sheet)
    ribbons = next(layer for layer in sheet.layers if layer.name == "ribbons")
    steps = np.concatenate([np.hypot(*np.diff(line, axis=0).T) for shape in ribbons.shapes
                            for line in shape.lines()])
    assert max(shape.style.stroke_width for shape in ribbons.shapes) < 0.5 * np.median(steps)


def test_the_middle_edges_are_the_edges_a_tiles_two_pentagons_share(levels):
    """A tile is two pentagons glued along their middle edge (a boundary pentagon alone): the
    edges two faces of one tile share, from the faces' vertices, are all middle edges, and a
    lone pentagon adds one more each."""
    weave = snub_weaves(levels)[-1]
    faces, v = weave.mesh.dense_faces(), weave.mesh.vertices
    coords, offsets = middle_edge_lines(weave.mesh)
    drawn = {frozenset(map(tuple, coords[a:b])) for a, b in zip(offsets[:-1], offsets[1:])}
    tiles = np.bincount(weave.face_tile)
    shared = set()
    for t in np.flatnonzero(tiles == 2):
        f, g = np.flatnonzero(weave.face_tile == t)
        common = sorted(set(faces[f].tolist()) & set(faces[g].tolist()))
        assert len(common) == 2
        shared.add(frozenset(tuple(v[k]) for k in common))
    assert shared <= drawn
    assert len(drawn) == len(shared) + np.count_nonzero(tiles == 1)


@given(st.floats(0.5, 50), st.floats(0.05, 0.95), st.floats(-180, 180))
def test_a_part_is_laid_flat_by_its_long_side_whatever_its_turn(long, ratio, turn):
    part = shapely.affinity.rotate(shapely.box(0, 0, long, long * ratio), turn, origin=(0, 0))
    angle = float(upright_angles(np.array([part], dtype=object))[0])
    flat = shapely.affinity.rotate(part, angle, origin=(0, 0))
    x0, y0, x1, y1 = flat.bounds
    assert x1 - x0 == pytest.approx(long, rel=1e-6) and y1 - y0 == pytest.approx(long * ratio,
                                                                               rel=1e-6)
    assert -90.0 <= angle < 90.0


def test_a_label_is_upright_unless_turned():
    assert centred_text((5.0, 5.0), "AB", 4.0).angle == 0.0
    assert centred_text((5.0, 5.0), "AB", 4.0, 30.0).angle == 30.0


def test_a_laser_job_carries_its_materials_operations():
    mat = material("birch-plywood-3mm")
    job = laser_job(mat, "as drawn")
    assert job.operations == mat["operations"] and job.kerf == "as drawn"
    assert job.material == f"{mat['description']}; preset {mat['name']}"


def _ciede2000_sharma(lab1, lab2) -> float:
    """One pair, transcribed from Sharma, Wu and Dalal (2005), eqs. 1-22, in math's scalars."""
    (L1, a1, b1), (L2, a2, b2) = lab1, lab2
    c_mean = (math.hypot(a1, b1) + math.hypot(a2, b2)) / 2
    g = 0.5 * (1 - math.sqrt(c_mean ** 7 / (c_mean ** 7 + 25 ** 7)))
    c1, c2 = math.hypot(a1 * (1 + g), b1), math.hypot(a2 * (1 + g), b2)
    h1 = math.degrees(math.atan2(b1, a1 * (1 + g))) % 360 if c1 else 0.0
    h2 = math.degrees(math.atan2(b2, a2 * (1 + g))) % 360 if c2 else 0.0
    dh = 0.0 if c1 * c2 == 0 else (h2 - h1 if abs(h2 - h1) <= 180
                                   else h2 - h1 - 360 if h2 - h1 > 180 else h2 - h1 + 360)
    d_l, d_c = L2 - L1, c2 - c1
    d_h = 2 * math.sqrt(c1 * c2) * math.sin(math.radians(dh / 2))
    l_mean, c_bar = (L1 + L2) / 2, (c1 + c2) / 2
    h_bar = (h1 + h2 if c1 * c2 == 0 else (h1 + h2) / 2 if abs(h1 - h2) <= 180
             else (h1 + h2 + 360) / 2 if h1 + h2 < 360 else (h1 + h2 - 360) / 2)
    t = (1 - 0.17 * math.cos(math.radians(h_bar - 30)) + 0.24 * math.cos(math.radians(2 * h_bar))
         + 0.32 * math.cos(math.radians(3 * h_bar + 6))
         - 0.20 * math.cos(math.radians(4 * h_bar - 63)))
    theta = 30 * math.exp(-(((h_bar - 275) / 25) ** 2))
    r_c = 2 * math.sqrt(c_bar ** 7 / (c_bar ** 7 + 25 ** 7))
    s_l = 1 + 0.015 * (l_mean - 50) ** 2 / math.sqrt(20 + (l_mean - 50) ** 2)
    s_c, s_h = 1 + 0.045 * c_bar, 1 + 0.015 * c_bar * t
    r_t = -math.sin(math.radians(2 * theta)) * r_c
    return math.sqrt((d_l / s_l) ** 2 + (d_c / s_c) ** 2 + (d_h / s_h) ** 2
                     + r_t * (d_c / s_c) * (d_h / s_h))


@given(st.floats(20, 80), st.floats(5, 60), st.floats(5, 60), st.floats(170, 200),
       st.floats(-3, 3))
def test_ciede2000_across_opposite_hues_agrees_with_the_paper(lightness, c1, c2, hue, off):
    """Hues about 180 degrees apart, on both sides of -180 after the a* stretch; the mean hue
    near 275 degrees, where the rotation term weighs the hue difference's sign."""
    h1, h2 = math.radians(hue), math.radians(hue - 180.0 + off)
    lab1 = (lightness, c1 * math.cos(h1), c1 * math.sin(h1))
    lab2 = (lightness + 5, c2 * math.cos(h2), c2 * math.sin(h2))
    assert float(ciede2000(lab1, lab2)) == pytest.approx(_ciede2000_sharma(lab1, lab2),
                                                         rel=1e-9, abs=1e-9)


def test_ciede2000_agrees_with_the_paper_on_a_grid_through_minus_180():
    """The same on a fixed grid whose hue differences step through -182..-178 degrees (a
    random draw seldom lands within a degree of -180)."""
    grid = [((50, c * math.cos(math.radians(185 + d)), c * math.sin(math.radians(185 + d))),
             (55, 20 * math.cos(math.radians(5)), 20 * math.sin(math.radians(5))))
            for c in (30, 40, 50) for d in np.linspace(-2, 2, 81)]
    got = ciede2000(np.array([p for p, _ in grid]), np.array([q for _, q in grid]))
    assert got == pytest.approx([_ciede2000_sharma(p, q) for p, q in grid], rel=1e-9)
