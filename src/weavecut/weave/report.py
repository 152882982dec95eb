"""Counts of a weave and of its lineage, in the shape ``weave-cut weave --json`` prints.

The paper says every strand splits into two interwoven strands at the next level; the lineage
summary measures how exactly that holds: children per parent, long children (three or more own
tiles) per long parent, how many sibling pairs cross each other, and short fragments.

A strand's length is that of its centre line through the centres of the tiles it visits
(mesh units): ``strand_length`` gives the spread; when every strand is a closed loop (a
woven ball) ``strand_lengths`` lists them all, strand by strand.

Which parent a child strand has is decided by :func:`weave.snub_weave.lineage`: every pentagon
of the child's own tiles votes for the parent strands that own or pass under the parent tile
its parent face lies in, and the most votes win (ties: the lower parent number). A short
fragment near the boundary (one or two own tiles) goes to whichever parent strand covers most
of its pentagons, so some parents collect several fragments (up to 6 children at pentagon level
6) and some short parents get none (37 of the 405 level-5 strands of the pentagon). The summary
counts every parent strand, with or without children (``parents``,
``parents_without_children``).
"""

from __future__ import annotations

import numpy as np

from .colour import crossing_pairs
from .model import Weave

LONG = 3  # own tiles that make a strand "long"


def _hist(values) -> dict[str, int]:
    counts = np.bincount(np.asarray(values, dtype=np.int64))
    return {str(k): int(counts[k]) for k in np.flatnonzero(counts)}


def _spread(values) -> dict[str, float]:
    """Smallest, mean and largest of ``values`` and their total, to 6 decimals."""
    if not len(values):
        return {"min": 0.0, "mean": 0.0, "max": 0.0, "total": 0.0}
    return {k: round(float(f(values)), 6) for k, f in
            (("min", np.min), ("mean", np.mean), ("max", np.max), ("total", np.sum))}


def own_tiles(weave: Weave) -> np.ndarray:
    """(S,) number of tiles each strand is on top of."""
    return np.bincount(weave.visit_strand[weave.visit_over], minlength=weave.n_strands)


def weave_summaries(weaves) -> list[dict]:
    """:func:`weave_summary` of every weave of a run, each with the weave before as parent."""
    return [weave_summary(w, weaves[i - 1] if i else None) for i, w in enumerate(weaves)]


def weave_summary(weave: Weave, parent: Weave | None = None) -> dict:
    """Counts of one weave; with its ``parent`` weave (the level before) also the lineage."""
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
        "strand_length": _spread(weave.strand_lengths()),
    }
    if weave.n_strands and weave.strand_closed.all():  # a ball: few loops, each listed
        out["strand_lengths"] = [round(float(x), 6) for x in weave.strand_lengths()]
    if weave.parent_strand is not None and parent is not None:
        out["lineage"] = lineage_summary(weave, parent)
    return out


def lineage_summary(weave: Weave, parent_weave: Weave) -> dict:
    """How the strands of ``weave`` descend from the strands of ``parent_weave`` (the level
    before).

    ``children_per_parent`` is a histogram over all parent strands (key "0": parents without
    children), ``childless_parent_length_histogram`` the own tiles of the parents without
    children; see the module docstring for how a child finds its parent.
    """
    parent = weave.parent_strand
    n_parents = parent_weave.n_strands
    if parent.max(initial=-1) >= n_parents:
        raise ValueError(f"parent strand {int(parent.max())} is beyond the {n_parents} parents")
    own = own_tiles(weave)
    has = parent >= 0
    children = np.bincount(parent[has], minlength=n_parents)
    long_children = np.bincount(parent[has & (own >= LONG)], minlength=n_parents)
    pairs = crossing_pairs(weave)
    siblings = (parent[pairs[:, 0]] == parent[pairs[:, 1]]) & (parent[pairs[:, 0]] >= 0)
    long_pair = (own[pairs[:, 0]] >= LONG) & (own[pairs[:, 1]] >= LONG)
    n_sibling_pairs = int((children * (children - 1) // 2).sum())
    return {
        "parents": n_parents,
        "parents_without_children": int((children == 0).sum()),
        "childless_parent_length_histogram": _hist(own_tiles(parent_weave)[children == 0]),
        "children_per_parent": _hist(children),
        "long_children_per_parent_with_long_children": _hist(long_children[long_children > 0]),
        "parents_with_exactly_two_long_children": int((long_children == 2).sum()),
        "sibling_pairs": n_sibling_pairs,
        "sibling_pairs_that_cross": int(siblings.sum()),
        "long_sibling_pairs_that_cross": int((siblings & long_pair).sum()),
        "short_fragments": int((own < LONG).sum()),
        "orphans": int((~has).sum()),
    }
