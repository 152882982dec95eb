"""Dense pages: a raster polygon packer (turns in 15 degree steps, never mirrored).

Every piece, turned by each allowed angle, becomes a mask on a grid of ``cell`` mm: the cells
whose centre lies within ``gap / 2 + cell / sqrt(2)`` of the piece. Two pieces whose masks share
no cell are at least ``gap`` apart (a point nearer than ``gap / 2`` to both would put its
cell in both masks), and a piece grown by ``gap / 2`` lies inside the union of its mask's cells,
so a mask may reach ``gap / 2`` beyond the packing area. Where a mask fits on a page's occupancy
grid is one FFT correlation per angle (the page's transform is kept and the masks' are cached,
so each try is one inverse FFT). Cheaper tests that never refuse a place that fits come first:
a page with too few free cells or no free disc as large as the piece's is skipped, a turn that
fits nowhere on the page's 2 x 2 blocks is skipped, and turns go shortest along the filling
axis first, so those longer than the best edge found are not tried.

Congruent pieces (the k copies of a module strip, the same ``kind``) are nested into a stack
first. Stacks go largest first (by their pieces' convex hulls: a curled strip takes up more
than its area), each on the first page with room (first fit), where its right edge is least,
then lowest (columns from the left); a stack that fits no open page is halved before a page
is opened. When the last page is nearly empty, the packing is redone with that
page's pieces first. All of it is done twice, filling columns from the left and rows from the
bottom (long strips lie across the page in one and along it in the other), and the packing with
the fewer pages (then the emptier last page) kept; a try is given up as soon as it needs as many
pages as the best so far.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from numpy.typing import NDArray
from scipy.fft import irfft2, next_fast_len, rfft2
from scipy.ndimage import distance_transform_edt

from ..numeric import affine, snap, transform

ANGLE_STEP = 15.0  # degrees between the turns tried


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


def _turned(shape, angle: float):
    return shapely.transform(shape, transform(affine(angle)))


def _mask(shape, angle: float, gap: float, cell: float, width: float, height: float):
    """(mask, origin) of ``shape`` turned by ``angle``: origin is where cell (0, 0) of the mask
    starts in the turned frame; None when the turned piece cannot fit the area at all."""
    turned = _turned(shape, angle)
    reach = gap / 2 + cell * np.sqrt(0.5)
    x0, y0, x1, y1 = turned.bounds
    nx = int(np.ceil((x1 - x0 + 2 * reach) / cell))
    ny = int(np.ceil((y1 - y0 + 2 * reach) / cell))
    if nx > width // cell or ny > height // cell:
        return None
    origin = np.array([x0 - reach, y0 - reach])
    xs = origin[0] + (np.arange(nx) + 0.5) * cell
    ys = origin[1] + (np.arange(ny) + 0.5) * cell
    gx, gy = np.meshgrid(xs, ys)
    grown = shapely.buffer(turned, reach / np.cos(np.pi / 16), quad_segs=4)  # holds the disc
    shapely.prepare(grown)
    mask = shapely.contains_xy(grown, gx, gy)
    return mask.astype(np.float64), origin


def nest_offset(shape, gap: float, step: float = 0.25) -> NDArray[np.float64]:
    """(dx, dy): the move that nests a copy of ``shape`` (long axis along x) ``gap`` mm clear of
    it most tightly: for every slide dx along the axis a clear dy across it, bisected to within
    ``step`` of one that is not, and of those the one whose pair has the smallest convex hull
    (congruent wavy strips nest)."""
    x0, y0, x1, y1 = shape.bounds
    slide = min(x1 - x0, 30.0)
    dxs = np.arange(-slide, slide + 1e-9, 1.0)
    low, high = np.zeros_like(dxs), np.full_like(dxs, y1 - y0 + gap)  # overlapping, clear

    def copies(dys):
        moves = np.column_stack([dxs, dys])
        return shapely.transform(np.full(len(dxs), shape, dtype=object),
                                 lambda xy: xy + np.repeat(moves, len(xy) // len(moves), axis=0))

    while (high - low > step).any():  # a few halvings, every slide at once
        mid = (low + high) / 2
        clear = shapely.distance(shape, copies(mid)) >= gap
        low, high = np.where(clear, low, mid), np.where(clear, mid, high)
    box = shapely.area(shapely.convex_hull(shapely.union(shape, copies(high))))
    best = np.lexsort((np.abs(dxs), np.round(box, 3)))[0]
    return np.array([dxs[best], high[best]])


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
    nx, ny = int(width // cell), int(height // cell)
    _, first, inverse = np.unique(kinds, return_index=True, return_inverse=True)
    units = []  # (members, move between members)
    for g in np.argsort(first, kind="stable").tolist():  # kinds of piece
        members = np.flatnonzero(inverse == g).tolist()
        move = nest_offset(shapes[members[0]], gap) if len(members) > 1 else np.zeros(2)
        units.append((members, move))
    masks: dict[tuple, list] = {}

    def options(members, move):
        key = (int(kinds[members[0]]), len(members))
        if key not in masks:
            stack = shapely.union_all([shapely.transform(shapes[members[0]],
                                                         lambda xy, j=j: xy + j * move)
                                       for j in range(len(members))])
            half = [(a, _mask(stack, a, gap, cell, width, height)) for a in angles if a < 180]
            # the turn by a + 180 is the turn by a read backwards (the grid is symmetric)
            turns = [(a, *m) for a, m in half if m is not None] + [
                (a + 180.0, m[0][::-1, ::-1], -m[1] - np.array(m[0].shape[::-1]) * cell)
                for a, m in half if m is not None]
            masks[key] = _Options(turns, stack, gap / 2 + cell * np.sqrt(0.5), cell)
        return masks[key]

    hulls = shapely.area(shapely.convex_hull(shapes))

    def area(unit):  # what a piece takes up: its convex hull (a curled strip holds little)
        return -int(snap(hulls[unit[0]].sum()))

    def rank(r):
        return (_pages(r), int(snap(_last_fill(r, shapes))))

    spectra: dict = {}  # the masks' Fourier transforms, shared by every packing tried
    best = None
    for axis in (1, 0):  # columns from the left, then rows from the bottom
        if best is not None and _pages(best) == 1:
            break  # nothing to save
        run = _fill(units, shapes, kinds, options, area, nx, ny, cell, set(), axis, spectra,
                    None if best is None else _pages(best) - 1)
        first: set = set()
        for _ in range(REPAIRS):  # the last page's pieces go first next time
            if run is None or _pages(run) == 1 or \
                    _last_fill(run, shapes) > REPAIR_BELOW * width * height:
                break
            first |= {i for i, p in enumerate(run) if p.page == _pages(run) - 1}
            again = _fill(units, shapes, kinds, options, area, nx, ny, cell, first, axis,
                          spectra, _pages(run))
            if again is not None and rank(again) < rank(run):
                run = again
        best = best if run is None else run
    return [Place(p.page, p.angle, (p.shift[0] - gap / 2, p.shift[1] - gap / 2)) for p in best]


REPAIRS = 2  # re-packings with the last page's pieces first ...
REPAIR_BELOW = 0.15  # ... when the last page is this empty (a page may be saved)


def _pages(places) -> int:
    return max(p.page for p in places) + 1


def _last_fill(places, shapes) -> float:
    last = max(p.page for p in places)
    return sum(s.area for p, s in zip(places, shapes) if p.page == last)


def _fill(units, shapes, kinds, options, area, nx: int, ny: int, cell: float, first, axis: int,
          spectra: dict, most: int | None = None):
    """Places for every piece: the units (stacks) largest first (those holding a piece in
    ``first`` before all others), first fit, each where its far edge along ``axis`` is least
    (:func:`_best_spot`); None as soon as it needs more than ``most`` pages."""
    def order(u):
        return (not first.intersection(u[0]), area(u), u[0][0])

    queue = sorted(units, key=order)
    pages: list[_Page] = []
    full: set = set()
    out: list[Place | None] = [None] * len(shapes)
    while queue:  # stacks of pieces
        members, move = queue.pop(0)
        opts = options(members, move)
        spot = None
        key = (int(kinds[members[0]]), len(members))
        for number, page in enumerate(pages):
            if opts and (key, number) not in full and page.may_hold(opts):
                if (best := _best_spot(page, opts, axis)) is not None:
                    spot = number, best
                    break
                full.add((key, number))  # pages only fill up: no need to try again
        if spot is None and (len(members) > 1 and (pages or not opts)):
            half = (len(members) + 1) // 2
            queue = sorted(queue + [(members[:half], move), (members[half:], move)], key=order)
            continue
        if spot is None:
            if not opts:
                x0, y0, x1, y1 = shapes[members[0]].bounds
                raise ValueError(f"a strip of {x1 - x0:.0f} x {y1 - y0:.0f} mm fits the printable "
                                 f"area at no angle")
            if most is not None and len(pages) == most:
                return None  # no better than a packing found before
            pages.append(_Page(ny, nx, spectra))
            spot = len(pages) - 1, _best_spot(pages[-1], opts, axis)
        number, ((iy, ix), angle, mask, origin) = spot
        pages[number].add(mask, iy, ix)
        shift = np.array([ix * cell - origin[0], iy * cell - origin[1]])
        turn = transform(Place(number, float(angle), (0.0, 0.0)).matrix())
        for j, i in enumerate(members):
            at = shift + turn(j * move)
            out[i] = Place(number, float(angle), (float(at[0]), float(at[1])))
    return out


def _best_spot(grid: "_Page", options, axis: int = 1):
    """((iy, ix), angle, mask, origin) of the place on ``grid``, among the turns in ``options``,
    whose far edge along ``axis`` (1: the right edge, filling columns from the left; 0: the top
    edge, filling rows from the bottom) is least, then the one nearest the origin across it;
    None if the piece fits nowhere. The turns go shortest along ``axis`` first, so the turns
    that cannot beat the best edge found (they are longer than it) are left untried."""
    best, best_key = None, None
    for t in options.along[axis]:  # the allowed turns
        (angle, mask, origin), core = options[t], options.cores[t]
        if best_key is not None and best_key < (mask.shape[axis], 0):
            break
        if not grid.could_fit(core):
            continue
        free = grid.correlate(mask) < 0.5
        if not free.any():
            continue
        at = np.nonzero(free)  # (iy, ix) of the free places
        j = np.lexsort((at[1 - axis], at[axis]))[0]
        key = (int(at[axis][j] + mask.shape[axis]), int(at[1 - axis][j]))
        if best_key is None or key < best_key:
            best, best_key = ((int(at[0][j]), int(at[1][j])), angle, mask, origin), key
    return best


class _Options(list):
    """The turns (angle, mask, origin) of ``shape`` (a piece or stack), with ``along[axis]`` their
    indices shortest along that axis first (0: y, 1: x), and what every turn needs of a page:
    ``cells`` free cells (as many as its mask holds, at least the fewest of any turn), and a
    free disc of ``radius`` cells.
    The cells within
    ``reach`` of the piece are in its mask, so the centres within ``r + reach`` of the centre of
    its largest inscribed circle (radius ``r``) are, and the mask's cell nearest that centre is at
    least ``(r + reach) / cell - sqrt(1 / 2)`` cells from any cell outside the mask, at any
    turn."""

    def __init__(self, turns, shape, reach: float, cell: float):
        super().__init__(turns)
        self.along = [sorted(range(len(turns)), key=lambda t: (turns[t][1].shape[axis],
                                                               turns[t][0])) for axis in (0, 1)]
        self.cores = [_core(m) for _, m, _ in self]
        self.cells = min((float(m.sum()) for _, m, _ in turns), default=0.0)
        with np.errstate(all="ignore"):  # GEOS on subnormal coordinates
            r = float(shapely.length(shapely.maximum_inscribed_circle(shape, 0.1 * cell)))
        r = min(np.nan_to_num(r), np.sqrt(shape.area / np.pi))  # no circle beats the area
        self.radius = (r + reach) / cell - np.sqrt(0.5)


def _core(mask):
    """The 2 x 2 blocks of cells that hold a cell of ``mask`` wherever it sits on the grid of
    blocks (at each of the four parities of its place), trimmed to their bounding box; None if
    there are none."""
    my, mx = mask.shape
    h, w = (my + 2) // 2, (mx + 2) // 2
    core = np.ones((h, w), dtype=bool)
    for py in (0, 1):  # the parities of the place
        for px in (0, 1):
            grid = np.zeros((2 * h, 2 * w), dtype=bool)
            grid[py:py + my, px:px + mx] = mask > 0.5
            core &= grid.reshape(h, 2, w, 2).any(axis=(1, 3))
    rows, cols = np.flatnonzero(core.any(axis=1)), np.flatnonzero(core.any(axis=0))
    if not len(rows):
        return None
    return core[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1].astype(np.float64)


def _inscribed(mask) -> float:
    """The largest distance (cells) from a cell of ``mask`` to the nearest cell outside it."""
    return float(distance_transform_edt(np.pad(mask, 1)).max())


class _Page:
    """A page's occupancy grid and its Fourier transform, kept in step (one FFT per placed
    piece, one inverse FFT per mask tried)."""

    def __init__(self, ny: int, nx: int, spectra: dict):
        self.cells = np.zeros((ny, nx), dtype=np.float32)
        self.spectra = spectra  # mask spectra, shared by the pages of one packing
        self.shape = (next_fast_len(ny), next_fast_len(nx))  # no wrap where it is read
        self._fft = self._room = self._blocks = None

    def may_hold(self, options: _Options) -> bool:
        """False when no turn in ``options`` can fit anywhere: too few free cells, or no free
        disc as large as the one every turn holds (a mask that fits leaves its disc free)."""
        if self.cells.size - self.cells.sum() < options.cells:
            return False
        if self._room is None:
            self._room = _inscribed(self.cells < 0.5)
        return self._room >= options.radius - 1e-9

    def could_fit(self, core) -> bool:
        """False when a mask whose :func:`_core` is ``core`` fits nowhere, found on the grid of
        2 x 2 blocks (a quarter of the work): a block is taken when all its cells are, and a
        mask that fits leaves every block of its core with a free cell."""
        if core is None:
            return True
        if self._blocks is None:
            ny, nx = self.cells.shape
            taken = np.pad(self.cells >= 0.5, ((0, ny % 2), (0, nx % 2)), constant_values=True)
            blocks = _Page(*(np.array(taken.shape) // 2), self.spectra)
            blocks.cells = taken.reshape(len(taken) // 2, 2, -1, 2).all(axis=(1, 3)).astype(
                np.float32)
            self._blocks = blocks
        return bool((self._blocks.correlate(core) < 0.5).any())

    def add(self, mask, iy: int, ix: int) -> None:
        self.cells[iy:iy + mask.shape[0], ix:ix + mask.shape[1]] += mask
        self._fft = self._room = self._blocks = None

    def correlate(self, mask):
        """sum over (i, j) of cells[y + i, x + j] * mask[i, j] for every (y, x) where the mask
        lies inside the page."""
        if self._fft is None:
            self._fft = rfft2(self.cells, self.shape)
        key = id(mask)  # masks live as long as the packing
        if key not in self.spectra:
            self.spectra[key] = (mask, np.conj(rfft2(mask.astype(np.float32), self.shape)))
        full = irfft2(self._fft * self.spectra[key][1], self.shape)
        ny, nx = self.cells.shape
        return full[:ny - mask.shape[0] + 1, :nx - mask.shape[1] + 1]
