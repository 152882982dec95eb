"""Symmetry modules (paper section 5.2): which strand is printed where, and in which colour.

The weave's rotation group C_k splits the strands into orbits. A *module* is one strand per
full orbit, chosen so that all of them head the same way (for the square grid turned by
pi / 4: north to south); the turn by j * 2 pi / k makes copy j of the module, and the k copies
hold every strand exactly once. Strands that some rotation fixes are printed once, as extras.

A strand's colour is the same for every copy of its module strand (``orbit_colours``), or one
per copy (``copy_colours``, ``copy_family_colours``). ``strips`` cuts the strands from paper.
"""

from __future__ import annotations

import string
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..weave.colour import Palette, crossing_pairs, greedy_classes
from ..weave.model import Weave
from .symmetry import Symmetry, rotate, rotation_group, strand_orbits, tile_centres


@dataclass(frozen=True, eq=False)
class ModulePlan:
    """Which strand is printed where.

    Parameters
    ----------
    symmetry : the weave's rotation group C_k
    copies : (k, M) strands; row j is copy j of the module (the module turned by j * 2 pi / k),
        column i is module strand i + 1
    extras : (X,) strands fixed by some rotation, printed once
    reversed : (S,) True where the printed direction runs against the weave's walking order
    labels : (S,) strand IDs: copy letter and module number ("B7"), extras "X1", "X2", ...
    """

    symmetry: Symmetry
    copies: NDArray[np.int64]
    extras: NDArray[np.int64]
    reversed: NDArray[np.bool_]
    labels: tuple[str, ...]

    @property
    def k(self) -> int:
        return self.copies.shape[0]


def copy_letter(j: int) -> str:
    letters = string.ascii_uppercase
    return letters[j] if j < 26 else letters[j // 26 - 1] + letters[j % 26]


def _angle_gap(a: NDArray, b: float) -> NDArray:
    return np.abs(np.angle(np.exp(1j * (a - b))))


def plan_modules(weave: Weave, heading: float = -np.pi / 2,
                 symmetry: Symmetry | None = None) -> ModulePlan:
    """Modules of ``weave``: one strand per full orbit, each printed heading near ``heading``.

    ``heading`` is an angle in the weave's frame; of the k turned copies of an orbit's strand
    (and, for odd k, their reverses) the one whose start-to-end direction is nearest to it
    joins the module. Module strands are numbered across that direction, left to right.
    """
    sym = rotation_group(weave) if symmetry is None else symmetry
    k = sym.order
    orbit, size = strand_orbits(sym)
    powers = sym.strand_powers()  # (k, S)
    tpowers = sym.tile_powers()  # (k, T)
    centres = tile_centres(weave)
    first = weave.strand_visits[weave.strand_offsets[:-1]]
    last = weave.strand_visits[weave.strand_offsets[1:] - 1]
    direction = centres[last] - centres[first]
    base = np.arctan2(direction[:, 1], direction[:, 0])

    seeds = np.flatnonzero((orbit == np.arange(weave.n_strands)) & (size == k))
    # candidate (copy j, flip) per orbit seed: direction base + j * angle (+ pi if flipped)
    j = np.arange(k)
    cand = base[seeds, None, None] + j[None, :, None] * sym.angle + np.array([0, np.pi])
    gap = _angle_gap(cand, heading) + 1e-9 * (j[None, :, None] + k * np.array([0, 1]))
    best = gap.reshape(len(seeds), -1).argmin(axis=1)
    jbest, flip = np.divmod(best, 2)
    reps = powers[jbest, seeds]
    # the turn may carry a strand onto its image walking the other way: flip the image so that
    # it heads where the chosen candidate does
    want = base[seeds] + jbest * sym.angle + np.pi * flip
    flip = _angle_gap(base[reps], want) > np.pi / 2
    # order across the heading: x in a frame where the heading points down
    mid = np.array([centres[weave.strand_visits[a:b]].mean(axis=0) for a, b in
                    zip(weave.strand_offsets[reps].tolist(), weave.strand_offsets[reps + 1].tolist())]
                   ).reshape(-1, 2)
    across = rotate(mid, -np.pi / 2 - heading, (0.0, 0.0))[:, 0] if len(reps) else np.zeros(0)
    order = np.lexsort((reps, np.round(across, 6)))
    reps, flip = reps[order], flip[order].astype(bool)
    copies = powers[:, reps] if len(reps) else np.zeros((k, 0), dtype=np.int64)

    # printed direction: the module strand's (possibly flipped) walk, turned along its orbit
    rev = np.zeros(weave.n_strands, dtype=bool)
    rep_first = first[reps]
    rep_first = np.where(flip, last[reps], rep_first)
    for jj in range(k):  # k copies, not mesh elements
        members = copies[jj]
        rev[members] = tpowers[jj, rep_first] != first[members]
    extras = np.flatnonzero(size < k)
    labels = np.empty(weave.n_strands, dtype=object)
    for jj in range(k):
        labels[copies[jj]] = [f"{copy_letter(jj)}{i + 1}" for i in range(copies.shape[1])]
    labels[extras] = [f"X{i + 1}" for i in range(len(extras))]
    return ModulePlan(sym, copies, extras, rev, tuple(labels.tolist()))


def orbit_colours(weaves: list[Weave], plan: ModulePlan, pal: Palette) -> list[str]:
    """A colour per strand, the same for every copy of a module strand (print k identical
    copies). With a palette of shade families and a coarser level, module strands that
    follow the same parent orbit share a hue and take its shades (the braided pairs)."""
    weave = weaves[-1]
    n = weave.n_strands
    # nodes: module columns, then extras
    node = np.full(n, -1, dtype=np.int64)
    m = plan.copies.shape[1]
    node[plan.copies.ravel()] = np.tile(np.arange(m), plan.k)
    node[plan.extras] = m + np.arange(len(plan.extras))
    n_nodes = m + len(plan.extras)
    pairs = node[crossing_pairs(weave)]
    pairs = np.unique(np.sort(pairs[pairs[:, 0] != pairs[:, 1]], axis=1), axis=0) \
        if len(pairs) else pairs
    if pal.shaded and len(weaves) >= 2 and weave.parent_strand is not None:
        # family: the parent strand of the node's copy-A strand (rotating a copy rotates
        # its parent too, so the choice is the same for every copy)
        rep = np.zeros(n_nodes, dtype=np.int64)
        rep[:m] = plan.copies[0]
        rep[m:] = plan.extras
        ps = weave.parent_strand[rep]
        fam_key = np.where(ps >= 0, ps, weaves[-2].n_strands + np.arange(n_nodes))
        keys, fam_node = np.unique(fam_key, return_inverse=True)
        fpairs = fam_node[pairs] if len(pairs) else pairs
        fpairs = fpairs[fpairs[:, 0] != fpairs[:, 1]] if len(fpairs) else fpairs
        fpairs = np.unique(np.sort(fpairs, axis=1), axis=0) if len(fpairs) else fpairs
        family = greedy_classes(len(keys), fpairs.reshape(-1, 2), len(pal.families))
        order = np.lexsort((np.arange(n_nodes), fam_node))
        starts = np.r_[True, fam_node[order][1:] != fam_node[order][:-1]]
        group_start = np.maximum.accumulate(np.where(starts, np.arange(n_nodes), 0))
        shade = np.empty(n_nodes, dtype=np.int64)
        shade[order] = np.arange(n_nodes) - group_start
        fams = [pal.families[f % len(pal.families)] for f in family[fam_node].tolist()]
        node_colour = [f[s % len(f)] for f, s in zip(fams, shade.tolist())]
    else:
        flat = pal.flat
        cls = greedy_classes(n_nodes, pairs.reshape(-1, 2), len(flat))
        node_colour = [flat[c] for c in cls.tolist()]
    return [node_colour[i] for i in node.tolist()]


def copy_colours(plan: ModulePlan, pal: Palette) -> list[str]:
    """A colour per strand: one colour per module copy (the paper's 4-colour scheme)."""
    flat = pal.flat
    out = [flat[-1]] * len(plan.labels)
    for j in range(plan.k):
        for s in plan.copies[j].tolist():
            out[s] = flat[j % len(flat)]
    return out


def copy_family_colours(weave: Weave, plan: ModulePlan, pal: Palette) -> list[str]:
    """A colour per strand that tells the copies apart: with three or more copies, copy j takes
    shade family j and its module strands the family's shades in turn (neighbours differ);
    extras the next family. With fewer copies the copies are not what the eye must separate,
    so crossing strands simply differ (greedy colouring over the flat palette)."""
    fams = pal.families
    if plan.k < 3:
        cls = greedy_classes(weave.n_strands, crossing_pairs(weave), len(pal.flat))
        return [pal.flat[c] for c in cls.tolist()]
    out = [""] * len(plan.labels)
    for j, row in enumerate(plan.copies.tolist()):  # copies
        fam = fams[j % len(fams)]
        for i, s in enumerate(row):
            out[s] = fam[i % len(fam)]
    fam = fams[plan.k % len(fams)]
    for i, s in enumerate(plan.extras.tolist()):
        out[s] = fam[i % len(fam)]
    return out


def book_colours(weaves: list[Weave], plan: ModulePlan, pal: Palette, layout: str) -> list[str]:
    """A colour per strand of ``weaves[-1]`` as the strand book prints it: a flat palette gives
    one colour per copy; shade families tell the copies apart (``mixed``) or give a module
    strand its braided-pair shade (``module``)."""
    if not pal.shaded:
        return copy_colours(plan, pal)
    if layout == "module":
        return orbit_colours(weaves, plan, pal)
    return copy_family_colours(weaves[-1], plan, pal)
