"""Every strip piece on its page is the weave's own tiles moved by a turn and a shift at the
print's true scale: its frame has determinant scale^2 > 0 (never mirrored), and mapping the
model's tiles through that frame gives the printed tiles exactly, in walking order."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from weavecut import inputs
from weavecut.papermodel.book import strand_book
from weavecut.papermodel.strips import model_tiles, octagon_size
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves


@pytest.mark.parametrize("page, tile_size", [((210.0, 297.0), 20.0), ((297.0, 210.0), 24.0)])
def test_pieces_are_the_weaves_tiles_turned_never_mirrored(page, tile_size):
    weaves = snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2))
    weave = weaves[-1]
    book = strand_book(weaves, palette("maritime-12"), page, tile_size=tile_size)
    tiles = model_tiles(weave)
    assert book.scale == pytest.approx(tile_size / octagon_size(weave))
    for _, piece in book.pieces:
        m = piece.frame
        assert np.allclose(m[2], [0.0, 0.0, 1.0])
        assert np.linalg.det(m[:2, :2]) == pytest.approx(book.scale ** 2, rel=1e-9)
        assert np.allclose(m[:2, :2] @ m[:2, :2].T, book.scale ** 2 * np.eye(2))
        visits, _ = weave.strand(piece.strand)
        if book.plan.reversed[piece.strand]:
            visits = visits[::-1]
        mapped = shapely.transform(tiles[visits], lambda xy: xy @ m[:2, :2].T + m[:2, 2])
        printed = np.asarray(piece.tiles, dtype=object)
        # a piece of a split strip is a run of consecutive visits
        start = int(np.argmin(shapely.hausdorff_distance(mapped, printed[0])))
        mapped = mapped[start:start + len(printed)]
        assert len(mapped) == len(printed)
        assert (shapely.hausdorff_distance(mapped, printed) < 1e-6).all(), piece.label
