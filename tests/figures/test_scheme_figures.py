"""The classic schemes' figures: built from the engine, and showing what the captions say."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.svg_readback import assert_svg_shows
from weavecut import export, inputs
from weavecut.figures import gallery, scheme_stages, schemes
from weavecut.figures import fractal as fractal_figures
from weavecut.layout.drawing import Drawing, Polylines, Text
from weavecut.subdivision import subdivide
from weavecut.validation import validate
from weavecut.weave.schemes import scheme_weaves


@pytest.mark.parametrize("name", sorted(schemes.FIGURES))
def test_scheme_figures_render(name):
    assert name in gallery.FIGURES
    drawing = schemes.FIGURES[name][1]()
    assert isinstance(drawing, Drawing)
    assert_svg_shows(drawing, export.render(drawing, "svg"))


def test_figure_inputs_are_valid_meshes():
    for mesh in (scheme_stages.triangle_input(), scheme_stages.quad_dominant_input()):
        validate(mesh)
    quad = scheme_stages.quad_dominant_input()
    assert sorted(np.unique(quad.face_sizes).tolist()) == [3, 4, 5]


def _captions(drawing):
    return [s.text for layer in drawing.sheets[0].layers if layer.name.endswith("caption")
            for s in layer.shapes if isinstance(s, Text)]


def test_scheme_stages_has_every_stage_of_the_paper():
    captions = _captions(scheme_stages.fig_scheme_stages())
    assert len(captions) == 4 * 4 + 3       # Loop, butterfly, sqrt3, mid-edge; singularities
    for word in ("Loop: input", "butterfly: input", "\u221a3: input", "mid-edge: input",
                 "flip the old edges", "Catmull-Clark", "Doo-Sabin"):
        assert any(word in c for c in captions), word


def test_splits_count_the_paper_s_parallel_strands():
    # Loop: one strand -> two parallel strands; sqrt3: two steps -> three
    assert "2 parallel strands" in " ".join(_captions(schemes.fig_loop_split()))
    assert "3 parallel strands" in " ".join(_captions(schemes.fig_sqrt3_split()))
    assert "2 parallel strands" in " ".join(_captions(schemes.fig_two_colourings()))


def test_along_finds_the_catmull_clark_children_and_not_the_crossing_strands():
    h = subdivide(inputs.get("square-grid:4x4"), 2, "catmull-clark")
    weaves = scheme_weaves(h, "catmull-clark")
    for strand in range(weaves[0].n_strands):
        kids = schemes.along(weaves[0], weaves[1], h[2].parent_face, strand)
        assert kids.sum() == 2


def test_face_split_construction_has_six_panels():
    assert len(_captions(schemes.fig_face_split_construction())) == 6


def _circle(p, q, r):
    """Centre and radius of the circle through three points."""
    a = np.array([q - p, r - p], dtype=float)
    b = 0.5 * np.array([(q - p) @ (q + p), (r - p) @ (r + p)])
    centre = np.linalg.solve(a, b)
    return centre, float(np.linalg.norm(p - centre))


def test_z_triplet_labels_sit_at_their_arcs():
    """Each 2pi/3 label lies inside its angle, on the bisector, within two arc radii of the
    vertex (the old labels sat about three radii away, off the bisector)."""
    drawing = fractal_figures.fig_z_triplet()
    layers = {layer.name: layer for layer in drawing.sheets[0].layers}
    arcs = [s for s in layers["z-triplet"].shapes if isinstance(s, Polylines)][2:]
    labels = [s for s in layers["labels"].shapes if s.text == "2\u03c0/3"]
    assert len(arcs) == len(labels) == 2
    for arc, label in zip(arcs, labels):
        c = arc.coords
        vertex, radius = _circle(c[0], c[len(c) // 2], c[-1])
        bisector = (c[0] + c[-1]) / 2 - vertex
        to_label = np.array([label.x, label.y]) - vertex
        cos = bisector @ to_label / (np.linalg.norm(bisector) * np.linalg.norm(to_label))
        assert np.linalg.norm(to_label) < 2 * radius
        assert math.degrees(math.acos(min(cos, 1.0))) < 25
