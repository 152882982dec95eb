"""What cannot be unfolded is refused in one line naming the strand and the reason: a flat
weave (no surface in space), a strand over a boundary pentagon, a chain whose consecutive
pentagons share no edge."""

from __future__ import annotations

import dataclasses

import pytest

from weavecut.inputs import get
from weavecut.papermodel.unfold import UnfoldError, chain_faces, flatten, unfold
from weavecut.subdivision import subdivide
from weavecut.weave.snub_weave import snub_weaves


def test_a_flat_weave_is_refused():
    flat = snub_weaves(subdivide(get("square-grid:2x2"), 1))[-1]
    with pytest.raises(UnfoldError, match=r"^unfolding needs a snub level of a surface in space "
                                          r"\(pentagons, x y z\)$"):
        flatten(flat)
    with pytest.raises(UnfoldError, match=r"^strand 3 crosses a boundary pentagon; only "
                                          r"octagons unfold$"):
        chain_faces(flat, 3)


def test_a_chain_whose_pentagons_share_no_edge_is_refused():
    """Strand 1 of the cube's ball with its second and fourth visits swapped: its chain jumps
    between tiles that do not touch."""
    weave = snub_weaves(subdivide(get("cube"), 1, project="sphere"))[-1]
    visits = weave.strand_visits.copy()
    a = int(weave.strand_offsets[1])
    visits[a + 1], visits[a + 3] = visits[a + 3], visits[a + 1]
    broken = dataclasses.replace(weave, strand_visits=visits)
    with pytest.raises(UnfoldError, match=r"^strand 1: pentagons 2 and 3 of its chain share 0 "
                                          r"corners, not an edge$"):
        unfold(broken, 1)
    unfold(weave, 1)  # the weave itself unfolds
