"""Labels drawn all at once are each label drawn alone: its text's strokes at its height, its
ink box centred on its centre, turned by its angle (texts without ink left out, their index
kept), to the last bit."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.layout.strokefont import ink_box, labels, text_strokes
from weavecut.numeric import turn


def one_by_one(texts, centres, heights, angles):
    coords, counts, owner = [], [], []
    for k, text in enumerate(texts):
        xy, offsets, _ = text_strokes(text, heights[k])
        if not len(xy):
            continue
        x0, y0, x1, y1 = np.array(ink_box(text)) * heights[k]
        coords.append(turn(xy - ((x0 + x1) / 2, (y0 + y1) / 2), angles[k], centres[k]))
        counts += np.diff(offsets).tolist()
        owner += [k] * (len(offsets) - 1)
    return np.concatenate(coords), np.r_[0, np.cumsum(counts)], np.array(owner)


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(st.text(alphabet=" 0123456789F-.A", max_size=4),
                          st.floats(0.1, 50), st.sampled_from([0.0, 90.0, -33.5, 180.0]),
                          st.floats(-500, 500), st.floats(-500, 500)), max_size=12))
def test_all_at_once_as_one_by_one(specs):
    texts = [t for t, *_ in specs]
    heights = np.array([h for _, h, *_ in specs], dtype=float)
    angles = np.array([a for _, _, a, *_ in specs], dtype=float)
    centres = np.array([(x, y) for *_, x, y in specs], dtype=float).reshape(-1, 2)
    coords, offsets, owner = labels(texts, centres, heights, angles)
    if not any(len(text_strokes(t, 1.0)[0]) for t in texts):
        assert len(coords) == 0 and offsets.tolist() == [0] and len(owner) == 0
        return
    want = one_by_one(texts, centres, heights, angles)
    assert np.array_equal(coords, want[0])
    assert offsets.tolist() == want[1].tolist() and owner.tolist() == want[2].tolist()
