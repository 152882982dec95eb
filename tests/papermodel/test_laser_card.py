"""The laser-card kit from the card's side: the tile borders scored, every under tile marked
(its name engraved, or a dot whose crossing the instructions call out), the fewer-colours hint
true to what the named palette gives, and the instructions' pages readable. The sheets are
read back from their DXF with ezdxf; the borders are worked out from the strips' tiles by
another route than the code's (a tile's edge within a hair of the next tile)."""

from __future__ import annotations

import re
from functools import lru_cache

import ezdxf
import numpy as np
import pytest
import shapely

from weavecut import export, inputs
from weavecut.layout.drawing import Text
from weavecut.layout.lasersetup import laser, material
from weavecut.papermodel import cardkit, lasercard
from weavecut.papermodel.book import strip_set, tile_size_for
from weavecut.papermodel.pages import PageArea
from weavecut.papermodel.checks import report
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

A4 = (210.0, 297.0)
HAIR = 0.01  # mm: how near a line read back from a file lies to where it belongs


@lru_cache(maxsize=None)
def weaves(spec: str, levels: int = 2):
    return tuple(snub_weaves(subdivide(inputs.get(spec), levels)))


def kit(spec: str = "square-grid:2x2", palette: str = "maritime-12", width: float | None = None):
    """The card kit of ``spec`` at 20 mm octagons, or ``width`` mm wide."""
    ws = list(weaves(spec))
    tile = 20.0 if width is None else tile_size_for(ws[-1], width)
    return cardkit.card_kit(ws, palette, material("card-300gsm"), laser(), A4, 10.0, tile, 0.0,
                            "test")


@lru_cache(maxsize=None)
def grid_kit(palette: str = "maritime-12"):
    return kit(palette=palette)


@lru_cache(maxsize=None)
def flower_kit():
    """The pentagon flower at 10 cm: 35 under tiles too small for a name."""
    return kit("pentagon-flower", width=100.0)


def dxf_lines(path, layer: str) -> list[np.ndarray]:
    doc = ezdxf.readfile(path)
    return [np.array([(x, y) for x, y, *_ in e.get_points()])
            for e in doc.modelspace().query(f'LWPOLYLINE[layer=="{layer}"]')]


def borders(strip) -> list:
    """The borders between consecutive tiles of ``strip`` (the last one skipped on a piece with
    a glue band: the band's engraved edge is there), each the part of a tile's edge that lies
    within a hair of the next tile."""
    n = len(strip.tiles) - 1 - (strip.glue is not None)
    return [strip.tiles[i].boundary.intersection(strip.tiles[i + 1].buffer(1e-6))
            for i in range(n)]


def engraved_labels(cut, n: int):
    """Sheet ``n``'s engraved labels (each the hull of its strokes: the patch of card it
    marks) and arrows, as one geometry."""
    hulls = []
    for c, o, owner in cut.texts[n]:  # strips
        point_owner = np.repeat(owner, np.diff(o))
        hulls += [shapely.MultiPoint(c[point_owner == k]).convex_hull for k in set(owner.tolist())]
    arrows = [a for p in cut.pieces[n] for a in p.arrows.tolist()]
    return shapely.union_all(hulls + arrows)


@pytest.mark.parametrize("case", [grid_kit, flower_kit])
def test_every_tile_border_is_scored_clear_of_the_labels(case, tmp_path):
    """Read back from each sheet's DXF: every border between two tiles of a strip has a score
    line on it, which covers the border (less ENGRAVE_MARGIN at the strip's edges) except
    within SCORE_CLEAR of an engraved label (the hull of its strokes) or arrow, and keeps that
    far from them; no score line lies anywhere else."""
    cut = case().cut
    clear = lasercard.SCORE_CLEAR
    for n, (drawing, pieces) in enumerate(zip(cut.sheets, cut.pieces)):
        path = tmp_path / f"sheet{n}.dxf"
        export.write(drawing, path)
        scores = [shapely.LineString(r) for r in dxf_lines(path, "score")]
        assert scores
        scored = shapely.union_all(scores)
        labels = engraved_labels(cut, n)
        all_borders = []
        for p in pieces:
            inner = shapely.buffer(p.cut, -lasercard.ENGRAVE_MARGIN + 1e-6, join_style="mitre")
            for b in borders(p):
                assert b.length > 1.0
                on = scored.intersection(b.buffer(HAIR))
                assert on.length > 0.5, p.label  # a mark the maker sees
                missing = b.intersection(inner).difference(scored.buffer(HAIR))
                assert missing.difference(labels.buffer(clear + 2 * HAIR)).length < HAIR, p.label
                all_borders.append(b)
        near = shapely.union_all(all_borders).buffer(HAIR)
        assert all(near.covers(s) for s in scores)  # nothing scored off a border
        assert labels.distance(scored) >= clear - 2 * HAIR  # round ends drawn as polygons


@pytest.mark.parametrize("case, spec", [(grid_kit, "square-grid:2x2"),
                                        (flower_kit, "pentagon-flower")])
def test_no_engraved_arrow_breaks_a_score_line(case, spec, tmp_path):
    """Read back from each sheet's DXF: every arrow the printed strips have is engraved (a
    closed outline of 7 corners, at least a quarter of the printed arrow's area) and keeps
    SCORE_CLEAR off every tile border, so no score line stops for an arrow (the printed
    arrows reach 0.3 mm from a border: on card the score line there was broken round the
    arrow's tail). Planted: the printed arrows engraved as they are fail."""
    kit = case()
    cut, clear = kit.cut, lasercard.SCORE_CLEAR
    made = strip_set(list(weaves(spec)), palette("maritime-12"), PageArea(
        *material("card-300gsm")["sheet"], lasercard.SHEET_MARGIN, furniture=False),
        kit.book.tile_size, 0.0)
    printed = {p.label: sorted(shapely.area(p.arrows).tolist()) for p in made.pieces}
    engraved: dict[str, list[float]] = {}
    for n, (drawing, pieces) in enumerate(zip(cut.sheets, cut.pieces)):
        path = tmp_path / f"sheet{n}.dxf"
        export.write(drawing, path)
        closed = [shapely.Polygon(r) for r in dxf_lines(path, "engrave")
                  if len(r) == 8 and np.allclose(r[0], r[-1])]
        for p in pieces:
            arrows = [g for g in closed if p.cut.contains(g) and any(
                g.hausdorff_distance(a) < HAIR for a in p.arrows.tolist())]
            engraved[p.label] = sorted(g.area for g in arrows)
            if arrows:
                assert shapely.union_all(borders(p)).distance(
                    shapely.union_all(arrows)) >= clear - HAIR, p.label
    assert engraved.keys() == printed.keys()
    for label, areas in printed.items():
        assert len(engraved[label]) == len(areas), label
        assert all(e >= a / 4 for e, a in zip(engraved[label], areas)), label
    assert sum(map(len, printed.values())) > 0


@pytest.mark.parametrize("case", [grid_kit, flower_kit])
def test_every_under_tile_carries_a_name_or_a_dot(case, tmp_path):
    """Read back from the DXF: every under tile of every strip has engraving in it (the name
    of the strand on top, or a ring); a ring lies only in an under tile the strip leaves
    unnamed (its ``left_out``), one per such tile."""
    cut = case().cut
    for n, (drawing, pieces) in enumerate(zip(cut.sheets, cut.pieces)):
        path = tmp_path / f"sheet{n}.dxf"
        export.write(drawing, path)
        lines = dxf_lines(path, "engrave")
        is_ring = [len(r) >= 8 and np.allclose(np.hypot(*(r - r.mean(axis=0)).T),
                                               lasercard.DOT, atol=0.05) for r in lines]
        rings = [shapely.Point(r.mean(axis=0)) for r, ring in zip(lines, is_ring) if ring]
        strokes = shapely.union_all([shapely.LineString(r) for r, ring in zip(lines, is_ring)
                                     if not ring and len(r) > 1])
        dotted = 0
        for p in pieces:
            for i in np.flatnonzero(~p.over).tolist():
                tile = p.tiles[i]
                dots = sum(tile.covers(d) for d in rings)
                assert dots == (i in p.left_out), (p.label, i)
                assert dots or tile.intersects(strokes), (p.label, i)
                dotted += dots
        assert dotted == len(rings)
    assert (sum(len(d) for d in cut.dots) > 0) == (case is flower_kit)


def test_names_too_small_to_engrave_become_dots_and_callouts(monkeypatch):
    """With the smallest engraved label raised above every name's size (3 mm), no name is
    engraved: every under tile gets a dot, and every such crossing is called out once in the
    instructions ("C8 over A14"), on pages that exist."""
    monkeypatch.setattr(lasercard, "MIN_ENGRAVED", 3.2)
    made = kit()
    cut, book = made.cut, made.book
    pieces = [p for group in cut.pieces for p in group]
    assert all(set(p.left_out) == set(np.flatnonzero(~p.over).tolist()) for p in pieces)
    assert sum(len(d) for d in cut.dots) == sum((~p.over).sum() for p in pieces)
    wanted = sorted({f"{p.names[i]} over {p.label.split(' ')[0]}"
                     for p in pieces for i in p.left_out})
    called = sorted(t.text for sheet in book.drawing.sheets for layer in sheet.layers
                    if layer.name == "crossings" for t in layer.shapes if isinstance(t, Text))
    assert called == wanted
    assert len(book.drawing.sheets) == 3 + len(book.extra_pages[2:])
    assert any("called out on" in w for w in made.warnings)


def test_the_fewer_colours_hint_names_palettes_that_give_fewer_card_colours():
    """The default palette's 8 card colours on sheets about a quarter covered: the hint names
    the flat presets, and cutting with one of them does give that many card colours (no fewer
    than the copies: 4 here, 5 on the pentagon flower); a kit already in 4 colours gets no hint,
    nor do well-filled sheets."""
    made = grid_kit()
    cut = made.cut
    assert len(set(cut.colours)) == 8 and cut.fill < cardkit.FULL
    assert dict(made.fewer) == {"maritime-4": 4, "okabe-ito": 4}
    page = " ".join(t.text for layer in made.instructions.sheets[2].layers
                    for t in layer.shapes if isinstance(t, Text))
    assert "--palette maritime-4 or --palette okabe-ito cuts these strips from 4 colours" in page
    # the pentagon flower's 5 copies: maritime-4 would give two copies one colour
    assert dict(flower_kit().fewer) == {"okabe-ito": 5}
    four = grid_kit("maritime-4")
    assert len(set(four.cut.colours)) == 4 and four.fewer == ()
    assert "A palette with fewer colours" not in " ".join(
        t.text for layer in four.instructions.sheets[2].layers for t in layer.shapes
        if isinstance(t, Text))
    assert cardkit.hint(0.9, 8, ()) == ""


def test_the_instruction_pages_are_readable_and_numbered():
    """Every text of the card's instructions passes the label checks (size, contrast, no
    overlap, inside the margins, page 1's IDs on their strands), every page says its own
    number of the file's count, and the strip drawn on page 3 is drawn at no more than 100 %
    and lies inside the page's box."""
    for made in (grid_kit(), flower_kit()):
        book = made.book
        assert report(book)["label_violations"] == 0
        total = len(book.drawing.sheets)
        for n, sheet in enumerate(book.drawing.sheets, start=1):
            numbers = [t.text for layer in sheet.layers for t in layer.shapes
                       if isinstance(t, Text) and re.fullmatch(r"page \d+ / \d+", t.text)]
            assert numbers == [f"page {n} / {total}"]
        colours = book.drawing.sheets[cardkit.COLOURS_PAGE - 1]
        caption = next(t.text for layer in colours.layers for t in layer.shapes
                       if isinstance(t, Text) and t.text.startswith("Strip "))
        scale = float(re.search(r"drawn at (\d+) %", caption)[1])
        assert 0 < scale <= 100
        points = np.concatenate([s.coords for layer in colours.layers for s in layer.shapes
                                 if not isinstance(s, Text) and layer.name != "page"])  # the
        # page's furniture (title, number, the 100 mm bar) lies in the margins, by design
        assert shapely.box(*book.area.box).buffer(1e-6).covers(shapely.MultiPoint(points))
