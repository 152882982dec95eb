"""The puzzle's paint recounted one face, one piece, one strand at a time (loops over the
weave, apart from the vectorised code): the front shows the level t-1 weave, the back the
level t weave in its parents' colours, touching colours and paint names are what the pieces
show, and the paper's rules hold (one colour per strand with an octagon, families from the
grandparents, light and dark siblings, border fragments in their family)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
import shapely

from weavecut import inputs
from weavecut.layout.colour_difference import colour_difference
from weavecut.mesh import edge_faces
from weavecut.layout.colour_difference import ciede2000, srgb_to_lab
from weavecut.puzzle.colouring import (UNPAINTED, _colour_index, _families, _main_colours,
                                       _Plan, _score, _search, _trials, colour_puzzle,
                                       on_top_of_octagon,
                                       palette_names)
from weavecut.puzzle.guides import piece_halves
from weavecut.puzzle.pieces import build_puzzle
from weavecut.subdivision import subdivide
from weavecut.weave.colour import palette

CASES = [("pentagon", 3), ("pentagon", 4), ("square-grid:2x2", 3), ("pentagon", 2)]


@lru_cache(maxsize=None)
def _puzzle(spec: str, levels: int):
    return build_puzzle(subdivide(inputs.get(spec), levels), size=300.0)


def case(spec: str, levels: int):
    """The puzzle (built once) and its paint, coloured in every test: mutmut maps a test to
    the functions it calls itself, so a colouring cached across tests would hide them."""
    puzzle, pal = _puzzle(spec, levels), palette("puzzle")
    return puzzle, pal, colour_puzzle(puzzle, pal, palette_names("puzzle", pal))


def _top(weave, tile: int) -> int:
    over, under = int(weave.tile_over[tile]), int(weave.tile_under[tile])
    return over if over >= 0 else under


def _face_paint(puzzle, colouring, face: int) -> str:
    """The colour of the strand on top of the level t-1 tile that level-t ``face`` lies in."""
    parent = puzzle.weaves[-2]
    tile = int(parent.face_tile[puzzle.hierarchy[-1].parent_face[face]])
    s = _top(parent, tile)
    return colouring.front_strands[s] if s >= 0 else UNPAINTED


@pytest.mark.parametrize("spec, levels", CASES)
def test_every_face_wears_the_strand_on_top_of_its_parent_tile(spec, levels):
    puzzle, _, colouring = case(spec, levels)
    n = puzzle.weaves[-1].mesh.n_faces
    assert colouring.face_colours.tolist() == [_face_paint(puzzle, colouring, f)
                                               for f in range(n)]


@pytest.mark.parametrize("spec, levels", CASES)
def test_each_front_half_shows_the_paint_of_the_face_under_it(spec, levels):
    """Half k of every piece lies over level-t faces of the colour front[:, k]: found by
    locating a point inside the half among the level-t faces."""
    puzzle, _, colouring = case(spec, levels)
    mesh = puzzle.weaves[-1].mesh
    faces = shapely.polygons(puzzle.to_mm(mesh.vertices[mesh.dense_faces()]))
    tree = shapely.STRtree(faces)
    halves = piece_halves(puzzle)
    for p in range(puzzle.n_pieces):
        for k in (0, 1):
            point = halves[p, k].representative_point()
            hit = [f for f in tree.query(point) if faces[f].covers(point)]
            assert hit, (p, k)
            assert colouring.front[p, k] == _face_paint(puzzle, colouring, hit[0]), (p, k)


@pytest.mark.parametrize("spec, levels", CASES)
def test_the_back_wears_the_front_colour_of_each_strands_parent(spec, levels):
    puzzle, _, colouring = case(spec, levels)
    child = puzzle.weaves[-1]
    for s, p in enumerate(child.parent_strand.tolist()):
        assert colouring.back_strands[s] == (colouring.front_strands[p] if p >= 0
                                             else UNPAINTED)
    for piece, tile in enumerate(puzzle.piece_tiles.tolist()):
        s = _top(child, tile)
        assert colouring.back[piece] == (colouring.back_strands[s] if s >= 0 else UNPAINTED)
    assert len(colouring.front_strands) == puzzle.weaves[-2].n_strands


@pytest.mark.parametrize("spec, levels", CASES)
def test_touching_pairs_and_smallest_difference_are_those_of_neighbouring_faces(spec, levels):
    puzzle, _, colouring = case(spec, levels)
    pairs = set()
    for a, b in edge_faces(puzzle.weaves[-1].mesh).tolist():
        if a >= 0 and b >= 0:
            ca, cb = colouring.face_colours[a], colouring.face_colours[b]
            if ca != cb and UNPAINTED not in (ca, cb):
                pairs.add(tuple(sorted((ca, cb))))
    assert sorted(map(tuple, colouring.touching.tolist())) == sorted(pairs)
    if pairs:
        smallest = min(float(colour_difference(a, b)) for a, b in pairs)
        assert colouring.smallest_difference == pytest.approx(smallest, abs=1e-9)
    else:
        assert colouring.smallest_difference is None


@pytest.mark.parametrize("spec, levels", CASES)
def test_paints_are_named_by_family_and_shade_in_palette_order(spec, levels):
    puzzle, pal, colouring = case(spec, levels)
    family_names = palette_names("puzzle", pal)
    assert family_names == ["green", "blue", "pink"]
    used = set(colouring.front_strands) - {UNPAINTED}
    assert set(colouring.names) == used
    for colour, name in colouring.names.items():
        f = next(i for i, fam in enumerate(pal.families) if colour in fam)
        assert name == f"{family_names[f]} {pal.families[f].index(colour) + 1}"
    flat = [c for fam in pal.families for c in fam]
    assert colouring.front_colours == sorted(set(colouring.front.ravel()) - {UNPAINTED},
                                             key=flat.index)
    assert colouring.back_colours == sorted(set(colouring.back) - {UNPAINTED}, key=flat.index)
    assert list(colouring.names) == sorted(colouring.names, key=flat.index)


def _main_strands(weave) -> list[int]:
    """Strands on top of an octagon (a two-face tile); at level 1 every strand on top."""
    main = sorted({int(weave.tile_over[t]) for t in range(weave.n_tiles)
                   if weave.tile_offsets[t + 1] - weave.tile_offsets[t] == 2
                   and weave.tile_over[t] >= 0})
    return main or sorted({int(s) for s in weave.tile_over.tolist() if s >= 0})


@pytest.mark.parametrize("spec, levels", CASES)
def test_strands_with_an_octagon_have_own_colours_in_their_grandparents_family(spec, levels):
    puzzle, pal, colouring = case(spec, levels)
    front = puzzle.weaves[-2]
    main = _main_strands(front)
    colours = [colouring.front_strands[s] for s in main]
    assert len(set(colours)) == len(main) <= len(pal.flat)
    family = {c: i for i, fam in enumerate(pal.families) for c in fam}
    if levels < 3:  # no grandparents: every strand is a family group of its own, balanced
        counts = np.bincount([family[c] for c in colours], minlength=len(pal.families))
        assert counts.max() - counts.min() <= 1
        return
    lineage = front.parent_strand
    by_parent: dict[int, set] = {}
    for s in main:
        if lineage[s] >= 0:
            by_parent.setdefault(int(lineage[s]), set()).add(family[colouring.front_strands[s]])
    assert by_parent and all(len(f) == 1 for f in by_parent.values())
    # families are balanced: no family holds more than its share plus one group
    counts = np.bincount([family[c] for c in colours], minlength=len(pal.families))
    biggest = max(sum(1 for s in main if lineage[s] == p) for p in by_parent)
    assert counts.max() - counts.min() <= biggest


@pytest.mark.parametrize("spec, levels", CASES[:3])
def test_the_two_longest_siblings_are_a_dark_and_light_pair(spec, levels):
    """Shades 2j and 2j + 1 of one family, for the two children of a level t-2 strand that
    lie on top of the most tiles (the lower strand number first on a tie)."""
    puzzle, pal, colouring = case(spec, levels)
    front = puzzle.weaves[-2]
    main = _main_strands(front)
    over = {s: int(front.visit_over[front.strand_offsets[s]:front.strand_offsets[s + 1]].sum())
            for s in main}
    groups: dict[int, list[int]] = {}
    for s in main:
        groups.setdefault(int(front.parent_strand[s]), []).append(s)
    pairs = 0
    for p, members in groups.items():
        if p < 0 or len(members) < 2:
            continue
        a, b = sorted(members, key=lambda s: (-over[s], s))[:2]
        shades = []
        for s in (a, b):
            colour = colouring.front_strands[s]
            fam = next(f for f in pal.families if colour in f)
            shades.append(fam.index(colour))
        assert sorted(shades)[0] % 2 == 0 and abs(shades[0] - shades[1]) == 1, (p, shades)
        pairs += 1
    assert pairs > 0


@pytest.mark.parametrize("spec, levels", CASES[:3])
def test_border_fragments_take_a_colour_of_their_parents_family(spec, levels):
    """A strand on top of tiles but of no octagon wears a colour that a strand with an octagon
    of its grandparent's family wears: the one whose smallest difference to the strands it
    touches (with an octagon, or fragments before it) is largest."""
    puzzle, pal, colouring = case(spec, levels)
    front = puzzle.weaves[-2]
    main = set(_main_strands(front))
    family = {c: i for i, fam in enumerate(pal.families) for c in fam}
    strand_of = [_face_strand(puzzle, f) for f in range(puzzle.weaves[-1].mesh.n_faces)]
    touching: dict[int, set] = {}
    for a, b in edge_faces(puzzle.weaves[-1].mesh).tolist():
        if a >= 0 and b >= 0 and strand_of[a] != strand_of[b] and min(strand_of[a],
                                                                        strand_of[b]) >= 0:
            touching.setdefault(strand_of[a], set()).add(strand_of[b])
            touching.setdefault(strand_of[b], set()).add(strand_of[a])
    fragments = sorted({int(s) for s in front.tile_over.tolist() if s >= 0} - main)
    assert fragments
    checked = 0
    for s in fragments:
        colour = colouring.front_strands[s]
        assert colour != UNPAINTED
        p = int(front.parent_strand[s])
        siblings = [m for m in main if front.parent_strand[m] == p]
        if p >= 0 and siblings:
            fam = family[colouring.front_strands[siblings[0]]]
            candidates = {colouring.front_strands[m] for m in main
                          if family[colouring.front_strands[m]] == fam}
        else:  # no sibling with an octagon: any colour a strand with an octagon wears
            candidates = {colouring.front_strands[m] for m in main}
        assert colour in candidates
        near = [colouring.front_strands[n] for n in touching.get(s, ())
                if n in main or (n < s and n in fragments)]
        if near:
            def worst(c):
                return min(float(colour_difference(c, n)) for n in near)
            assert worst(colour) >= max(worst(c) for c in candidates) - 1e-9
            checked += 1
    assert checked


def _face_strand(puzzle, face: int) -> int:
    parent = puzzle.weaves[-2]
    return _top(parent, int(parent.face_tile[puzzle.hierarchy[-1].parent_face[face]]))


def test_family_names_come_from_the_preset_or_are_numbered(tmp_path):
    pal = palette("puzzle")
    assert palette_names("puzzle", pal) == ["green", "blue", "pink"]
    path = tmp_path / "two.toml"
    path.write_text('family_names = ["sea"]\nfamilies = [["#06426e", "#2eaed0"], '
                    '["#730a35", "#b36d7e"], ["#323d0d", "#2aad78"]]\n', encoding="utf-8")
    own = palette(str(path))
    assert palette_names(str(path), own) == ["sea", "family 2", "family 3"]
    # a palette that is no preset (built in code) has numbered families
    assert palette_names("no-such-palette", own) == ["family 1", "family 2", "family 3"]
    # without names the paints are called by family number and shade
    puzzle = case("pentagon", 3)[0]
    names = colour_puzzle(puzzle, pal).names
    for colour, name in names.items():
        f = next(i for i, fam in enumerate(pal.families) if colour in fam)
        assert name == f"family {f + 1} {pal.families[f].index(colour) + 1}"


def _strand_touching(puzzle) -> set:
    """Pairs of level t-1 strands whose painted faces share an edge."""
    strand_of = [_face_strand(puzzle, f) for f in range(puzzle.weaves[-1].mesh.n_faces)]
    pairs = set()
    for a, b in edge_faces(puzzle.weaves[-1].mesh).tolist():
        if a >= 0 and b >= 0:
            sa, sb = strand_of[a], strand_of[b]
            if sa != sb and min(sa, sb) >= 0:
                pairs.add((min(sa, sb), max(sa, sb)))
    return pairs


def _paired(front, main) -> set:
    """The two longest strands (most tiles on top) of every group of two or more siblings."""
    over = {s: int(front.visit_over[front.strand_offsets[s]:front.strand_offsets[s + 1]].sum())
            for s in main}
    groups: dict[int, list[int]] = {}
    for s in main:
        p = int(front.parent_strand[s]) if front.parent_strand is not None else -1
        groups.setdefault(p if p >= 0 else -1 - s, []).append(s)
    return {s for members in groups.values() if len(members) >= 2
            for s in sorted(members, key=lambda s: (-over[s], s))[:2]}


@pytest.mark.parametrize("spec, levels", CASES[:3])
def test_no_swap_of_shades_on_the_worst_touching_pairs_improves_the_colouring(spec, levels):
    """The local search's promise, checked by trying its moves: the fewest touching strands
    sharing a colour, then the ten smallest differences as large as they go. No swap of two
    single strands' shades in one family, and no light/dark flip of a sibling pair, that
    involves a strand of the worst touching pairs raises that score."""
    puzzle, pal, colouring = case(spec, levels)
    front = puzzle.weaves[-2]
    main = _main_strands(front)
    pairs = [p for p in sorted(_strand_touching(puzzle)) if p[0] in main and p[1] in main]
    family = {c: i for i, fam in enumerate(pal.families) for c in fam}
    colour = {s: colouring.front_strands[s] for s in main}

    def score(col):
        d = [float(colour_difference(col[a], col[b])) for a, b in pairs]
        return (-sum(x == 0 for x in d), tuple(sorted(round(x, 6) for x in d if x > 0)[:10]))

    best = score(colour)
    d = sorted(float(colour_difference(colour[a], colour[b])) for a, b in pairs)
    cut = d[min(11, len(d) - 1)]
    worst = {s for a, b in pairs if float(colour_difference(colour[a], colour[b])) < cut
             for s in (a, b)}
    paired = _paired(front, main)
    tried = 0
    for k in sorted(worst):
        if k in paired:
            mates = [m for m in paired if m != k and front.parent_strand[m]
                     == front.parent_strand[k] and family[colour[m]] == family[colour[k]]]
            others = mates[:1]
        else:
            others = [o for o in main if o != k and o not in paired
                      and family[colour[o]] == family[colour[k]]]
        for o in others:
            trial = dict(colour)
            trial[k], trial[o] = colour[o], colour[k]
            assert not score(trial) > best, (k, o)
            tried += 1
    assert tried > 0


@pytest.mark.parametrize("spec, levels", CASES[:3])
def test_on_top_of_octagon_is_a_mask_of_the_strands_with_an_octagon(spec, levels):
    front = _puzzle(spec, levels).weaves[-2]
    mask = on_top_of_octagon(front)
    assert np.arange(front.n_strands)[mask].tolist() == _main_strands(front)


def test_families_balance_the_colour_count_then_keep_touching_groups_apart():
    """Three groups of one strand each and two families: the first two take one family each
    (balance first); the third could join either, and joins the one of no group it touches
    (strands 0 and 2 touch, so it takes group 1's family, and the other way round)."""
    group = np.arange(3)
    for touching, want in (([[0, 2]], [0, 1, 1]), ([[1, 2]], [0, 1, 0])):
        pairs = np.array(touching, dtype=np.int64)
        assert _families(group, 3, np.arange(3), pairs, 2).tolist() == want


def test_a_fragment_without_a_parent_may_take_any_colour_with_an_octagon():
    """At level 2 there is no level t-2 (no families from grandparents): the square grid's
    border fragments have no parent, so each may wear any colour a strand with an octagon
    wears, and wears the one whose smallest difference to the strands it touches is largest
    (the first in palette order on a tie), not one of a single family."""
    puzzle, pal, colouring = case("square-grid:2x2", 2)
    front = puzzle.weaves[-2]
    main = _main_strands(front)
    fragments = sorted({int(s) for s in front.tile_over.tolist() if s >= 0} - set(main))
    flat = [c for fam in pal.families for c in fam]
    candidates = sorted({colouring.front_strands[m] for m in main}, key=flat.index)
    family = {c: i for i, fam in enumerate(pal.families) for c in fam}
    assert len({family[c] for c in candidates}) == len(pal.families)
    near_of: dict[int, set] = {}
    for a, b in _strand_touching(puzzle):
        near_of.setdefault(a, set()).add(b)
        near_of.setdefault(b, set()).add(a)
    checked = 0
    for s in fragments:
        near = [colouring.front_strands[n] for n in near_of.get(s, ())
                if n in main or (n < s and n in fragments)]
        if not near:
            continue

        def worst(c):
            return min(float(colour_difference(c, n)) for n in near)
        best = max(worst(c) for c in candidates)
        assert colouring.front_strands[s] == next(c for c in candidates
                                                  if worst(c) >= best - 1e-9), s
        checked += 1
    assert checked == len(fragments) > 0


def _one_family_plan(n: int, shades: int, pairs) -> _Plan:
    """``n`` single strands (no sibling pairs), all in one family of the puzzle palette's first
    ``shades`` greens, touching as ``pairs`` (listed by strand, as colour_puzzle lists them)."""
    greens = list(palette("puzzle").families[0][:shades])
    lab = srgb_to_lab(greens)
    return _Plan(np.arange(n), np.arange(n), np.zeros(n, dtype=np.int64), np.zeros(n, bool),
                 greens, np.array([0]), np.array([shades]), ciede2000(lab[:, None], lab[None]),
                 np.array(pairs, dtype=np.int64).reshape(-1, 2), [])


def _hill_climb(plan: _Plan, slot: list[int], worst: int = 12) -> list[int]:
    """The search as its docstring states it, in plain Python: each round, the strands of the
    ``worst`` touching pairs of smallest difference (pairs of equal difference in the order
    they are listed), worst first, each strand's moves in turn (swap shades with every other
    strand, in strand order, then every other shade), the first move that raises the score
    (fewest equal colours touching, then the ten smallest differences) is kept."""
    shades = int(plan.family_size[0])
    pairs = plan.pairs.tolist()

    def differences(slot):
        return [float(plan.difference[slot[a] % shades, slot[b] % shades]) for a, b in pairs]

    def score(slot):
        d = differences(slot)
        return (-d.count(0.0), tuple(sorted(round(x, 6) for x in d if x > 0)[:10]))

    def moves(slot, k):
        for o in range(len(slot)):
            if o != k:
                trial = list(slot)
                trial[k], trial[o] = slot[o], slot[k]
                yield trial
        for value in range(shades):
            if value != slot[k] % shades:
                yield slot[:k] + [value] + slot[k + 1:]

    for _ in range(400):
        d = differences(slot)
        ranked = sorted(range(len(pairs)), key=d.__getitem__)[:worst]  # sorted() is stable
        strands = dict.fromkeys(s for i in ranked for s in pairs[i])
        best = score(slot)
        better = next((t for k in strands for t in moves(slot, k) if score(t) > best), None)
        if better is None:
            return slot
        slot = better
    return slot


@pytest.mark.parametrize("seed", range(12))
def test_the_colour_search_breaks_ties_between_equal_differences_in_pair_order(seed):
    """Twelve strands in four shades touch in 18 to 33 pairs, so many pairs share a colour
    pair (an equal difference). Which of them the search tries first decides where it ends:
    the search must take them in the order the pairs are listed (a sort that does not keep
    that order, such as numpy's default one, gives another colouring, and one that depends
    on the machine's sort routine), as the plain-Python search of its docstring does."""
    rng = np.random.default_rng(seed)
    every = np.array([(a, b) for a in range(12) for b in range(a + 1, 12)])
    pairs = every[np.sort(rng.choice(len(every), int(rng.integers(18, 34)), replace=False))]
    plan = _one_family_plan(12, 4, pairs)
    assert _search(plan, np.arange(12)).tolist() == _hill_climb(plan, list(range(12)))


def _hand_plan(colours, family, group, paired, pairs, fragments=()) -> _Plan:
    """A plan for strands 0 .. len(family) - 1 with an octagon, all in one family of the shades
    ``colours``: their groups, which hold half of a light/dark pair, the touching pairs and
    the fragments ((strand, candidate main strands) each)."""
    lab = srgb_to_lab(list(colours))
    n = len(family)
    return _Plan(np.arange(n), np.array(group, dtype=np.int64).reshape(n),
                 np.array(family, dtype=np.int64).reshape(n), np.array(paired, bool).reshape(n),
                 list(colours), np.array([0]), np.array([len(colours)]),
                 ciede2000(lab[:, None], lab[None]),
                 np.array(pairs, dtype=np.int64).reshape(-1, 2),
                 [(s, np.array(m, dtype=np.int64)) for s, m in fragments])


def test_every_fragment_is_painted_even_one_that_touches_nothing():
    """Strands 0-2 wear greens 0-2. Fragment 3 touches nothing: it takes its first candidate
    colour; fragment 4 touches strand 0 and takes whichever of greens 1 and 2 differs more
    from green 0; fragment 5, the last strand, touches nothing either. A strand that touches
    one but is on top of no tile (6) stays unpainted (-1), as do fragments before the
    fragments' pass."""
    greens = list(palette("puzzle").families[0][:3])
    fragments = [(3, [0, 1, 2]), (4, [1, 2]), (5, [1, 2])]
    plan = _hand_plan(greens, [0] * 3, [0, 1, 2], [False] * 3, [(0, 4)], fragments)
    slot = np.arange(3)
    assert _main_colours(plan, slot).tolist() == [0, 1, 2, -1, -1, -1]
    far = max((1, 2), key=lambda c: (colour_difference(greens[c], greens[0]), -c))
    assert _colour_index(plan, slot).tolist() == [0, 1, 2, 0, far, 1]
    under = _hand_plan(greens, [0] * 3, [0, 1, 2], [False] * 3, [(0, 4), (2, 6)], fragments)
    assert _main_colours(under, slot).tolist() == [0, 1, 2, -1, -1, -1, -1]
    assert _colour_index(under, slot).tolist()[6] == -1


@pytest.mark.parametrize("n", [0, 1])
def test_a_plan_of_one_strand_or_none(n):
    """No strand: nothing to paint and nothing to search. One strand touching nothing: it
    wears its family's first shade, and the search leaves it there."""
    plan = _hand_plan(["#2aad78", "#323d0d"], [0] * n, list(range(n)), [False] * n, [])
    assert _main_colours(plan, np.zeros(n, dtype=np.int64)).tolist() == [0] * n
    assert _search(plan, np.zeros(n, dtype=np.int64)).tolist() == [0] * n
    assert _score(plan, np.zeros(n, dtype=np.int64)) == (0, ())


def test_the_score_counts_equal_colours_then_every_difference_to_a_millionth():
    """Two greys 0.75 CIEDE2000 apart (under 1, still a difference): the score of two
    touching strands in them is no equal pair and that difference, rounded to 1e-6 (float
    noise below that is no gain); in one grey, one equal pair and no difference."""
    greys = ["#808080", "#828282"]
    plan = _hand_plan(greys, [0, 0], [0, 1], [False, False], [(0, 1)])
    d = float(colour_difference(*greys))
    assert 0 < d < 1
    assert _score(plan, np.array([0, 1])) == (0, (round(d, 6),))
    assert _score(plan, np.array([1, 1])) == (-1, ())


def test_a_sibling_pair_flips_or_trades_with_another_pair_of_its_family():
    """Strands 0, 1 are the sibling pair of group 0, strands 2, 3 that of group 1, strand 4 a
    single, all in one family of seven shades (no shade repeats, so no recolouring). A pair
    strand's moves: flip its pair's light and dark, then trade shades with every other pair
    of the family (the strand takes the other pair's first strand's shade, its mate the
    second's); the lone single has no other single to swap with."""
    greens = list(palette("puzzle").families[0])
    plan = _hand_plan(greens, [0] * 5, [0, 0, 1, 1, 2], [True] * 4 + [False], [])
    slot = np.arange(5)
    assert [t.tolist() for t in _trials(plan, slot, 0)] == [[1, 0, 2, 3, 4], [2, 3, 0, 1, 4]]
    assert [t.tolist() for t in _trials(plan, slot, 3)] == [[0, 1, 3, 2, 4], [3, 2, 1, 0, 4]]
    assert list(_trials(plan, slot, 4)) == []
