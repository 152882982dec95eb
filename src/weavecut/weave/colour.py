"""Strand colours from palette presets: crossing strands differ, children shade their parent.

A palette is either flat (``colours``) or made of families of shades (``families``). With
families and a parent level, every parent strand takes a family (strands that cross take
different ones where the palette allows) and its child strands the family's shades, so the
two interwoven children of a strand share a hue. Assignment is deterministic.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import presets
from ..numeric import distinct
from .model import Weave


@dataclass(frozen=True)
class Palette:
    """A palette preset: its name, its families of shades and what a maker calls each colour
    (``colour_names``, or a family's name and the shade's number; "" where the preset names
    none)."""

    name: str
    families: tuple[tuple[str, ...], ...]
    names: tuple[str, ...] = ()

    def called(self, colour: str) -> str:
        """"orange (#e69f00)", or the bare colour where the palette names none."""
        name = dict(zip(self.flat, self.names)).get(colour, "")
        return f"{name} ({colour})" if name else colour

    @property
    def flat(self) -> tuple[str, ...]:
        return tuple(c for family in self.families for c in family)

    @property
    def shaded(self) -> bool:
        return min(len(f) for f in self.families) >= 2


def palette(name: str) -> Palette:
    """Load a palette preset by name (``templates/palettes/NAME.toml``) or path."""
    doc = presets.load("palettes", name)
    if "families" in doc:
        families = tuple(tuple(f) for f in doc["families"])
    elif "colours" in doc:
        families = tuple((c,) for c in doc["colours"])
    else:
        raise presets.PresetError(f"palette {name!r} needs 'colours' or 'families'")
    for colour in (c for f in families for c in f):
        if not (isinstance(colour, str) and len(colour) == 7 and colour.startswith("#")):
            raise presets.PresetError(f"palette {name!r}: {colour!r} is not a #rrggbb colour")
    if not families or not all(families):
        raise presets.PresetError(f"palette {name!r} has no colours")
    return Palette(str(doc.get("name", name)), families, _names(name, doc, families))


def _names(name: str, doc: dict, families) -> tuple[str, ...]:
    """A name per colour of ``families`` (flat order), from ``colour_names`` (one per colour)
    or ``family_names`` (a family's shades "green 1", "green 2"...), else none."""
    if "colour_names" in doc:
        given, count = doc["colour_names"], sum(map(len, families))
        if len(given) != count:
            raise presets.PresetError(f"palette {name!r}: {len(given)} colour_names for "
                                      f"{count} colours")
        return tuple(map(str, given))
    given = doc.get("family_names", [])  # as the puzzle's colour key: unnamed families last
    return tuple(f"{given[f]} {k + 1}" if f < len(given) else ""
                 for f, family in enumerate(families) for k in range(len(family))) if given else ()


def crossing_pairs(weave: Weave) -> np.ndarray:
    """(K, 2) pairs of distinct strands that cross at some tile, each pair once."""
    over, under = weave.tile_over, weave.tile_under
    ok = (over >= 0) & (under >= 0) & (over != under)
    pairs = np.sort(np.column_stack([over[ok], under[ok]]), axis=1)
    return distinct(pairs, axis=0) if len(pairs) else pairs.reshape(0, 2)


def greedy_classes(n: int, pairs: np.ndarray, k: int) -> np.ndarray:
    """A class 0..k-1 per node; neighbours differ where k allows.

    Welsh-Powell order (most neighbours first), least-used free class first, so that the
    classes come out balanced and deterministic."""
    neighbours: list[list[int]] = [[] for _ in range(n)]
    for a, b in pairs.tolist():
        neighbours[a].append(b)
        neighbours[b].append(a)
    degree = np.array([len(x) for x in neighbours], dtype=np.int64)
    out = np.full(n, -1, dtype=np.int64)
    used = np.zeros(k, dtype=np.int64)
    for node in np.lexsort((np.arange(n), -degree)).tolist():  # strands, not mesh elements
        taken = {out[m] for m in neighbours[node] if out[m] >= 0}
        free = [c for c in range(k) if c not in taken] or list(range(k))
        choice = min(free, key=lambda c: (used[c], c))
        out[node] = choice
        used[choice] += 1
    return out


def sibling_rank(parent_strand: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """(S,) rank of every strand among the children of its parent, longest first (orphans: 0),
    so that the two long children of a strand get its family's first two shades."""
    n = len(parent_strand)
    key = np.where(parent_strand >= 0, parent_strand, -1 - np.arange(n))
    order = np.lexsort((np.arange(n), -np.asarray(lengths), key))
    k = key[order]
    first = np.r_[True, k[1:] != k[:-1]]
    start = np.maximum.accumulate(np.where(first, np.arange(n), 0))
    rank = np.empty(n, dtype=np.int64)
    rank[order] = np.arange(n) - start
    return rank


def shade(colour: str, rank: int) -> str:
    """The rank-th shade of a colour: darker, lighter, then further darker and lighter."""
    target = 0.0 if rank % 2 == 0 else 1.0
    amount = min(0.2 + 0.15 * (rank // 2), 0.85)
    r, g, b = (int(colour[i:i + 2], 16) for i in (1, 3, 5))
    return "#{:02x}{:02x}{:02x}".format(*(round(c + (255 * target - c) * amount)
                                          for c in (r, g, b)))


def strand_colours(weaves: list[Weave], pal: Palette) -> list[str]:
    """A colour for every strand of the last weave in ``weaves``.

    The first weave's strands get the palette's families (crossing strands different ones
    where the palette allows); every later level follows ``parent_strand``: a child takes a
    shade of its parent's colour (at the first split the family's own shades), so a strand's
    whole lineage stays in one hue. Levels above a weave without lineage are not used.
    """
    weaves = _lineage_chain(weaves)
    first = weaves[0]
    family = greedy_classes(first.n_strands, crossing_pairs(first), len(pal.families))
    colours = [pal.families[f][0] for f in family.tolist()]
    for depth, weave in enumerate(weaves[1:], start=1):
        ps = weave.parent_strand
        lengths = np.bincount(weave.visit_strand[weave.visit_over], minlength=weave.n_strands)
        rank = sibling_rank(ps, lengths).tolist()
        new_family, new_colours = [], []
        for s, p in enumerate(ps.tolist()):  # strands, not mesh elements
            f = int(family[p]) if p >= 0 else s % len(pal.families)
            shades = pal.families[f]
            if depth == 1 and len(shades) > 1:
                colour = shades[rank[s] % len(shades)]
            else:
                colour = shade(colours[p] if p >= 0 else shades[0], rank[s])
            new_family.append(f)
            new_colours.append(colour)
        family, colours = np.array(new_family, dtype=np.int64), new_colours
    return colours


def strand_families(weaves: list[Weave], pal: Palette) -> np.ndarray:
    """(S,) the palette family of every strand of the last weave (its level-one ancestor's)."""
    weaves = _lineage_chain(weaves)
    family = greedy_classes(weaves[0].n_strands, crossing_pairs(weaves[0]), len(pal.families))
    for weave in weaves[1:]:
        ps = weave.parent_strand
        family = np.where(ps >= 0, family[np.maximum(ps, 0)], np.arange(len(ps)) % len(
            pal.families))
    return family


def _lineage_chain(weaves: list[Weave]) -> list[Weave]:
    """The last weaves linked by ``parent_strand`` (at least the last one)."""
    start = len(weaves) - 1
    while start > 0 and weaves[start].parent_strand is not None:
        start -= 1
    return weaves[start:]
