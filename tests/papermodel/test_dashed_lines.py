"""Dashed fold and tab lines (``unfold.dashed``), checked against the segment they dash: every
dash lies on it, is ``dash`` long (or the whole segment, if that is shorter), the gaps are
``gap``, as many dashes as fit, and the pattern is centred on the segment."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given
from hypothesis import strategies as st

from weavecut.papermodel.unfold import DASH, DASH_GAP, dashed

coordinate = st.floats(-200.0, 200.0, allow_nan=False)
segment = st.tuples(coordinate, coordinate, st.floats(0.2, 60.0), st.floats(0.0, 2 * np.pi))


def dashes_of(line) -> list[np.ndarray]:
    """Every dash of a MultiLineString as its two end points, in order along the segment."""
    return [np.asarray(part.coords) for part in shapely.get_parts(line)]


@given(st.lists(segment, min_size=1, max_size=5), st.floats(0.5, 4.0), st.floats(0.3, 3.0))
def test_dashes_lie_on_their_segment_evenly_and_centred(specs, dash, gap):
    a = np.array([complex(x, y) for x, y, _, _ in specs])
    length = np.array([s[2] for s in specs])
    b = a + length * np.exp(1j * np.array([s[3] for s in specs]))
    lines = dashed(np.column_stack([a, b]), dash, gap)
    assert len(lines) == len(specs)
    for za, zb, n_len, line in zip(a, b, length, lines):
        parts = dashes_of(line)
        unit = (zb - za) / n_len
        # position of every dash end along the segment, and its distance off the segment
        t = np.array([[((complex(*p) - za) * np.conj(unit)).real for p in d] for d in parts])
        off = np.array([[((complex(*p) - za) * np.conj(unit)).imag for p in d] for d in parts])
        tol = 1e-6 * max(n_len, 1.0) + 1e-9
        assert np.abs(off).max() < tol
        assert t.min() >= -tol and t.max() <= n_len + tol
        assert (np.diff(t, axis=1) > 0).all()  # each dash runs from a towards b
        dash_lengths = t[:, 1] - t[:, 0]
        if n_len <= dash:
            assert len(parts) == 1 and abs(dash_lengths[0] - n_len) < tol
            continue
        assert np.abs(dash_lengths - dash).max() < tol
        assert np.abs(t[1:, 0] - t[:-1, 1] - gap).max(initial=0.0) < tol
        # centred: as much left free before the first dash as after the last
        assert abs(t[0, 0] - (n_len - t[-1, 1])) < tol
        # as many dashes as fit: one more would not
        assert t[-1, 1] - t[0, 0] + gap + dash > n_len - tol


def test_the_fold_dashes_are_2_mm_with_1_5_mm_gaps():
    """The defaults: an 18 mm fold holds five 2 mm dashes 1.5 mm apart (5 x 2 + 4 x 1.5 = 16 mm),
    1 mm free at each end; a 1 mm fold is one dash, the whole fold."""
    lines = dashed(np.array([[0j, 18 + 0j], [5j, 5j + 1j]]))
    five = dashes_of(lines[0])
    assert (DASH, DASH_GAP) == (2.0, 1.5)
    assert np.allclose([d[0, 0] for d in five], [1.0, 4.5, 8.0, 11.5, 15.0])
    assert np.allclose([d[1, 0] for d in five], [3.0, 6.5, 10.0, 13.5, 17.0])
    assert np.allclose([d[:, 1] for d in five], 0.0)
    one = dashes_of(lines[1])
    assert len(one) == 1 and np.allclose(one[0], [[0.0, 5.0], [0.0, 6.0]])
