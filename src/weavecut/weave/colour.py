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
from .model import Weave


@dataclass(frozen=True)
class Palette:
    name: str
    families: tuple[tuple[str, ...], ...]

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
    return Palette(str(doc.get("name", name)), families)


def crossing_pairs(weave: Weave) -> np.ndarray:
    """(K, 2) pairs of distinct strands that cross at some tile, each pair once."""
    over, under = weave.tile_over, weave.tile_under
    ok = (over >= 0) & (under >= 0) & (over != under)
    pairs = np.sort(np.column_stack([over[ok], under[ok]]), axis=1)
    return np.unique(pairs, axis=0) if len(pairs) else pairs.reshape(0, 2)


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


def strand_colours(weaves: list[Weave], pal: Palette) -> list[str]:
    """A colour for every strand of the last weave in ``weaves``."""
    last = weaves[-1]
    if pal.shaded and len(weaves) >= 2 and last.parent_strand is not None:
        parent = weaves[-2]
        family = greedy_classes(parent.n_strands, crossing_pairs(parent), len(pal.families))
        ps = last.parent_strand
        # shade index: rank among the siblings of one parent (orphans use their own id)
        key = np.where(ps >= 0, ps, parent.n_strands + np.arange(last.n_strands))
        order = np.lexsort((np.arange(last.n_strands), key))
        sorted_key = key[order]
        first = np.r_[True, sorted_key[1:] != sorted_key[:-1]]
        group_start = np.maximum.accumulate(np.where(first, np.arange(len(order)), 0))
        rank = np.empty(last.n_strands, dtype=np.int64)
        rank[order] = np.arange(len(order)) - group_start
        fam = np.where(ps >= 0, family[np.maximum(ps, 0)], np.arange(last.n_strands))
        return [pal.families[f % len(pal.families)][r % len(pal.families[f % len(pal.families)])]
                for f, r in zip(fam.tolist(), rank.tolist())]
    flat = pal.flat
    classes = greedy_classes(last.n_strands, crossing_pairs(last), len(flat))
    return [flat[c] for c in classes.tolist()]
