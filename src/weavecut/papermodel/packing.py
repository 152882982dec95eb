"""Dense pages: a raster polygon packer (turns in 15 degree steps, never mirrored).

Every piece, turned by each allowed angle, becomes a mask on a grid of ``cell`` mm: the cells
whose centre lies within ``gap / 2 + cell / sqrt(2)`` of the piece. Two pieces whose masks share
no cell are at least ``gap`` apart (a point nearer than ``gap / 2`` to both would put its
cell in both masks), and a piece grown by ``gap / 2`` lies inside the union of its mask's cells,
so a mask may reach ``gap / 2`` beyond the packing area. Where a mask fits on a page is
narrowed by block tests that never refuse a place that fits (:mod:`.packing_grid`): one FFT
correlation of every turn's core on 8 x 8 blocks of cells gives each turn's least possible
edge along the filling axis, turns go least edge first and stop where none can beat the best
place found, and a turn's core on 4 x 4 blocks leaves the places tried cell by cell, in order,
the first that holds the mask being the turn's best (finer tests, down to an exact
correlation, take over where many places fail). A page with too few free cells is skipped.

Congruent pieces (the k copies of a module strip, the same ``kind``) are nested into a stack
first. Stacks go largest first (by their pieces' convex hulls: a curled strip takes up more
than its area), each on the first page with room (first fit), where its right edge is least,
then lowest (columns from the left); a stack that fits no open page is halved before a page
is opened. When the last page is nearly empty, the packing is redone with that
page's pieces first. All of it is done twice, filling columns from the left and rows from the
bottom (long strips lie across the page in one and along it in the other), and the packing with
the fewer pages (then the emptier last page) kept; a try is given up as soon as it needs as many
pages as the best so far. Then a last page whose pieces would fit by their area beside those
of an earlier page (no more room than the fullest page holds, and a little) is emptied where
those pieces, packed again in other orders and on a finer grid, go onto one page; and the
pieces of the stacks left on the last page go one by one to the first earlier page with room
for them alone (a stack went to the first page with room for all of it): pages are used
before new ones are started.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from numpy.typing import NDArray

from ..numeric import affine, snap, transform
from .packing_grid import BLOCKS, Options, Page, start_cells, turned_masks
from .stacks import nest_offset

ANGLE_STEP = 15.0  # degrees between the turns tried
TRIES = 256  # places tried one by one before the next finer block test


@dataclass(frozen=True)
class Place:
    """Where a piece went: ``page`` (0-based), turned by ``angle`` degrees about the origin of its
    own frame, then moved by ``shift`` (mm, in the packing area's frame)."""

    page: int
    angle: float
    shift: tuple[float, float]

    def matrix(self) -> NDArray[np.float64]:
        """(3, 3) the affine map from the piece's frame to the packing area."""
        return affine(self.angle, self.shift)


def pack(shapes, width: float, height: float, gap: float = 2.0, cell: float = 0.75,
         kinds=None, angle_step: float = ANGLE_STEP) -> list[Place]:
    """Pack ``shapes`` (shapely polygons, mm) onto as few ``width`` x ``height`` areas as it can.

    Congruent pieces (equal ``kinds``, the same polygon in their own frames) are first nested
    into a stack, each copy moved by :func:`nest_offset` from the one before, and the stack is
    packed as one piece; a stack that fits on no open page is halved before a page is opened.

    Parameters
    ----------
    shapes : (n,) polygons in their own frames, long axis along x
    width, height : the packing area (mm); the area's lower-left corner is the origin
    gap : least distance between two pieces (mm)
    cell : grid size (mm); smaller packs tighter and slower
    kinds : (n,) ints, equal for congruent pieces
    angle_step : turns tried are the multiples of this (degrees), never a mirror

    Returns
    -------
    one Place per shape, in input order

    Raises
    ------
    ValueError if a piece fits the area at no angle
    """
    shapes = np.asarray(shapes, dtype=object)
    n = len(shapes)
    kinds = np.arange(n) if kinds is None else np.asarray(kinds)
    angles = np.arange(0.0, 360.0, angle_step).tolist()
    # a mask reaches gap / 2 beyond its piece: it may reach as far beyond the area's edge
    width, height = width + gap, height + gap
    _, first, inverse = np.unique(kinds, return_index=True, return_inverse=True)
    units = []  # (members, move between members)
    for g in np.argsort(first, kind="stable").tolist():  # kinds of piece
        members = np.flatnonzero(inverse == g).tolist()
        x0, _, x1, _ = shapes[members[0]].bounds
        move = nest_offset(shapes[members[0]], gap, longest=max(width, height) - gap - (x1 - x0)) \
            if len(members) > 1 else np.zeros(2)
        units.append((members, move))
    grids: dict[float, Grid] = {}

    def grid(size: float) -> Grid:
        """The raster of ``size`` mm cells: its masks and transforms are made once."""
        if size not in grids:
            masks: dict[tuple, Options] = {}

            def options(members, move):
                key = (int(kinds[members[0]]), len(members))
                if key not in masks:
                    stack = shapely.union_all([shapely.transform(
                        shapes[members[0]], lambda xy, j=j: xy + j * move)
                        for j in range(len(members))])
                    masks[key] = Options(turned_masks(stack, angles, gap, size, width, height))
                return masks[key]

            grids[size] = Grid(options, int(width // size), int(height // size), size, {}, {})
        return grids[size]

    hulls = shapely.area(shapely.convex_hull(shapes))

    def area(unit):  # what a piece takes up: its convex hull (a curled strip holds little)
        return -int(snap(hulls[unit[0]].sum()))

    def rank(r):
        return (_pages(r[0]), int(snap(_last_fill(r[0], shapes))))

    best = None  # (places, what was laid where, axis)
    for axis in (1, 0):  # columns from the left, then rows from the bottom
        if best is not None and _pages(best[0]) == 1:
            break  # nothing to save
        run = _fill(units, shapes, kinds, grid(cell), area, set(), axis,
                    None if best is None else _pages(best[0]) - 1)
        first: set = set()
        for _ in range(REPAIRS):  # the last page's pieces go first next time
            if run is None or _pages(run[0]) == 1 or \
                    _last_fill(run[0], shapes) > REPAIR_BELOW * width * height:
                break
            first |= {i for i, p in enumerate(run[0]) if p.page == _pages(run[0]) - 1}
            again = _fill(units, shapes, kinds, grid(cell), area, first, axis, _pages(run[0]))
            if again is not None and rank(again) < rank(run):
                run = again
        best = best if run is None else (*run, axis)
    places, laid, axis = best
    if _pages(places) > 1:  # each piece's share of a page, grown by half the gap
        room = shapely.area(shapely.buffer(shapes, gap / 2, quad_segs=4)) / (width * height)
        places, laid = _merge_last(places, laid, room, lambda here, size, first, axis: _fill(
            [(m, move) for members, move in units if (m := [i for i in members if i in here])],
            shapes, kinds, grid(size), area, first, axis, 1), cell)
        places = _settle(places, laid, grid(cell), kinds, axis)
    return [Place(p.page, p.angle, (p.shift[0] - gap / 2, p.shift[1] - gap / 2))
            for p in places]


@dataclass(frozen=True)
class Grid:
    """A raster to pack on: ``options(members, move)`` the turns of a stack, the page's
    ``nx`` x ``ny`` cells of ``cell`` mm, the masks' transforms shared by its pages, and the
    best spots found (:func:`_spot`)."""

    options: object
    nx: int
    ny: int
    cell: float
    spectra: dict
    spots: dict


MERGE_SLACK = 50_000  # millionths of the area: a last page is emptied into an earlier one where
# the two pages' pieces take up at most this much more than the fullest page holds ...
MERGE_PAGES = 3  # ... tried with the pieces of each of the this many emptiest pages
FINE = 2.0 / 3.0  # ... then on cells this much smaller (masks less grown)
MERGES = ((1.0, 1, True), (1.0, 0, True), (1.0, 0, False),  # (cell, axis, last page first)
          (FINE, 1, False), (FINE, 1, True), (FINE, 0, False), (FINE, 0, True))


def _merge_last(run, laid, room, one_page, cell: float):
    """(places, laid): ``run`` (places) with its last page emptied into an earlier page, again
    and again while one can be: the pieces of the last page and of one of the ``MERGE_PAGES``
    emptiest pages before it whose pieces take up together (``room``: each piece's share of
    the area, grown by half the gap) no more than the fullest page holds and ``MERGE_SLACK``,
    packed as in ``MERGES`` onto one page (``one_page(pieces, cell, pieces first, axis)``:
    their places and what was laid where, or None where they need a second page)."""
    while _pages(run) > 1:
        last = _pages(run) - 1
        on = [[i for i, p in enumerate(run) if p.page == n] for n in range(last + 1)]
        need = [int(snap(room[o].sum())) for o in on]  # in millionths of the area
        most = max(need[:last]) + MERGE_SLACK  # what the fullest page holds, and a little
        tries = [n for n in sorted(range(last), key=lambda n: (need[n], n))
                 if need[n] + need[last] <= most][:MERGE_PAGES]
        for n, (size, axis, lead) in ((n, m) for m in MERGES for n in tries):
            here = set(on[n] + on[last])
            got = one_page(here, size * cell, set(on[last]) if lead else set(), axis)
            if got is not None:
                run = [Place(n, q.angle, q.shift) if i in here else p
                       for i, (p, q) in enumerate(zip(run, got[0]))]
                fine = size != 1.0  # a page laid on a finer grid takes no more pieces
                laid = [e for e in laid if e[0] not in (n, last)] + \
                    [(n, members, None if fine else mask, at) for _, members, mask, at in got[1]]
                break
        else:
            return run, laid
    return run, laid


SETTLE_MOST = 24  # pieces of stacks on the last page tried one by one, at most


def _settle(run, laid, grid: Grid, kinds, axis: int):
    """``run`` (places) with the pieces of the stacks on its last page moved, one by one, to
    the first earlier page with room for them alone (a stack went to the first page with room
    for all of it), its pages rebuilt from what was ``laid`` where (a page laid on a finer
    grid, a mask of None, is left as it is); left as it is where the last page's stacks hold
    more than ``SETTLE_MOST`` pieces (a full last page: the time is not worth it)."""
    last = _pages(run) - 1
    if sum(len(m) for n, m, _, _ in laid if n == last and len(m) > 1) > SETTLE_MOST:
        return run
    pages = [Page(grid.ny, grid.nx, grid.spectra) for _ in range(last)]
    for number, _, mask, (iy, ix) in laid:
        if number < last:
            if mask is None:
                pages[number].taken[:] = True
            else:
                pages[number].add(mask, iy, ix)
    out, full = list(run), set()
    for number, members, _, _ in laid:
        for i in (members if number == last and len(members) > 1 else []):
            opts = grid.options([i], np.zeros(2))
            if (spot := _first_fit(pages, opts, (int(kinds[i]), 1), full, axis,
                                   grid.spots)) is not None:
                _place(out, [], pages, [i], np.zeros(2), *spot, grid.cell)
    return out


REPAIRS = 2  # re-packings with the last page's pieces first ...
REPAIR_BELOW = 0.15  # ... when the last page is this empty (a page may be saved)


def _pages(places) -> int:
    return max(p.page for p in places) + 1


def _last_fill(places, shapes) -> float:
    last = max(p.page for p in places)
    return sum(s.area for p, s in zip(places, shapes) if p.page == last)


def _fill(units, shapes, kinds, grid: Grid, area, first, axis: int, most: int | None = None):
    """Places for every piece: the units (stacks) largest first (those holding a piece in
    ``first`` before all others), first fit, each where its far edge along ``axis`` is least
    (:func:`_best_spot`); None as soon as it needs more than ``most`` pages. Returns the places
    and what was laid where: (page, members, mask, (iy, ix)) per stack."""
    keys: dict = {}

    def order(u):  # worked out once per stack: the queue is sorted again at every halving
        if (at := tuple(u[0])) not in keys:
            keys[at] = (not first.intersection(at), area(u), at[0])
        return keys[at]

    queue = sorted(units, key=order)
    options, nx, ny, cell = grid.options, grid.nx, grid.ny, grid.cell
    pages: list[Page] = []
    full: set = set()
    out: list[Place | None] = [None] * len(shapes)
    laid: list = []
    while queue:  # stacks of pieces
        members, move = queue.pop(0)
        key = (int(kinds[members[0]]), len(members))
        spot = _first_fit(pages, options(members, move), key, full, axis, grid.spots)
        if spot is None and (len(members) > 1 and (pages or not options(members, move))):
            half = (len(members) + 1) // 2
            queue = sorted(queue + [(members[:half], move), (members[half:], move)], key=order)
            continue
        if spot is None:
            if not options(members, move):
                x0, y0, x1, y1 = shapes[members[0]].bounds
                raise ValueError(f"a strip of {x1 - x0:.0f} x {y1 - y0:.0f} mm fits the printable "
                                 f"area at no angle")
            if most is not None and len(pages) == most:
                return None  # no better than a packing found before
            pages.append(Page(ny, nx, grid.spectra))
            spot = len(pages) - 1, _spot(pages[-1], options(members, move), key, axis, grid.spots)
        _place(out, laid, pages, members, move, *spot, cell)
    return out, laid


def _first_fit(pages, opts, key, full: set, axis: int, spots: dict):
    """(page, spot) of the first of ``pages`` with room for the stack of ``opts`` (see
    :func:`_best_spot`), or None; ``full`` holds the (key, page) already found without."""
    for number, page in enumerate(pages):
        if opts and (key, number) not in full and page.may_hold(opts):
            if (best := _spot(page, opts, key, axis, spots)) is not None:
                return number, best
            full.add((key, number))  # pages only fill up: no need to try again
    return None


def _place(out, laid, pages, members, move, number: int, spot, cell: float) -> None:
    """Lay the stack of ``members`` (each ``move`` from the one before) at ``spot`` on page
    ``number``: its mask onto the page, its pieces' places into ``out``, the stack into
    ``laid``."""
    (iy, ix), angle, mask, origin = spot
    pages[number].add(mask, iy, ix)
    shift = np.array([ix * cell - origin[0], iy * cell - origin[1]])
    turn = transform(Place(number, float(angle), (0.0, 0.0)).matrix())
    for j, i in enumerate(members):
        at = shift + turn(j * move)
        out[i] = Place(number, float(angle), (float(at[0]), float(at[1])))
    laid.append((number, members, mask, (iy, ix)))


def _spot(page: Page, opts, key, axis: int, spots: dict):
    """:func:`_best_spot` of the stack of ``opts`` (``key``: its kind and size) on ``page``,
    looked up in ``spots`` by the page's cells where a run before asked the same (a packing
    redone, or its other stacks' pieces settled, meets the same pages now and then)."""
    at = (np.packbits(page.taken).tobytes(), key, axis)
    if at not in spots:
        spots[at] = _best_spot(page, opts, axis)
    return spots[at]


def _best_spot(grid: Page, options, axis: int = 1):
    """((iy, ix), angle, mask, origin) of the place on ``grid``, among the turns in ``options``,
    whose far edge along ``axis`` (1: the right edge, filling columns from the left; 0: the top
    edge, filling rows from the bottom) is least, then the one nearest the origin across it,
    then the turn shortest along ``axis``; None if the piece fits nowhere.

    The coarsest block test of every turn at once gives each turn's least possible edge; the
    turns go least edge first and stop where none can beat the best place found. A turn's
    places are those its next block test leaves, tried cell by cell in order; after ``TRIES``
    that fail, the next finer test cuts down the rest, the last (on single cells) exact."""
    best, best_key = None, None
    free = grid.places(BLOCKS[0], options.cores)  # every turn's coarse places at once
    lines = free.any(axis=2 - axis)  # block rows (axis 0) or columns any place is on
    first = np.where(lines.any(axis=1), lines.argmax(axis=1), -1).tolist()
    bounds = []
    for t, (line, core, offset) in enumerate(zip(first, options.cores, options.offsets)):
        if core is not None and line < 0:
            continue  # no place
        edge = 0 if core is None else max(BLOCKS[0] * (line - offset[axis]), 0)
        bounds.append((edge + int(options.sizes[t, axis]), options.rank[axis][t], t))
    ny, nx = free.shape[1:]
    for edge, r, t in sorted(bounds):
        if best_key is not None and edge > best_key[0]:
            break
        last = None  # the key of the last place tried
        core = options.cores[t]  # the finest test with a core
        test = (1, None, (0, 0)) if core is None else (BLOCKS[0], free[
            t, :ny - core.shape[0] + 1, :nx - core.shape[1] + 1], options.offsets[t])
        for k in BLOCKS[1:]:
            core, offset = options.core(k, t)
            if core is not None:
                test = (k, _finer(grid, k, core, offset, test), offset)
            tries = TRIES if k > 1 else -1
            last, at, more = _try(grid, options[t][1], test, axis, (r, best_key, last), tries)
            if not more:
                break
        if at is not None:
            best, best_key = (at, *options[t]), last
    return best


def _finer(grid: Page, k: int, core, offset, coarser):
    """The block places where ``core`` (at ``offset``) lies on free k x k blocks among those
    the ``coarser`` test (k, fits, offset) leaves: read directly at those places when they are
    few, else everywhere by FFT (both leave every place that fits)."""
    step, fits, at = coarser
    if fits is not None:
        r, c = np.nonzero(fits)
        m = step // k
        if len(r) * m * m * np.count_nonzero(core) <= DIRECT:
            dy, dx = np.divmod(np.arange(m * m), m)  # the finer blocks of each coarse one
            return grid.fits_at(k, core, (((r - at[0]) * m + offset[0])[:, None] + dy).ravel(),
                                (((c - at[1]) * m + offset[1])[:, None] + dx).ravel())
    return grid.fits(k, [core])[0]


DIRECT = 8192  # a finer test reads the blocks under a core at a few places up to this often


def _try(grid, mask, test, axis: int, keys, tries: int):
    """(last, at, more): the first place ``at`` (iy, ix) that holds ``mask`` among those
    ``test`` leaves (see :func:`start_cells`), trying at most ``tries`` (-1: all) of those whose
    key comes after ``last`` (None: from the first) and before ``bound``, ``keys`` being (rank,
    bound, last) and a place's key (its edge along ``axis``, its place across, rank); None if
    none holds it. ``last`` is the key last tried, ``more`` whether untried places remain."""
    rank, bound, last = keys
    for iy, ix in start_cells(*test, mask.shape, grid.taken.shape, axis):
        key = ((iy, ix)[axis] + mask.shape[axis], (iy, ix)[1 - axis], rank)
        if bound is not None and key >= bound:
            break
        if last is not None and key <= last:
            continue  # tried before
        if tries == 0:
            return last, None, True
        tries, last = tries - 1, key
        if not (grid.taken[iy:iy + mask.shape[0], ix:ix + mask.shape[1]] & mask).any():
            return key, (iy, ix), False
    return last, None, False
