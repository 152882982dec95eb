"""Page 1 speaks of what the model has (issue 29, the star): no "copy letter" on a model of one
copy, and one crossing or name left out is "its strip", not "their strip"."""

from __future__ import annotations

from pathlib import Path

import pytest

from weavecut import inputs
from weavecut.layout.drawing import Text
from weavecut.mesh_io import read_valid_mesh
from weavecut.papermodel.book import strand_book
from weavecut.papermodel.wording import left_out_note
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

ROOT = Path(__file__).resolve().parents[2]


def _subtitle(book) -> str:
    sheet = book.drawing.sheets[0]
    return " ".join(t.text for lay in sheet.layers for t in lay.shapes
                    if isinstance(t, Text) and t.text.startswith("Assembly sheet"))


@pytest.mark.parametrize("mesh, copies", [
    (lambda: read_valid_mesh(str(ROOT / "examples" / "house.obj")), False),
    (lambda: inputs.get("square-grid:2x2"), True)])
def test_the_copy_letter_is_named_only_where_there_are_copies(mesh, copies):
    ws = list(snub_weaves(subdivide(mesh(), 2)))
    book = strand_book(ws, palette("maritime-12"), tile_size=25.0)
    assert (book.plan.k > 1) == copies
    assert ("copy letter" in _subtitle(book)) == copies, _subtitle(book)


def test_one_name_left_out_is_said_in_the_singular():
    one = left_out_note(1, None, "page 1")
    assert one.startswith("1 under-crossing name is left off its strip: the tile under it,")
    assert one.endswith("it is called out on page 1")
    three = left_out_note(3, None, "pages 3-4")
    assert three.startswith("3 under-crossing names are left off their strips: the tile "
                            "under them,") and "they are called out on pages 3-4" in three
