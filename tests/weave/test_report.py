"""The lineage summary counts every parent strand, with or without children."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
from click.testing import CliRunner

from weavecut import inputs
from weavecut.cli import cli
from weavecut.subdivision import subdivide
from weavecut.weave.colour import crossing_pairs
from weavecut.weave.face_split import face_split_weave
from weavecut.weave.quad import quad_weave
from weavecut.weave.report import (
    LONG, lineage_summary, own_tiles, weave_summaries, weave_summary,
)
from weavecut.weave.snub_weave import snub_weaves

from ..subdivision.classic_meshes import polygon, quad_grid


@pytest.mark.parametrize("name,levels", [("pentagon", 4), ("triangulated-ngon:24", 3),
                                         ("square-grid:3x3", 3)])
def test_every_parent_is_counted(name, levels):
    weaves = snub_weaves(subdivide(inputs.get(name), levels))
    for parent, row in zip(weaves, weave_summaries(weaves)[1:]):
        lin = row["lineage"]
        hist = {int(k): v for k, v in lin["children_per_parent"].items()}
        assert sum(hist.values()) == parent.n_strands == lin["parents"]
        # children: every strand with a parent, counted once
        assert sum(k * v for k, v in hist.items()) == row["strands"] - lin["orphans"]
        assert hist.get(0, 0) == lin["parents_without_children"]
        assert sum(lin["childless_parent_length_histogram"].values()) == hist.get(0, 0)


def test_parents_at_the_end_of_the_numbering_are_not_dropped():
    # the case first seen: at level 3 of the triangulated 24-gon, parents without children sit
    # at the end of the parent numbering, which parent.max() + 1 dropped (48 of 72)
    weaves = snub_weaves(subdivide(inputs.get("triangulated-ngon:24"), 3))
    lin = weave_summaries(weaves)[2]["lineage"]
    assert lin["parents"] == 72
    assert lin["parents_without_children"] == 72 - len(np.unique(weaves[2].parent_strand))
    assert lin["parents_without_children"] > 0


def test_lineage_refuses_the_wrong_parent_weave():
    weaves = snub_weaves(subdivide(inputs.get("pentagon"), 3))
    with pytest.raises(ValueError, match="beyond"):
        lineage_summary(weaves[2], weaves[0])


def test_weave_json_has_lineage_and_nonconvex_counts():
    out = CliRunner().invoke(cli, ["weave", "pentagon", "--levels", "3", "--json"])
    data = json.loads(out.stdout)
    assert data["nonconvex_faces"] == 0
    assert "lineage" not in data["levels"][0]
    assert data["levels"][1]["lineage"]["parents"] == data["levels"][0]["strands"]


def _recount(weave, parent_weave=None) -> dict:
    """The summary recounted strand by strand with plain loops and Counters."""
    from collections import Counter
    from itertools import combinations

    sizes = [weave.tile_offsets[t + 1] - weave.tile_offsets[t] for t in range(weave.n_tiles)]
    walks = [list(zip(*(a.tolist() for a in weave.strand(s)))) for s in range(weave.n_strands)]
    own = [sum(over for _, over in walk) for walk in walks]
    hist = lambda values: {str(k): n for k, n in sorted(Counter(values).items())}  # noqa: E731
    top, below = {}, {}
    for s, walk in enumerate(walks):
        for tile, over in walk:
            (top if over else below)[tile] = s
    out = {
        "tiles": weave.n_tiles,
        "octagons": sizes.count(2),
        "boundary_pentagons": sizes.count(1),
        "strands": len(walks),
        "closed_strands": int(sum(weave.strand_closed.tolist())),
        "strands_with_octagon": sum(any(over and sizes[t] == 2 for t, over in walk)
                                    for walk in walks),
        "strand_length_histogram": hist(own),
        "self_crossings": sum(top.get(t) == below.get(t) for t in below),
        "strand_length": _length_spread(weave, walks),
    }
    if parent_weave is None:
        return out
    parent = weave.parent_strand.tolist()
    kids = {p: [s for s in range(len(walks)) if parent[s] == p]
            for p in range(parent_weave.n_strands)}
    long_kids = {p: [s for s in ss if own[s] >= 3] for p, ss in kids.items()}
    crossing = {tuple(sorted((top[t], below[t]))) for t in below
                if t in top and top[t] != below[t]}
    siblings = [(a, b) for a, b in crossing if parent[a] == parent[b] >= 0]
    parent_own = [sum(over) for over in
                  (parent_weave.strand(p)[1].tolist() for p in range(parent_weave.n_strands))]
    out["lineage"] = {
        "parents": parent_weave.n_strands,
        "parents_without_children": sum(not ss for ss in kids.values()),
        "childless_parent_length_histogram": hist(parent_own[p] for p, ss in kids.items()
                                                  if not ss),
        "children_per_parent": hist(len(ss) for ss in kids.values()),
        "long_children_per_parent_with_long_children": hist(len(ss) for ss in
                                                            long_kids.values() if ss),
        "parents_with_exactly_two_long_children": sum(len(ss) == 2
                                                      for ss in long_kids.values()),
        "sibling_pairs": sum(len(list(combinations(ss, 2))) for ss in kids.values()),
        "sibling_pairs_that_cross": len(siblings),
        "long_sibling_pairs_that_cross": sum(own[a] >= 3 and own[b] >= 3 for a, b in siblings),
        "short_fragments": sum(n < 3 for n in own),
        "orphans": parent.count(-1),
    }
    return out


def _length_spread(weave, walks) -> dict:
    """Centre-line lengths by loops: a tile's centre is the mean of its faces' vertex means;
    a strand's line runs through its tiles' centres in walking order (back to the start for a
    loop). Compared to 1e-6, the rounding of the summary."""
    mesh = weave.mesh
    offsets, faces = mesh.face_offsets.tolist(), mesh.face_indices.tolist()

    def face_mean(f):
        corners = [mesh.vertices[v] for v in faces[offsets[f]:offsets[f + 1]]]
        return sum(corners) / len(corners)

    centres = []
    for t in range(weave.n_tiles):
        tile = weave.tile_faces[weave.tile_offsets[t]:weave.tile_offsets[t + 1]].tolist()
        centres.append(sum(face_mean(f) for f in tile) / len(tile))
    lengths = []
    for s, walk in enumerate(walks):
        points = [centres[t] for t, _ in walk]
        if weave.strand_closed[s]:
            points.append(points[0])
        lengths.append(sum(float(np.sqrt(((b - a) ** 2).sum()))
                           for a, b in zip(points, points[1:])))
    return pytest.approx({"min": min(lengths), "mean": sum(lengths) / len(lengths),
                          "max": max(lengths), "total": sum(lengths)}, abs=2e-6)


@pytest.mark.parametrize("name,levels", [("pentagon", 4), ("square-grid:2x2", 3),
                                         ("triangulated-ngon:7", 3)])
def test_summary_equals_a_loop_recount(name, levels):
    weaves = snub_weaves(subdivide(inputs.get(name), levels))
    rows = weave_summaries(weaves)
    assert rows[0] == _recount(weaves[0])
    for parent, weave, row in zip(weaves, weaves[1:], rows[1:]):
        assert row == _recount(weave, parent)
    # the recount is not trivially empty: crossings, octagons and lineage all occur
    last = rows[-1]
    assert last["octagons"] and last["lineage"]["sibling_pairs_that_cross"]
    assert last["strands_with_octagon"] and last["lineage"]["short_fragments"]


def test_summary_recount_on_a_made_up_lineage():
    """Level 1 of the 3 x 3 grid (strands of exactly three own tiles, the LONG bound, which
    later levels lack) given made-up parents: orphans, siblings, the last parent number."""
    weave = snub_weaves(subdivide(inputs.get("square-grid:3x3"), 1))[0]
    assert weave.n_strands == 12 and (own_tiles(weave) == LONG).sum() == 4
    # strands 0 and 5 (three own tiles each) cross and are siblings
    assert [0, 5] in crossing_pairs(weave).tolist() and own_tiles(weave)[[0, 5]].tolist() == [3, 3]
    parents = np.array([0, 0, 1, 1, -1, 0, 2, 3, 3, 11, 11, -1], dtype=np.int32)
    child = replace(weave, parent_strand=parents)
    row = weave_summary(child, weave)
    assert row == _recount(child, weave)
    assert row["lineage"]["long_sibling_pairs_that_cross"] == 1
    assert all(v == round(v, 6) for v in row["strand_length"].values())  # 6 decimals
    with pytest.raises(ValueError, match="^parent strand 12 is beyond the 12 parents$"):
        lineage_summary(replace(weave, parent_strand=parents.clip(0) + 1), weave)


def test_summaries_of_a_run_give_the_first_weave_no_parent():
    weaves = snub_weaves(subdivide(inputs.get("pentagon"), 3))[1:]  # starts with a lineage
    rows = weave_summaries(weaves)
    assert "lineage" not in rows[0] and "lineage" in rows[1]


def test_own_tiles_counts_strands_that_are_never_on_top():
    """Two quads side by side: one of the one-quad strands is only ever below."""
    mesh = quad_grid(2, 1)
    weave = quad_weave(mesh, np.array([True, False, True, False, True, False]))
    by_loop = [int(weave.strand(s)[1].sum()) for s in range(weave.n_strands)]
    assert 0 in by_loop and own_tiles(weave).tolist() == by_loop


def test_an_empty_weave_has_a_zero_length_spread():
    weave = face_split_weave(polygon(5))  # no inner edge: no tile, no strand
    assert weave_summary(weave)["strand_length"] == {"min": 0.0, "mean": 0.0, "max": 0.0,
                                                     "total": 0.0}


def test_self_crossings_of_the_first_strand_count():
    """On the cube projected onto a sphere, level 2, strands cross themselves, strand 0
    among them (strand numbers start at 0, so a guard that skips "no strand below", -1,
    must not skip strand 0): the summary equals the recount, lineage included."""
    weaves = snub_weaves(subdivide(inputs.get("cube"), 2, project="sphere"))
    weave = weaves[-1]
    assert ((weave.tile_over == 0) & (weave.tile_under == 0)).any()
    row = weave_summary(weave, weaves[-2])
    loops = row.pop("strand_lengths")  # a ball lists its loops (the recount does not)
    assert len(loops) == weave.n_strands and sum(loops) == pytest.approx(
        row["strand_length"]["total"])
    assert row == _recount(weave, weaves[-2])
    assert row["self_crossings"] == 12


def test_a_balls_listed_loops_agree_with_its_length_spread():
    """The loops a ball lists and the spread beside them are the same lengths to the same 6
    decimals: the shortest and longest listed are the spread's min and max exactly."""
    weave = snub_weaves(subdivide(inputs.get("dodecahedron"), 2, project="sphere"))[-1]
    row = weave_summary(weave)
    loops = row["strand_lengths"]
    assert weave.strand_closed.all() and len(loops) == weave.n_strands
    assert (min(loops), max(loops)) == (row["strand_length"]["min"], row["strand_length"]["max"])
    assert all(round(x, 6) == x for x in loops)
