"""The puzzle's paint: the front shows the level t-1 weave, the back the level t weave.

The paper (section 6): the front has "a total of 20 different colors", "reduced to three
primary colors - green, blue, and pink"; "the light and dark green strands originate from one
strand and are thus interwoven"; tiles with a single colour "are always at the center of the
larger octagons"; on the back "the colors of the strand pairs ... correspond to the front-side
color of the enclosed puzzle-piece". weave-cut makes that a rule:

- **One colour per front strand.** Every level t-1 strand that is on top of an octagon gets its
  own colour (20 on the paper's pentagon). A strand with no octagon (a short fragment along the
  border, on top of boundary pentagons only) takes one of the colours of its parent's family
  (of every family where it has no parent, as at level 2): the one that differs most from
  every strand it touches, so it never merges with a neighbour.
- **Families from the grandparents.** Each level t-2 strand takes a family (a hue: green, blue,
  pink); its descendants share it. Families are balanced by the number of colours they must
  hold, and strands whose descendants touch go to different families where the balance allows.
- **Siblings light and dark.** The two longest children of one level t-2 strand take a
  dark/light pair of their family (palette shades 2k, 2k + 1); other children take the
  family's remaining shades.
- **Touching strands stay apart.** Within those rules, a deterministic local search (swap
  pairs, flip a pair's light and dark, swap single shades) maximises the smallest CIEDE2000
  difference between any two different colours that touch on the front.
- **The back.** A level t strand takes the front colour of its parent strand, so a strand pair
  on the back has the colour of the piece it encloses on the front: the same paints serve both
  sides.

Every level t pentagon is painted in the colour of the strand on top of its parent's level t-1
tile. Ring hexagons and the frame stay unpainted (natural wood).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from .. import presets
from ..mesh import edge_faces
from ..numeric import distinct
from ..layout.colour_difference import srgb_to_lab, ciede2000
from ..weave.colour import Palette
from ..weave.model import Weave
from .pieces import Puzzle

UNPAINTED = "#ffffff"


@dataclass(frozen=True, eq=False)
class Colouring:
    """Front and back paint of every piece.

    Parameters
    ----------
    front : (P, 2) object, the colours of every piece's two halves (an enneagon's one painted
        half twice; the same colour twice on a single-coloured piece)
    back : (P,) object, one colour per piece
    front_strands : colour of every level t-1 strand
    back_strands : colour of every level t strand
    face_colours : (F_t,) object, front colour of every level t pentagon
    names : colour -> paint name (``"green 3"``)
    touching : (K, 2) object, every pair of different colours that touch on the front, once
    """

    front: NDArray[np.object_]
    back: NDArray[np.object_]
    front_strands: tuple[str, ...]
    back_strands: tuple[str, ...]
    face_colours: NDArray[np.object_]
    names: dict[str, str]
    touching: NDArray[np.object_]

    @cached_property
    def smallest_difference(self) -> float | None:
        """The smallest CIEDE2000 difference between two different touching front colours;
        None when no two different colours touch (a one-colour palette)."""
        if not len(self.touching):
            return None
        return float(ciede2000(srgb_to_lab(self.touching[:, 0].tolist()),
                               srgb_to_lab(self.touching[:, 1].tolist())).min())

    @property
    def front_colours(self) -> list[str]:
        """The distinct front paints, in palette order."""
        return _ordered(self.front.ravel(), self.names)

    @property
    def back_colours(self) -> list[str]:
        """The distinct back paints, in palette order."""
        return _ordered(self.back, self.names)


def _ordered(colours, names: dict[str, str]) -> list[str]:
    order = {c: k for k, c in enumerate(names)}
    return sorted(set(colours) - {UNPAINTED}, key=lambda c: (order.get(c, len(order)), c))


def palette_names(name: str, pal: Palette) -> list[str]:
    """Family names of a palette preset (``family_names``), else "family 1", "family 2"..."""
    try:
        doc = presets.load("palettes", name)
    except presets.PresetError:
        doc = {}
    given = doc.get("family_names", [])
    return [str(given[k]) if k < len(given) else f"family {k + 1}"
            for k in range(len(pal.families))]


def colour_puzzle(puzzle: Puzzle, pal: Palette, family_names: list[str] | None = None
                  ) -> Colouring:
    """Front and back colours of every piece (see the module docstring)."""
    parent, child = puzzle.weaves[-2], puzzle.weaves[-1]
    lineage = parent.parent_strand if puzzle.levels >= 3 else None
    family_names = family_names or [f"family {k + 1}" for k in range(len(pal.families))]
    face_strand = top_strand(parent)[parent.face_tile[puzzle.hierarchy[-1].parent_face]]
    face_pairs = _inner_edge_faces(child.mesh)
    strand_pairs = face_strand[face_pairs]
    strand_pairs = strand_pairs[(strand_pairs >= 0).all(axis=1)
                                & (strand_pairs[:, 0] != strand_pairs[:, 1])]
    strand_pairs = distinct(np.sort(strand_pairs, axis=1), axis=0).reshape(-1, 2)
    colours, names = strand_paint(parent, lineage, strand_pairs, pal, family_names)
    front_strands = np.array(colours + [UNPAINTED], dtype=object)
    face_colours = front_strands[face_strand]  # strand -1 -> UNPAINTED
    # the back: a level t strand wears its parent's front colour
    ps = child.parent_strand
    back_strands = front_strands[np.where(ps >= 0, ps, -1)]
    tiles = puzzle.piece_tiles
    back = np.append(back_strands, UNPAINTED).astype(object)[top_strand(child)[tiles]]
    first_face = child.tile_faces[child.tile_offsets[tiles]]
    last_face = child.tile_faces[child.tile_offsets[tiles + 1] - 1]
    front = np.column_stack([face_colours[first_face], face_colours[last_face]])
    touch = face_colours[face_pairs].astype(str)
    touch = touch[(touch[:, 0] != touch[:, 1]) & (touch != UNPAINTED).all(axis=1)]
    touch = distinct(np.sort(touch, axis=1), axis=0).reshape(-1, 2).astype(object)
    return Colouring(front, back, tuple(front_strands[:-1]), tuple(back_strands.tolist()),
                     face_colours, names, touch)


def top_strand(weave: Weave) -> NDArray[np.int32]:
    """(T,) the strand on top of every tile, or the one below where none is on top (-1: none)."""
    return np.where(weave.tile_over >= 0, weave.tile_over, weave.tile_under)


def _inner_edge_faces(mesh) -> NDArray[np.int64]:
    """(K, 2) the two faces of every inner edge."""
    ef = edge_faces(mesh)
    return ef[(ef >= 0).all(axis=1)].astype(np.int64)


def on_top_of_octagon(weave: Weave) -> NDArray[np.bool_]:
    """(S,) True for strands on top of at least one octagon (a two-face tile)."""
    octagon = np.diff(weave.tile_offsets) == 2
    out = np.zeros(weave.n_strands, dtype=bool)
    over = weave.tile_over[octagon]
    out[over[over >= 0]] = True
    return out


@dataclass(frozen=True)
class _Plan:
    """The fixed part of the search: strands with an octagon (``main``), their groups
    (siblings), families, and every candidate colour with its differences."""

    main: NDArray[np.int64]
    group: NDArray[np.int64]
    family: NDArray[np.int64]  # per main strand
    paired: NDArray[np.bool_]  # per main strand: holds half of its group's light/dark pair
    colours: list[str]  # every shade of every family, family by family
    family_start: NDArray[np.int64]  # first colour of every family in ``colours``
    family_size: NDArray[np.int64]  # shades per family (reused when more strands need one)
    difference: NDArray[np.float64]  # (C, C) CIEDE2000 between colours
    pairs: NDArray[np.int64]  # (K, 2) touching strands (all strands)
    fragments: list[tuple[int, NDArray[np.int64]]]  # (strand, candidate colours) each


def strand_paint(weave: Weave, lineage, strand_pairs, pal: Palette,
                 family_names: list[str]) -> tuple[list[str], dict[str, str]]:
    """A colour for every strand of ``weave`` (level t-1) and the names of the paints used.

    Parameters
    ----------
    lineage : (S,) level t-2 parent of every strand (-1: none), or None
    strand_pairs : (K, 2) strands whose painted areas touch on the front
    """
    plan = _plan(weave, lineage, strand_pairs, pal)
    slot = _search(plan, _initial_slots(plan))
    colour_of = _colour_index(plan, slot)
    colours = [UNPAINTED] * weave.n_strands
    for s, c in enumerate(colour_of.tolist()):  # strands, not mesh elements
        if c >= 0:
            colours[s] = plan.colours[c]
    family_of = np.searchsorted(plan.family_start, np.arange(len(plan.colours)), side="right") - 1
    names = {}
    for c, colour in enumerate(plan.colours):
        rank = c - plan.family_start[family_of[c]]
        names.setdefault(colour, f"{family_names[family_of[c]]} {rank + 1}")
    used = set(colours)
    return colours, {c: n for c, n in names.items() if c in used}


def _plan(weave: Weave, lineage, strand_pairs, pal: Palette) -> _Plan:
    n = weave.n_strands
    main = np.flatnonzero(on_top_of_octagon(weave))
    if not len(main):  # level 1 has no octagons: every strand on top of a tile is painted
        main = distinct(weave.tile_over[weave.tile_over >= 0]).astype(np.int64)
    parent = lineage if lineage is not None else np.full(n, -1, dtype=np.int32)
    keys, group = np.unique(np.where(parent[main] >= 0, parent[main], -1 - main),
                            return_inverse=True)
    lengths = np.bincount(weave.visit_strand[weave.visit_over], minlength=n)
    k = len(pal.families)
    group_family = _families(group, len(keys), main, strand_pairs, k)
    family = group_family[group]
    colours = [c for fam in pal.families for c in fam]
    family_size = np.array([len(f) for f in pal.families], dtype=np.int64)
    family_start = np.r_[0, np.cumsum(family_size)[:-1]].astype(np.int64)
    lab = srgb_to_lab(colours)
    difference = ciede2000(lab[:, None], lab[None])
    # siblings: a group's two longest strands hold a pair
    order = np.lexsort((main, -lengths[main], group))
    rank = np.empty(len(main), dtype=np.int64)
    first = np.r_[True, group[order][1:] != group[order][:-1]]
    rank[order] = np.arange(len(main)) - np.maximum.accumulate(np.where(first, np.arange(
        len(main)), 0))
    size = np.bincount(group)
    paired = (size[group] >= 2) & (rank < 2)
    # fragments: strands on top of no octagon take a colour of their parent's family
    key_family = dict(zip(keys.tolist(), group_family.tolist()))
    fragments = []
    painted_tile = np.zeros(n, dtype=bool)
    painted_tile[weave.tile_over[weave.tile_over >= 0]] = True
    painted_tile[main] = False
    for s in np.flatnonzero(painted_tile).tolist():  # a few dozen border fragments
        f = key_family.get(int(parent[s]), -1) if parent[s] >= 0 else -1
        members = np.flatnonzero(family == f) if f >= 0 else np.arange(len(main))
        fragments.append((s, members))
    return _Plan(main, group, family, paired, colours, family_start, family_size, difference,
                 np.asarray(strand_pairs, dtype=np.int64).reshape(-1, 2), fragments)


def _families(group, n_groups: int, main, strand_pairs, k: int) -> NDArray[np.int64]:
    """A family per group: balanced by colour count, touching groups apart where possible."""
    weight = np.bincount(group, minlength=n_groups)
    group_of = np.full(int(max(main.max(initial=0), strand_pairs.max(initial=0))) + 1, -1)
    group_of[main] = group
    g_pairs = group_of[strand_pairs] if len(strand_pairs) else np.empty((0, 2), dtype=int)
    g_pairs = g_pairs[(g_pairs >= 0).all(axis=1) & (g_pairs[:, 0] != g_pairs[:, 1])]
    near = [set() for _ in range(n_groups)]
    for a, b in g_pairs.tolist():  # group pairs, a few dozen
        near[a].add(b)
        near[b].add(a)
    out = np.full(n_groups, -1, dtype=np.int64)
    load = np.zeros(k, dtype=np.int64)
    for g in np.lexsort((np.arange(n_groups), -weight)).tolist():
        clash = [sum(out[m] == f for m in near[g]) for f in range(k)]
        f = min(range(k), key=lambda f: (load[f] + weight[g], clash[f], f))
        out[g] = f
        load[f] += weight[g]
    return out


def _initial_slots(plan: _Plan) -> NDArray[np.int64]:
    """Shade index (within the family) per main strand: each group's pair takes the family's
    next dark/light pair (2j, 2j + 1), the other strands the free shades after them."""
    slot = np.full(len(plan.main), -1, dtype=np.int64)
    for f in distinct(plan.family).tolist():  # three families
        members = np.flatnonzero(plan.family == f)
        pair_members = members[plan.paired[members]]
        pair_members = pair_members[np.lexsort((plan.main[pair_members],
                                                plan.group[pair_members]))]
        slot[pair_members] = np.arange(len(pair_members))
        singles = members[~plan.paired[members]]
        slot[singles] = len(pair_members) + np.arange(len(singles))
    return slot


def _colour_index(plan: _Plan, slot: NDArray[np.int64]) -> NDArray[np.int64]:
    """(S,) colour (index into ``plan.colours``) of every strand; fragments pick the colour of
    their candidates that differs most from what they touch (-1: unpainted)."""
    out = _main_colours(plan, slot)
    for s, members in plan.fragments:  # a few dozen border fragments
        near = np.concatenate([plan.pairs[plan.pairs[:, 0] == s, 1],
                               plan.pairs[plan.pairs[:, 1] == s, 0]])
        near = out[near][out[near] >= 0]
        candidates = distinct(out[plan.main[members]])
        if not len(near):
            out[s] = candidates.min()
            continue
        worst = plan.difference[np.ix_(candidates, near)].min(axis=1)
        out[s] = candidates[np.lexsort((candidates, -worst))[0]]
    return out


def _main_colours(plan: _Plan, slot: NDArray[np.int64]) -> NDArray[np.int64]:
    """(S,) colour of every strand with an octagon (-1 elsewhere); a family with more strands
    than shades reuses them in order."""
    n = max(int(plan.pairs.max(initial=-1)), int(plan.main.max(initial=-1)),
            max((s for s, _ in plan.fragments), default=-1)) + 1
    out = np.full(n, -1, dtype=np.int64)
    out[plan.main] = plan.family_start[plan.family] + slot % plan.family_size[plan.family]
    return out


def _differences(plan: _Plan, colour: NDArray[np.int64]) -> NDArray[np.float64]:
    """(K,) CIEDE2000 across every touching pair of strands with an octagon (inf elsewhere)."""
    a, b = colour[plan.pairs[:, 0]], colour[plan.pairs[:, 1]]
    ok = (a >= 0) & (b >= 0)
    return np.where(ok, plan.difference[np.maximum(a, 0), np.maximum(b, 0)], np.inf)


def _score(plan: _Plan, slot: NDArray[np.int64]) -> tuple:
    """Higher is better: fewer touching strands sharing a colour, then the ten smallest
    differences between touching different colours, ascending."""
    d = _differences(plan, _main_colours(plan, slot))
    return (-int((d == 0).sum()), tuple(np.round(np.sort(d[d > 0])[:10], 6).tolist()))


def _trials(plan: _Plan, slot: NDArray[np.int64], k: int):
    """Slot arrays one move away that involve main strand ``k`` and keep families and sibling
    pairs: swap with another single strand of its family, recolour it (when its family has
    more strands than shades, so shades repeat anyway), or flip or trade its pair."""
    family = np.flatnonzero(plan.family == plan.family[k])
    size = int(plan.family_size[plan.family[k]])

    def swapped(*pairs):
        trial = slot.copy()
        for a, b in pairs:
            trial[a], trial[b] = trial[b], trial[a]
        return trial

    if not plan.paired[k]:
        yield from (swapped((k, int(o))) for o in family[~plan.paired[family]] if o != k)
        if len(family) > size:
            for value in range(size):
                if value != slot[k] % size:
                    trial = slot.copy()
                    trial[k] = value
                    yield trial
        return
    mate = int(family[plan.paired[family] & (plan.group[family] == plan.group[k])
                      & (family != k)][0])
    yield swapped((k, mate))
    for g in distinct(plan.group[family[plan.paired[family]]]).tolist():
        if g != plan.group[k]:
            other = family[plan.paired[family] & (plan.group[family] == g)]
            yield swapped((k, int(other[0])), (mate, int(other[1])))


def _search(plan: _Plan, slot: NDArray[np.int64], rounds: int = 400,
            worst: int = 12) -> NDArray[np.int64]:
    """Hill-climb on the worst touching pairs: try the moves that involve the strands of the
    ``worst`` pairs, worst first (see ``_trials``), keep the first that raises the score; stop
    when none does (or after ``rounds``). Pairs of equal difference are taken in the order
    ``plan.pairs`` lists them (a stable sort): which is tried first decides where the search
    ends, and an unstable sort's order depends on the machine's sort routine."""
    index = np.full(int(plan.main.max(initial=-1)) + 1, -1)
    index[plan.main] = np.arange(len(plan.main))
    best = _score(plan, slot)
    for _ in range(rounds):  # bounded: each round raises the score or stops
        d = _differences(plan, _main_colours(plan, slot))
        order = np.argsort(d, kind="stable")[:worst]
        strands = dict.fromkeys(index[plan.pairs[order[np.isfinite(d[order])]]].ravel().tolist())
        found = None
        for k in strands:
            for trial in _trials(plan, slot, k):
                score = _score(plan, trial)
                if score > best:
                    found, best = trial, score
                    break
            if found is not None:
                break
        if found is None:
            break
        slot = found
    return slot
