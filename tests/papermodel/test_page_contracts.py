"""Contracts of the paper model's pages that the other tests leave unchecked: instruction text
in sentence case, the layers the pages are built from, the legend's dashed swatches, split
strips' glue bands and their placement, the assembly sheet's turns, leaders and page number."""

from __future__ import annotations

import re
from dataclasses import replace
from functools import lru_cache

import numpy as np
import pytest
import shapely

from weavecut import inputs
from weavecut.layout.drawing import Polygons, Polylines, Text
from weavecut.papermodel import assembly, ball
from weavecut.papermodel.book import strand_book
from weavecut.papermodel.pages import FOLD, PageArea, page_layers, split_strip, strip_layers
from weavecut.papermodel.modules import copy_colours, copy_letter, plan_modules
from weavecut.papermodel.strips import build_strips
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette
from weavecut.weave.snub_weave import snub_weaves

SHOUT = re.compile(r"\b[A-Z]{4,}\b")  # a word of 4+ letters in capitals


def texts_of(layers, names=None) -> list[Text]:
    return [s for lay in layers if names is None or lay.name in names
            for s in lay.shapes if isinstance(s, Text)]


def sentence_case(text: str) -> bool:
    return SHOUT.search(text) is None


@lru_cache(maxsize=None)
def ball_case():
    """A 40 mm-octagon dodecahedron ball (its own pages are rebuilt by the tests)."""
    ws = snub_weaves(subdivide(inputs.get("dodecahedron"), 1, project="sphere"))
    return ws[-1], ball.ball_book(ws, palette("maritime-12"), (210.0, 297.0),
                                  ball.diameter_for(ws[-1], 40.0))


@lru_cache(maxsize=None)
def grid_case():
    ws = list(snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2)))
    return ws, strand_book(ws, palette("maritime-12"), (210.0, 297.0), tile_size=20.0)


def hexagon_weaves():
    from weavecut.mesh import Mesh
    ring = [(np.cos(a), np.sin(a)) for a in np.arange(6) * np.pi / 3]
    mesh = Mesh.from_faces([(0.0, 0.0), *ring], [[0, i + 1, (i + 1) % 6 + 1] for i in range(6)])
    return snub_weaves(subdivide(mesh, 2))


def test_ball_pages_speak_in_sentence_case():
    weave, book = ball_case()
    labels = book.plan.labels
    total = len(book.drawing.sheets)
    cover = ball.assembly_sheet(weave, book, labels, "ball", total)
    steps = ball.weaving_sheet(weave, book, labels, "ball", total)
    words = texts_of(cover.layers, {"notes"}) + texts_of(steps.layers, {"steps"})
    assert len(words) > 5
    loud = [t.text for t in words if not sentence_case(t.text)]
    assert not loud, loud


def test_ball_assembly_sheet_has_its_notes_layer():
    """Page 1 of a ball: the six views (paint), their IDs and captions, the notes (labels)."""
    weave, book = ball_case()
    cover = ball.assembly_sheet(weave, book, book.plan.labels, "ball", 9)
    roles = {lay.name: lay.role for lay in cover.layers}
    assert {"views": "paint", "ids": "label", "captions": "label", "notes": "label",
            "page": "label"}.items() <= roles.items()
    notes = " ".join(t.text for t in texts_of(cover.layers, {"notes"}))
    assert "Where each strip is" in notes


def test_ball_strips_carry_their_folds_as_a_score_layer():
    """A ball's strips bend round it: their fold lines are a "folds" layer of role score."""
    _, book = ball_case()
    pieces = [p for _, p in book.pieces]
    assert any(len(p.folds) for p in pieces)
    layers = strip_layers(pieces)
    folds = [lay for lay in layers if lay.name == "folds"]
    assert len(folds) == 1 and folds[0].role == "score"
    assert all(isinstance(s, Polylines) for s in folds[0].shapes)


def test_flat_weaving_steps_speak_in_sentence_case():
    ws, book = grid_case()
    assert book.plan.k == 4
    steps, groups = assembly.weaving_steps(ws[-1], book, 0.0)
    assert len(steps) > 5 and groups
    loud = [s for s in steps if not sentence_case(s)]
    assert not loud, loud


def sentence_problems(step: str) -> list[str]:
    """What breaks plain sentences in ``step``: each sentence starts with a capital or a digit
    and the step ends with a full stop; inside a sentence a capital starts only a copy letter
    or strand ID ("A", "B or D", "A14", "X2") or the acronym "ID"; no word is in capitals."""
    out = [] if step.endswith(".") else [f"ends in {step[-5:]!r}"]
    for sentence in re.split(r"(?<=\.)\s+", step):
        if not (sentence[:1].isupper() or sentence[:1].isdigit()):
            out.append(f"starts in lower case: {sentence[:20]!r}")
        loud = [w for w in re.findall(r"[A-Za-z]+", sentence)[1:]
                if w != w.lower() and not (len(w) == 1 or w in ("ID", "IDs"))]
        out += [f"{w!r} in {sentence[:30]!r}" for w in loud]
    return out


@pytest.mark.parametrize("spec, levels", [("square-grid:2x2", 2), ("pentagon-flower", 2)])
def test_weaving_steps_are_plain_sentences_naming_every_strand_once(spec, levels, monkeypatch):
    """The weaving steps of a square grid (k = 4: warp and weft) and of the pentagon flower
    (k = 5: groups from the centre), with every optional step (label tabs, unnamed crossings,
    glued parts): each step is plain sentences, and the groups woven in name every strand
    once. A book stand-in holds only what the steps read (its one unnamed crossing is tile
    0's)."""
    from types import SimpleNamespace
    from weavecut.papermodel import crossings
    weave = snub_weaves(subdivide(inputs.get(spec), levels))[-1]
    plan = plan_modules(weave)
    monkeypatch.setattr(crossings, "left_out_crossings", lambda weave, *_: [
        (0, int(weave.tile_over[0]), int(weave.tile_under[0]))])
    piece = SimpleNamespace(flap=shapely.box(0, 0, 1, 1), left_out=(0,),
                            glue=shapely.box(0, 0, 1, 1), label=f"{plan.labels[0]} 1/2")
    book = SimpleNamespace(plan=plan, pieces=((3, piece),), extra_pages=(1, 2, 3),
                           callout_pages=(3,), layout="mixed", diagram_colours=())
    steps, groups = assembly.weaving_steps(weave, book, 0.0)
    assert len(steps) >= 10
    problems = {s[:40]: sentence_problems(s) for s in steps if sentence_problems(s)}
    assert not problems, problems
    woven = np.concatenate(groups)
    assert sorted(woven.tolist()) == list(range(weave.n_strands))
    assert len(sentence_problems("Lay the warp XX(copies A and C).XX")) == 3
    assert len(sentence_problems("Join the group BEFORE THE NEXT. so it holds.")) == 4


def test_legend_fold_swatch_dashes_are_even_and_apart():
    """Fold and tab swatches: three equal dashes, evenly spaced and disjoint, inside the 5 mm
    swatch."""
    layers = page_layers(PageArea(210.0, 297.0, 10.0), "t", "s", 1, 1, folds=True, tabs=True)
    dashed = [s for s in layers[0].shapes if isinstance(s, Polylines) and s.style == FOLD]
    assert len(dashed) == 1
    lines = dashed[0].lines()
    assert len(lines) == 6  # fold and tab, three dashes each
    for k in range(0, 6, 3):  # swatches
        xs = np.array([[seg[0, 0], seg[-1, 0]] for seg in lines[k:k + 3]])
        assert np.allclose(xs[:, 1] - xs[:, 0], xs[0, 1] - xs[0, 0])
        gaps = xs[1:, 0] - xs[:-1, 1]
        assert (gaps > 0).all() and np.allclose(gaps, gaps[0])
        assert xs.max() - xs.min() <= 5.0 + 1e-9


def test_split_strip_glues_every_piece_but_the_last_and_lays_them_at_the_origin():
    ws = snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2))
    w = ws[-1]
    plan = plan_modules(w)
    strips = build_strips(w, plan, copy_colours(plan, palette("maritime-12")), 20.0,
                          range(w.n_strands))
    strip = max(strips, key=lambda s: s.length)
    pieces = split_strip(strip, strip.length / 2.2, 1000.0)
    n = len(pieces)
    assert n >= 3
    assert [p.glue is not None for p in pieces] == [True] * (n - 1) + [False]
    assert sum(len(p.tiles) for p in pieces) == len(strip.tiles) + n - 1
    for p in pieces:  # laid flat at the origin, as the packer expects
        assert np.allclose(p.outline.bounds[:2], 0.0, atol=1e-9)


def test_module_layout_names_copy_j_turned_by_j_times_360_over_k():
    ws = hexagon_weaves()
    book = strand_book(ws, palette("maritime-12"), (210.0, 297.0), tile_size=25.0,
                       layout="module")
    k = book.plan.k
    assert k > 2
    sheet, _, _ = assembly.assembly_sheet(ws[-1], book, book.tile_size, 0.0, "t", 5)
    notes = " ".join(t.text for t in texts_of(sheet.layers, {"notes"}))
    found = re.findall(r"copy\s+([A-Z]):\s+turned\s+by\s+([-\d.e+]+)\s+deg", notes)
    assert [c for c, _ in found] == [copy_letter(j) for j in range(k)]
    assert np.allclose([float(d) for _, d in found], np.arange(k) * 360 / k)


def test_assembly_leaders_are_two_point_lines_one_per_plate_and_the_page_names_the_total():
    """On a page too small for every end ID, some sit on white plates with a leader line each;
    the page number reads "page 1 / total"."""
    ws, book = grid_case()
    small = replace(book, area=PageArea(100.0, 130.0, 5.0))
    sheet, _, _ = assembly.assembly_sheet(ws[-1], small, book.tile_size, 0.0, "t", 7)
    pattern = next(lay for lay in sheet.layers if lay.name == "pattern")
    plates = [s for s in pattern.shapes
              if isinstance(s, Polygons) and s.style.fill == "#ffffff"
              and s.style.stroke == "#333333"]
    leaders = [s for s in pattern.shapes
               if isinstance(s, Polylines) and s.style.stroke == "#000000"
               and s.style.stroke_width == 0.2]
    assert len(plates) == 1 and len(leaders) == 1
    lines = leaders[0].lines()
    assert len(lines) == len(plates[0].to_shapely()) > 0
    assert all(len(seg) == 2 for seg in lines)
    boxes = plates[0].to_shapely()
    for seg in lines:  # each leader starts on a plate
        assert min(shapely.distance(shapely.Point(seg[0]), boxes)) < 1e-6
    assert "page 1 / 7" in [t.text for t in texts_of(sheet.layers, {"page"})]


def test_ball_strand_pieces_name_the_tile_their_glue_band_goes_under():
    """Every piece ends with a band "glue j" that goes under the tile marked "j": the first
    tile of the next piece, or of the first where the loop closes."""
    weave, book = ball_case()
    labels = book.plan.labels
    for u in book.unfoldings:  # strands
        parts = ball.strand_pieces(weave, u, book.colours, labels, book.scale, book.area)
        for i, p in enumerate(parts):
            nxt = parts[(i + 1) % len(parts)]
            assert p.glue is not None and p.mark != p.tab
            assert p.tab == f"glue {nxt.mark}"


def test_a_glue_bands_word_stays_inside_its_band():
    """The "glue j" text is printed on the band, at least ``PAD`` clear of the band's edges
    (or not at all, on a ball too small for it)."""
    from weavecut.layout.labels import text_box
    from weavecut.papermodel.strip_labels import PAD, label_strip
    weave, book = ball_case()
    labels = book.plan.labels
    shown = 0
    for f in (1.0, 0.6):  # the ball at 40 mm and 24 mm octagons
        for u in book.unfoldings:  # strands
            for p in ball.strand_pieces(weave, u, book.colours, labels, book.scale * f,
                                        book.area):
                done = label_strip(p, book.tile_size * f)
                band = shapely.intersection(shapely.union_all(done.glue), done.outline)
                inside = shapely.buffer(band, -PAD + 1e-6, join_style="mitre")
                for t in done.texts:
                    if t.text == p.tab:
                        shown += 1
                        assert inside.covers(text_box(t)), (f, t)
    assert shown


def test_a_label_tab_goes_on_the_last_tile_when_the_first_is_in_two_parts():
    """The tab may sit on the first or the last tile's end edge; a first tile that is not one
    polygon (twisted, in two parts) leaves the last tile to take it."""
    from weavecut.papermodel.strip_labels import label_flap
    ws = snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2))
    w = ws[-1]
    plan = plan_modules(w)
    strips = build_strips(w, plan, copy_colours(plan, palette("maritime-12")), 20.0,
                          range(w.n_strands))
    tried = 0
    for strip in strips:
        if len(strip.tiles) < 3:
            continue
        # the last tile's end edge takes a tab (checked with the first tile left off)
        if label_flap(replace(strip, tiles=strip.tiles[1:].copy()), "A1") is None:
            continue
        first = strip.tiles[0]
        x0, y0, x1, y1 = first.bounds
        xm = (x0 + x1) / 2
        tiles = strip.tiles.copy()
        tiles[0] = shapely.MultiPolygon([
            shapely.intersection(first, shapely.box(x0 - 1, y0 - 1, xm - 0.01, y1 + 1)),
            shapely.intersection(first, shapely.box(xm + 0.01, y0 - 1, x1 + 1, y1 + 1))])
        tabbed = label_flap(replace(strip, tiles=tiles), "A1")
        tried += 1
        assert tabbed is not None
        tab = tabbed[0].flap
        assert shapely.distance(tab, strip.tiles[-1]) < 1e-6
        assert shapely.intersection(tab, shapely.union_all(tiles)).area <= 1e-6 * tab.area
    assert tried


def test_the_legend_shows_the_tab_entry_only_on_pages_with_label_tabs():
    from weavecut.papermodel.book import labelled_pieces, strip_sheets
    ws = list(snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2)))
    w = ws[-1]
    plan = plan_modules(w, heading=-np.pi / 2)
    colours = copy_colours(plan, palette("maritime-12"))
    area = PageArea(210.0, 297.0, 10.0)
    pieces, kinds = labelled_pieces(w, plan, colours, 20.0, "mixed", area)
    placed, sheets = strip_sheets(pieces, kinds, area, "t", colours, 3)
    assert sheets
    for n, sheet in enumerate(sheets, start=3):  # pages
        flaps = any(p.flap is not None for k, p in placed if k == n)
        legend = [t.text for t in texts_of(sheet.layers, {"page"})]
        assert ("tab: cut off after weaving" in legend) == flaps
        assert "cut" in legend and "on top" in legend


def test_a_full_page_could_fit_nothing():
    """The block tests refuse every mask on a page with no free cell, odd-sized too (the
    cells beyond the page's edge are taken)."""
    from weavecut.papermodel.packing_grid import Page, block_cores
    for ny, nx in ((5, 5), (5, 6), (6, 5), (7, 9), (17, 23)):
        page = Page(ny, nx, {})
        page.taken[:] = True
        for shape in ((1, 1), (2, 2), (1, 3), (3, 1), (5, 5), (9, 17)):
            for k in (1, 2, 4, 8):
                for core, _ in block_cores(np.ones(shape, dtype=bool), k):
                    if core is not None and min(page.taken.shape) >= max(shape):
                        assert not page.fits(k, [core])[0].any(), ((ny, nx), shape, k)


def test_best_spot_tries_a_longer_turn_when_a_shorter_one_fits_nowhere():
    """Rows 1 and 3 of a 4 x 4 page taken: a 3-cell bar fits standing nowhere (though every
    2 x 2 block keeps a free cell) but fits lying in row 0; the spot is found and free."""
    from weavecut.papermodel.packing import _best_spot
    from weavecut.papermodel.packing_grid import Options, Page
    page = Page(4, 4, {})
    page.taken[[1, 3]] = True
    standing, lying = np.ones((3, 1), dtype=bool), np.ones((1, 3), dtype=bool)
    turns = [(90.0, standing, np.zeros(2)), (0.0, lying, np.zeros(2)),
             (270.0, standing, np.zeros(2)), (180.0, lying, np.zeros(2))]  # half-turned
    opts = Options(turns)
    assert opts.rank[1][0] == 0  # the standing turn is tried first
    spot = _best_spot(page, opts, axis=1)
    assert spot is not None
    (iy, ix), angle, mask, _ = spot
    assert angle == 0.0
    assert not page.taken[iy:iy + mask.shape[0], ix:ix + mask.shape[1]][mask].any()


def test_card_colour_swatches_lie_under_the_texts():
    """The card colour page paints its swatches (and the strip drawn on it) first, so every
    text is drawn over them; each colour's two lines ("card navy (#rrggbb): sheet 1",
    "strands ...") stand beside the swatch of that colour."""
    from weavecut.layout.lasersetup import laser, material
    from weavecut.papermodel.cardkit import card_kit

    ws = list(snub_weaves(subdivide(inputs.get("square-grid:2x2"), 2)))
    kit = card_kit(ws, "maritime-4", material("card-300gsm"), laser(), (210.0, 297.0), 10.0,
                   20.0, 0.0, "test")
    shapes = kit.instructions.sheets[2].layers[0].shapes
    painted = [i for i, s in enumerate(shapes) if isinstance(s, Polygons)]
    written = [i for i, s in enumerate(shapes) if isinstance(s, Text)]
    assert painted and max(painted) < min(written)
    swatches = shapes[painted[0]]
    heads = [s for s in shapes if isinstance(s, Text) and re.match(r"card .*: sheets? \d", s.text)]
    assert len(heads) == swatches.n_polygons == len(set(kit.cut.colours))
    for head, ring, fill in zip(heads, swatches.rings(), swatches.fills):
        assert f"({fill}): sheet" in head.text
        assert ring[:, 1].min() <= head.y <= ring[:, 1].max() and head.x > ring[:, 0].max()