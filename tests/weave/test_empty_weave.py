"""A weave with no tiles and no strands (a mesh no weave fits yet) keeps the array shapes its
callers index: no crossing pairs as a (0, 2) array, no strand lengths as a (0,) array."""

from __future__ import annotations

import numpy as np

from weavecut import inputs
from weavecut.weave.colour import crossing_pairs
from weavecut.weave.model import Weave


def _empty_weave():
    return Weave(inputs.get("square-grid:2x2"), np.zeros(1, np.int64), np.zeros(0, np.int32),
                 np.zeros(1, np.int64), np.zeros(0, np.int32), np.zeros(0, bool),
                 np.zeros(0, bool))


def test_an_empty_weave_has_no_crossing_pairs_as_a_0_by_2_array():
    pairs = crossing_pairs(_empty_weave())
    assert pairs.shape == (0, 2)
    assert np.column_stack([pairs, pairs]).shape == (0, 4)  # stacks with other pair lists


def test_an_empty_weave_has_no_strand_lengths():
    lengths = _empty_weave().strand_lengths()
    assert lengths.shape == (0,)
    assert lengths.sum() == 0.0
