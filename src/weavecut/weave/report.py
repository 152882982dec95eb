"""Counts of a weave and of its lineage, in the shape ``weave-cut weave --json`` prints.

The paper says every strand splits into two interwoven strands at the next level; the lineage
summary measures how exactly that holds: children per parent, long children (three or more own
tiles) per long parent, how many sibling pairs cross each other, and short fragments.
"""

from __future__ import annotations

import numpy as np

from .colour import crossing_pairs
from .model import Weave

LONG = 3  # own tiles that make a strand "long"


def _hist(values) -> dict[str, int]:
    counts = np.bincount(np.asarray(values, dtype=np.int64))
    return {str(k): int(counts[k]) for k in np.flatnonzero(counts)}


def own_tiles(weave: Weave) -> np.ndarray:
    """(S,) number of tiles each strand is on top of."""
    return np.bincount(weave.visit_strand[weave.visit_over], minlength=weave.n_strands)


def weave_summary(weave: Weave) -> dict:
    sizes = np.diff(weave.tile_offsets)
    own = own_tiles(weave)
    with_octagon = np.bincount(weave.visit_strand[weave.visit_over & (sizes[
        weave.strand_visits] == 2)], minlength=weave.n_strands) > 0
    out = {
        "tiles": weave.n_tiles,
        "octagons": int((sizes == 2).sum()),
        "boundary_pentagons": int((sizes == 1).sum()),
        "strands": weave.n_strands,
        "closed_strands": int(weave.strand_closed.sum()),
        "strands_with_octagon": int(with_octagon.sum()),
        "strand_length_histogram": _hist(own),
        "self_crossings": int(((weave.tile_over == weave.tile_under)
                               & (weave.tile_under >= 0)).sum()),
    }
    if weave.parent_strand is not None:
        out["lineage"] = lineage_summary(weave)
    return out


def lineage_summary(weave: Weave) -> dict:
    parent = weave.parent_strand
    own = own_tiles(weave)
    n_parents = int(parent.max(initial=-1)) + 1
    has = parent >= 0
    children = np.bincount(parent[has], minlength=n_parents)
    long_children = np.bincount(parent[has & (own >= LONG)], minlength=n_parents)
    pairs = crossing_pairs(weave)
    siblings = (parent[pairs[:, 0]] == parent[pairs[:, 1]]) & (parent[pairs[:, 0]] >= 0)
    long_pair = (own[pairs[:, 0]] >= LONG) & (own[pairs[:, 1]] >= LONG)
    n_sibling_pairs = int((children * (children - 1) // 2).sum())
    return {
        "children_per_parent": _hist(children),
        "long_children_per_parent_with_long_children": _hist(long_children[long_children > 0]),
        "parents_with_exactly_two_long_children": int((long_children == 2).sum()),
        "sibling_pairs": n_sibling_pairs,
        "sibling_pairs_that_cross": int(siblings.sum()),
        "long_sibling_pairs_that_cross": int((siblings & long_pair).sum()),
        "short_fragments": int((own < LONG).sum()),
        "orphans": int((~has).sum()),
    }
