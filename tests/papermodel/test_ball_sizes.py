"""How large a ball a page takes: a strip is cut into pieces of whole tiles, and the shortest
piece is two tiles (one, and the glue band under the next piece). Where a long strip curls, it
is cut narrower than the page (a packing choice), but two tiles may take the page's whole
width: a 20 cm dodecahedron ball prints on A4 (it was refused). A ball whose two tiles do not
fit is refused naming the largest size that does, on this page and on A3; the oracle is the
tool itself (that size is made, one centimetre more is refused) and the pieces' rectangles
measured here."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import shapely

from weavecut.papermodel.ball import ball_book
from weavecut.papermodel.ball_pieces import strand_pieces
from weavecut.papermodel.book import CURL, SizeError
from weavecut.papermodel.pages import occupied
from weavecut.papermodel.unfold import flatten, unfold
from weavecut.units import PAPER_SIZES
from weavecut.weave.colour import palette, strand_colours

from tests.papermodel.test_ball import ball_weaves

PAL = palette("maritime-12")


@pytest.fixture(scope="module")
def weaves():
    return ball_weaves("dodecahedron", 1)


def pieces_at(weaves, diameter: float, page: str) -> list:
    """Every strand's pieces on a ball ``diameter`` mm across (what ``ball_book`` lays out)."""
    from weavecut.papermodel.ball import radius
    from weavecut.papermodel.modules import copy_letter
    from weavecut.papermodel.pages import PageArea

    weave = weaves[-1]
    area = PageArea(*PAPER_SIZES[page], 10.0)
    flat = flatten(weave)
    labels = tuple(copy_letter(i) for i in range(weave.n_strands))
    scale = diameter / (2 * radius(weave))
    return [p for s in range(weave.n_strands) for p in strand_pieces(
        weave, unfold(weave, s, flat), strand_colours(weaves, PAL), labels, scale, area)], area


def sides(geoms) -> np.ndarray:
    """(n, 2) short and long side of each smallest rectangle, measured from its corners."""
    out = []
    for g in geoms:
        ring = np.asarray(shapely.minimum_rotated_rectangle(g).exterior.coords)
        out.append(sorted(np.linalg.norm(ring[1:3] - ring[0:2], axis=1)))
    return np.array(out)


def test_a_20_cm_ball_prints_on_a4_its_pieces_as_wide_as_two_tiles_need(weaves):
    book = ball_book(weaves, PAL, PAPER_SIZES["a4"], 200.0)
    x0, y0, x1, y1 = book.area.box
    page = shapely.box(x0 - 1e-6, y0 - 1e-6, x1 + 1e-6, y1 + 1e-6)
    for n in book.strip_pages:
        assert all(page.contains(o) for o in occupied(book.drawing.sheets[n - 1].layers))
    measured = sides([p.outline for _, p in book.pieces])
    assert (measured[:, 0] > CURL * book.area.short).any()  # wider than a curl: two tiles
    assert (measured[:, 0] <= book.area.short + 1e-6).all()
    assert (measured[:, 1] <= book.area.long + 1e-6).all()


@pytest.mark.parametrize("page", ["a4", "letter"])
def test_a_ball_too_large_names_the_largest_that_fits_here_and_on_a3(weaves, page):
    with pytest.raises(SizeError) as refused:
        ball_book(weaves, PAL, PAPER_SIZES[page], 600.0)
    said = str(refused.value)
    here = int(re.search(r"use --size (\d+)cm or less", said).group(1))
    on_a3 = int(re.search(r"--page a3 \(up to (\d+)cm\)", said).group(1))
    assert on_a3 > here
    if page == "a4":  # the README says what the refusal says
        readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
        assert f"up to {here} cm on A4, {on_a3} cm on A3" in " ".join(readme.split())
    for size, paper in ((here, page), (on_a3, "a3")):  # that size is made; 1 cm more is not
        made, area = pieces_at(weaves, 10.0 * size, paper)
        measured = sides([p.outline for p in made])
        assert (measured[:, 0] <= area.short + 1e-6).all()
        assert (measured[:, 1] <= area.long + 1e-6).all()
        with pytest.raises(SizeError, match=r"\(its shortest piece\) need"):
            ball_book(weaves, PAL, PAPER_SIZES[paper], 10.0 * (size + 1))
