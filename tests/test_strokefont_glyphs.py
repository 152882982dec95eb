"""The stroke font's table of printable ASCII (``layout/hershey_futural.py``) is the
Hershey-Fonts package's font today, and a glyph drawn from it is the glyph drawn from the
package; engraving numbers loads no Hershey-Fonts."""

from __future__ import annotations

import numpy as np
from HersheyFonts import HersheyFonts

from weavecut.layout import hershey_futural, strokefont

from tests.fresh import modules_after


def test_the_table_is_the_packages_font():
    # after a Hershey-Fonts upgrade: python -m weavecut.layout.hershey_futural > (this file)
    with open(hershey_futural.__file__, encoding="utf-8") as f:
        assert f.read() == hershey_futural.source()


def test_every_glyph_is_drawn_as_from_the_package():
    font = HersheyFonts()
    font.load_default_font("futural")
    scale = 1 / 21
    for code in range(32, 127):
        (glyph,) = font.glyphs_for_text(chr(code))
        strokes, advance = strokefont._glyph(chr(code))
        want = [np.array([((x - glyph.left_offset) * scale, (9 - y) * scale) for x, y in s])
                for s in glyph.strokes if len(s) > 1]
        assert advance == glyph.char_width * scale
        assert len(strokes) == len(want)
        assert all(np.array_equal(a, b) for a, b in zip(strokes, want))


def test_numbers_are_engraved_without_the_package():
    assert "HersheyFonts" not in modules_after(
        "from weavecut.layout.strokefont import text_strokes\n"
        "assert len(text_strokes('F12 Ab-9', 3.0)[0])")


def test_poles_are_kept_for_the_same_polygons_only():
    """Every pole is the largest inscribed circle's centre of its own polygon, whichever
    polygons were asked for before (the same built anew, others, more than are kept)."""
    import shapely

    a = np.array([shapely.Point(0, 0).buffer(3), shapely.Point(20, 5).buffer(1)], dtype=object)
    b = np.array([shapely.Point(7, 1).buffer(2), shapely.Point(-9, 4).buffer(5)], dtype=object)
    rebuilt = np.array([shapely.Point(0, 0).buffer(3)], dtype=object)  # a[0], another object

    from weavecut.layout.poles import poles as fresh

    for polygons in (a, a.copy(), b, a, a[:1], rebuilt, np.concatenate([b, a, b[::-1]]),
                     np.array([a[1], a[1], b[0]], dtype=object), a[:0]):
        assert np.array_equal(strokefont._poles(polygons), fresh(polygons).reshape(-1, 2))
    strokefont._poles(a)[:] = 99.0  # a caller's changes do not reach the kept poles
    strokefont._poles(a)[:] = 99.0
    assert np.array_equal(strokefont._poles(a), fresh(a))
    many = shapely.buffer(shapely.points(np.arange(strokefont._KEPT + 3.0), 0.0), 0.25,
                          quad_segs=2)  # more than are kept: the first are asked anew
    assert np.array_equal(strokefont._poles(many)[-3:], fresh(many[-3:]))
    assert len(strokefont._kept) == strokefont._KEPT
    assert np.array_equal(strokefont._poles(np.concatenate([many[:2], b])),
                          fresh(np.concatenate([many[:2], b])))


def test_kept_fits_answer_only_the_same_question():
    """A fit asked again (the same polygons, built anew or not) is the one worked out then;
    one that differs in any of polygons, texts, margin, sizes, pad or level rule is worked out
    afresh: each agrees with a fit made with nothing kept."""
    import shapely

    def pieces(dx=0.0):
        return np.array([shapely.Polygon([(0 + dx, 0), (30, 0), (30, 8), (0, 12)]),
                         shapely.Point(50, 50).buffer(9, quad_segs=3),
                         shapely.box(0, 40, 14, 47)], dtype=object)

    base = (pieces(), ["1", "22", "333"], 0.6, 6.0, 0.25, 0.8, 3.0)
    asks = [base, (pieces(),) + base[1:], (pieces(0.5),) + base[1:],
            base[:1] + (["1", "22", "3"],) + base[2:], base[:2] + (1.5,) + base[3:],
            base[:3] + (np.array([6.0, 6.0, 2.0]),) + base[4:],
            base[:3] + (np.array([6.0, 6.0, 2.5]),) + base[4:], base[:4] + (0.0,) + base[5:],
            base[:5] + (1.0,) + base[6:], base[:6] + (0.0,), base]
    got = [strokefont.fit_labels(*a) for a in asks]  # each after the others are kept
    for a, g in zip(asks, got):
        strokefont._kept.clear()
        strokefont._fits.clear()
        want = strokefont.fit_labels(*a)
        assert all(np.array_equal(x, y) for x, y in zip(g, want))
    assert len({tuple(g[0].tolist()) for g in got}) > 3  # the asks differ in their answers
