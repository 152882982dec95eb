"""The colour rules in numbers worked out by hand: shades of a colour by rank, sibling ranks
with orphans among the strands, palette families of a lone weave and of orphan strands; the
triangle colourings a weave takes."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from weavecut import inputs
from weavecut.mesh import Mesh
from weavecut.subdivision import subdivide
from weavecut.weave.colour import (
    Palette, crossing_pairs, greedy_classes, palette, shade, sibling_rank, strand_colours,
    strand_families,
)
from weavecut.weave.snub_weave import snub_weaves
from weavecut.weave.triangles import triangle_weave
from weavecut.weave.two_colouring import disc_two_colouring, triangle_three_colouring

from ..subdivision.classic_meshes import quad_grid
from .test_triangle_weaves import _three_colouring_oracle, split_quads


@pytest.mark.parametrize("rank, expected", [
    # darker (towards 0) on even ranks, lighter (towards 255) on odd ones, by 0.2, 0.35, ...
    (0, "#6a6633"),   # 0x85 * 0.8 = 106.4, 0x7f * 0.8 = 101.6, 0x40 * 0.8 = 51.2
    (1, "#9d9966"),   # 133 + 122 * 0.2 = 157.4, 127 + 128 * 0.2 = 152.6, 64 + 191 * 0.2 = 102.2
    (2, "#56532a"),   # 0.35: 133 * 0.65 = 86.45, 127 * 0.65 = 82.55, 64 * 0.65 = 41.6
    (3, "#b0ac83"),   # 133 + 122 * 0.35 = 175.7, 127 + 128 * 0.35 = 171.8, 64 + 191 * 0.35 = 130.85
    (9, "#e7e5d9"),   # 0.2 + 0.15 * 4 = 0.8: 133 + 122 * 0.8 = 230.6, 229.4, 216.8
    (12, "#14130a"),  # 0.2 + 0.15 * 6 = 1.1, capped at 0.85: 19.95, 19.05, 9.6
])
def test_shades_by_rank(rank, expected):
    assert shade("#857f40", rank) == expected


def test_shade_hex_digits_are_lower_case():
    assert shade("#ffffff", 0) == "#cccccc" and shade("#000000", 1) == "#333333"


def test_sibling_ranks_with_orphans():
    """Children of strand 1 (strands 0, 2), of strand 0 (3, 5, equally long), orphans 1 and 4:
    longest first, ties by strand id; an orphan is always first of its own."""
    parent = np.array([1, -1, 1, 0, -1, 0])
    lengths = np.array([5, 9, 7, 2, 3, 2])
    assert sibling_rank(parent, lengths).tolist() == [1, 0, 0, 0, 0, 1]
    # orphans long enough to come first in any group they were wrongly put in
    assert sibling_rank(np.array([-1, 0, 0, -1]), np.array([9, 1, 2, 9])).tolist() == \
        [0, 1, 0, 0]


def test_families_of_a_lone_weave_are_its_greedy_classes():
    weaves = snub_weaves(subdivide(inputs.get("square-grid:3x3"), 2))
    pal = palette("okabe-ito")
    lone = weaves[:1]
    expected = greedy_classes(lone[0].n_strands, crossing_pairs(lone[0]), len(pal.families))
    np.testing.assert_array_equal(strand_families(lone, pal), expected)


def test_orphan_strands_take_a_family_by_their_id():
    """Strands following no parent (none on the bundled inputs; two made here) take family
    ``id % families``, the others their parent's."""
    weaves = snub_weaves(subdivide(inputs.get("square-grid:3x3"), 3))
    ps = weaves[-1].parent_strand.copy()
    orphans = np.array([3, 14])
    ps[orphans] = -1
    weaves[-1] = replace(weaves[-1], parent_strand=ps)
    pal = palette("maritime-12")
    families = strand_families(weaves, pal)
    assert families.dtype.kind == "i"
    np.testing.assert_array_equal(families[orphans], orphans % len(pal.families))
    parents = strand_families(weaves[:-1], pal)
    np.testing.assert_array_equal(families[ps >= 0], parents[ps[ps >= 0]])


def test_triangle_weave_takes_a_colouring_of_zeros_and_ones():
    mesh, _ = split_quads(2, 2)
    c1 = triangle_three_colouring(mesh)
    as_bool, as_int = triangle_weave(mesh, c1), triangle_weave(mesh, c1.astype(np.int64))
    np.testing.assert_array_equal(as_int.strand_visits, as_bool.strand_visits)
    np.testing.assert_array_equal(as_int.visit_over, as_bool.visit_over)


def test_three_colouring_of_a_mesh_ending_in_a_lone_triangle():
    """The last face touches no other: the face graph still has a node for it."""
    grid = inputs.get("triangle-grid:2x2")
    n = grid.n_vertices
    mesh = Mesh.from_faces(np.vstack([grid.vertices, [(10, 0), (11, 0), (10, 1)]]),
                           grid.faces() + [[n, n + 1, n + 2]])
    c1 = triangle_three_colouring(mesh)
    np.testing.assert_array_equal(c1, _three_colouring_oracle(mesh))
    assert c1[n] and not c1[n + 1:].any()  # the lone triangle's first corner is c1


def test_disc_colouring_starts_c1_at_the_lowest_vertex_of_every_part():
    """Two grids side by side: in each, the colour is the parity of the grid distance (BFS
    layers) from its lowest vertex, which is c1."""
    one = quad_grid(2, 2)
    n = one.n_vertices
    mesh = Mesh.from_faces(np.vstack([one.vertices, one.vertices + [10, 0]]),
                           one.faces() + [[v + n for v in f] for f in one.faces()])
    c1 = disc_two_colouring(mesh)
    i, j = np.divmod(np.arange(n), 3)  # vertex (i, j) of a 2 x 2 grid is 3 j + i
    np.testing.assert_array_equal(c1, np.tile((i + j) % 2 == 0, 2))


def test_disc_colouring_reaches_vertices_only_a_lower_number_leads_to():
    """Two quads numbered so that vertex 2 is next to 3 and 5 only: the layers are found
    walking edges both ways (0: c1; 1, 4: c2; 5, 3: c1; 2: c2)."""
    mesh = Mesh.from_faces([(0, 0), (1, 0), (2, 1), (2, 0), (0, 1), (1, 1)],
                           [[0, 1, 5, 4], [1, 3, 2, 5]])
    assert disc_two_colouring(mesh).tolist() == [True, False, False, True, False, True]


@pytest.mark.parametrize("name", ["maritime-12", "okabe-ito"])
def test_strand_colours_of_children_and_orphans_by_the_rules(name):
    """Three levels, two strands of each later level made orphans: a child takes its family's
    shade by sibling rank at the first split (when the family has shades), else a shade of
    its parent's colour; an orphan takes family ``id % families`` and shades its first
    colour."""
    weaves = snub_weaves(subdivide(inputs.get("square-grid:3x3"), 3))
    for k in (1, 2):
        ps = weaves[k].parent_strand.copy()
        ps[[0, 7]] = -1
        weaves[k] = replace(weaves[k], parent_strand=ps)
    pal = palette(name)
    families = pal.families
    family = greedy_classes(weaves[0].n_strands, crossing_pairs(weaves[0]), len(families))
    colours = [families[f][0] for f in family.tolist()]
    for depth, weave in enumerate(weaves[1:], start=1):
        own = [int(weave.strand(s)[1].sum()) for s in range(weave.n_strands)]
        rank = sibling_rank(weave.parent_strand, np.array(own)).tolist()
        new_family, new_colours = [], []
        for s, p in enumerate(weave.parent_strand.tolist()):
            f = int(family[p]) if p >= 0 else s % len(families)
            if depth == 1 and len(families[f]) > 1:
                colour = families[f][rank[s] % len(families[f])]
            else:
                colour = shade(colours[p] if p >= 0 else families[f][0], rank[s])
            new_family.append(f)
            new_colours.append(colour)
        family, colours = np.array(new_family), new_colours
        assert strand_colours(weaves[:depth + 1], pal) == colours


def test_greedy_classes_by_hand():
    """Most neighbours first (ties: lower id), then the least used free class (ties: lower)."""
    path = np.array([[0, 1], [1, 2], [2, 3]])
    # order 1, 2, 0, 3: 1 -> 0; 2 -> 1; 0 -> 2 (1 and 2 free, 2 unused); 3 -> 0 (all used once)
    assert greedy_classes(4, path, 3).tolist() == [2, 0, 1, 0]
    # no neighbours: classes in turn, each used as often as the others
    assert greedy_classes(6, np.zeros((0, 2), dtype=np.int64), 3).tolist() == [0, 1, 2, 0, 1, 2]
    # a triangle with two classes: the last node has none free and takes the least used
    triangle = np.array([[0, 1], [1, 2], [0, 2]])
    assert greedy_classes(3, triangle, 2).tolist() == [0, 1, 0]


def test_a_run_whose_first_weave_has_a_lineage_is_coloured_from_its_first_weave():
    weaves = snub_weaves(subdivide(inputs.get("square-grid:3x3"), 3))[1:]
    assert weaves[0].parent_strand is not None
    first = greedy_classes(weaves[0].n_strands, crossing_pairs(weaves[0]), 8)
    np.testing.assert_array_equal(strand_families(weaves[:1], palette("okabe-ito")), first)
    assert strand_colours(weaves, palette("okabe-ito")) != strand_colours(weaves[1:],
                                                                          palette("okabe-ito"))


def test_a_palette_is_named_by_its_file_or_by_where_it_was_found(tmp_path):
    assert palette("okabe-ito").name == "okabe-ito"
    named = tmp_path / "named.toml"
    named.write_text('name = "sea"\ncolours = ["#123456", "#abcdef"]\n')
    assert palette(str(named)).name == "sea"
    bare = tmp_path / "bare.toml"
    bare.write_text('colours = ["#123456"]\n')
    assert palette(str(bare)) == Palette(str(bare), (("#123456",),))


def test_levels_above_a_weave_without_lineage_are_not_used():
    """A run whose last weave has no lineage (a lineage cut, or a scheme without one) is
    coloured as that weave alone, whatever comes before it, with or without a lineage."""
    weaves = snub_weaves(subdivide(inputs.get("pentagon"), 3))
    cut = [*weaves[:-1], replace(weaves[-1], parent_strand=None)]
    pal = palette("okabe-ito")
    alone = strand_colours(cut[-1:], pal)
    assert strand_colours(cut, pal) == alone and strand_colours(cut[-2:], pal) == alone
    np.testing.assert_array_equal(strand_families(cut, pal), strand_families(cut[-1:], pal))
    # and a cut further down keeps the levels from the cut on
    middle = [weaves[0], replace(weaves[1], parent_strand=None), *weaves[2:]]
    assert strand_colours(middle, pal) == strand_colours(middle[1:], pal)
    assert strand_colours(middle, pal) != strand_colours(middle[2:], pal)
