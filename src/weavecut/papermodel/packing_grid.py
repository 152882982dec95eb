"""The packer's raster: the masks of a piece's turns on a grid of cells, their cores on blocks
of k x k cells, and pages that say where a core lies on free blocks only (one FFT correlation).

A block of a page is taken when all its cells are; the core of a mask is the blocks that hold a
cell of the mask wherever it sits on the grid of blocks. A mask that fits a page cell by cell
thus leaves every block of its core with a free cell: the block test never refuses a place
that fits, and it narrows the places to try to the cells of the blocks it leaves."""

from __future__ import annotations

import functools

import numpy as np
import shapely
from numpy.fft import irfft2, rfft2

from ..numeric import affine


def fast_len(n: int) -> int:
    """The least size >= ``n`` whose prime factors are 2, 3, 5, 7 and 11, which pocketfft
    transforms fastest (``scipy.fft.next_fast_len``'s answer, without importing scipy).

    Examples
    --------
    >>> [fast_len(n) for n in (1, 13, 17, 97, 1000)]
    [1, 14, 18, 98, 1000]
    """
    m = n
    while True:
        k = m
        for p in (2, 3, 5, 7, 11):
            while k % p == 0:
                k //= p
        if k == 1:
            return m
        m += 1

BLOCKS = (8, 4, 2, 1)  # the block tests' sizes (cells), coarsest first; 1: cell by cell


def turned_masks(shape, angles, gap: float, cell: float, width: float, height: float) -> list:
    """(angle, mask, origin) for each of ``angles`` by which ``shape`` turned fits the area:
    origin is where cell (0, 0) of the mask starts in the turned frame. The turn by a + 180
    is the turn by a read backwards (the grid is symmetric), so only turns below 180 degrees
    are drawn, all at once."""
    reach = gap / 2 + cell * np.sqrt(0.5)
    grown = shapely.buffer(shape, reach / np.cos(np.pi / 16), quad_segs=4)  # holds the disc
    xy, ring = shapely.get_coordinates(shapely.get_rings(shapely.get_parts(grown)),
                                       return_index=True)
    half = tuple(a for a in angles if a < 180)
    turn = _turns(half)  # (A, 1, 2, 2)

    def turned(points):  # (A, N, 2)
        return points[:, 0, None] * turn[..., 0] + points[:, 1, None] * turn[..., 1]

    own = turned(shapely.get_coordinates(shape))
    origin = own.min(axis=1) - reach
    size = np.ceil((own.max(axis=1) + reach - origin) / cell).astype(np.int64)  # (nx, ny)
    fit = np.flatnonzero((size[:, 0] <= width // cell) & (size[:, 1] <= height // cell))
    masks = raster((turned(xy)[fit] - origin[fit, None]) / cell - 0.5,
                   np.flatnonzero(ring[1:] == ring[:-1]), size[fit, ::-1])
    out = [(half[a], m, origin[a]) for a, m in zip(fit.tolist(), masks)]
    return out + [(a + 180.0, m[::-1, ::-1].copy(), -o - np.array(m.shape[::-1]) * cell)
                  for a, m, o in out]


@functools.cache
def _turns(angles: tuple) -> np.ndarray:
    """(A, 1, 2, 2) read-only: the matrices turning by each of ``angles`` (degrees), made once
    per packing's angles."""
    turn = np.array([affine(a)[:2, :2] for a in angles])[:, None]
    turn.flags.writeable = False
    return turn


def raster(uv, edges, shapes) -> list:
    """For each grid a, (ny, nx) = ``shapes[a]`` bool: the cells whose centre lies inside the
    rings with vertices ``uv[a]`` (N, 2) (in cells, centres at whole numbers), an edge from
    each vertex in ``edges`` to the next; even-odd along each row of centres, every grid at
    once."""
    (ua, va), (ub, vb) = uv[:, edges].transpose(2, 0, 1), uv[:, edges + 1].transpose(2, 0, 1)
    ny, nx = shapes[:, 0, None], shapes[:, 1]
    first = np.clip(np.ceil(np.minimum(va, vb)), 0, ny).astype(np.int64)
    count = np.clip(np.ceil(np.maximum(va, vb)), 0, ny).astype(np.int64) - first
    count = np.maximum(count, 0).ravel()  # rows crossed by each edge (centres on a lower end)
    e = np.repeat(np.arange(len(count)), count)
    rows = first.ravel()[e] + np.arange(len(e)) - np.repeat(np.cumsum(count) - count, count)
    (ua, va, ub, vb), grid = (w.ravel()[e] for w in (ua, va, ub, vb)), e // len(edges)
    u = ua + (rows - va) / (vb - va) * (ub - ua)
    starts = np.cumsum(shapes[:, 0] * (nx + 1)) - shapes[:, 0] * (nx + 1)
    line = starts[grid] + rows * (nx + 1)[grid]  # where the row starts, in all grids' cells
    at = line + np.clip(np.ceil(u), 0, nx[grid]).astype(np.int64)  # first cell right of it
    total = int(starts[-1] + shapes[-1, 0] * (nx[-1] + 1)) if len(shapes) else 0
    # inside: an odd number of crossings left of the centre (each row has an even number)
    odd = (np.bincount(at, minlength=total) & 1).astype(np.uint8)
    inside = np.bitwise_xor.accumulate(odd).view(bool)
    return [inside[s:s + h * (w + 1)].reshape(h, w + 1)[:, :w]
            for s, (h, w) in zip(starts.tolist(), shapes.tolist())]


class Options(list):
    """The turns (angle, mask, origin) of a piece or stack, the second half of them the first
    turned by half a turn, in order (:func:`turned_masks`), with ``rank[axis]`` their order
    shortest along that axis first (0: y, 1: x), ``cells`` the fewest cells of any turn's
    mask (a page with fewer free cells holds no turn), and the turns' ``cores`` and their
    ``offsets`` on the coarsest blocks (:func:`block_cores`); :meth:`core` for the others."""

    def __init__(self, turns):
        super().__init__(turns)
        self.rank = []
        for axis in (0, 1):
            order = sorted(range(len(turns)), key=lambda t: (turns[t][1].shape[axis], turns[t][0]))
            self.rank.append(np.argsort(order).tolist())
        self.cells = min((int(np.count_nonzero(m)) for _, m, _ in turns), default=0)
        self._cores: dict = {}
        cores = [self.core(BLOCKS[0], t) for t in range(len(turns))]
        self.cores, self.offsets = [c for c, _ in cores], [o for _, o in cores]
        self.sizes = np.array([m.shape for _, m, _ in turns], dtype=np.int64).reshape(-1, 2)

    def core(self, k: int, t: int):
        """(core, offset) of turn ``t`` on k x k blocks, made when first asked for (with its
        half-turned twin's)."""
        if (k, t) not in self._cores:
            first, half = t % (len(self) // 2), len(self) // 2
            self._cores[k, first], self._cores[k, first + half] = block_cores(self[first][1], k)
        return self._cores[k, t]


def block_cores(mask, k: int) -> list:
    """[(core, offset)] of ``mask`` and of ``mask`` turned by half a turn (read backwards):
    the k x k blocks of cells that hold a cell of the mask wherever it sits on the grid of
    blocks (at each of the k * k parities of its place), trimmed to their bounding box, which
    starts ``offset`` (rows, columns) blocks from the block of the mask's first cell; core is
    None if there are none. A mask whose cell (0, 0) is at (iy, ix) thus puts a cell into every
    block of its core placed at (iy // k, ix // k) + offset."""
    my, mx = mask.shape
    h, w = (my + 2 * k - 2) // k, (mx + 2 * k - 2) // k
    grid = np.zeros((k * h + 3 * k - 2, k * w + 3 * k - 2), dtype=bool)
    grid[2 * k - 2:2 * k - 2 + my, 2 * k - 2:2 * k - 2 + mx] = mask
    # held[r]: grid's rows r ... r + k - 1 (mask rows r - 2 k + 2 ...) hold a cell; all[r]:
    # held[r ... r + k - 1] all do. Block b at parity p holds mask rows k b - p ... k b - p +
    # k - 1: every parity, all[k b + k - 1]; read backwards, all[my + k - 2 - k b]
    held = _window(_window(grid, k, np.logical_or).T, k, np.logical_or).T
    every = _window(_window(held, k, np.logical_and).T, k, np.logical_and).T
    return [_trimmed(every[k - 1::k, k - 1::k][:h, :w]),
            _trimmed(every[my + k - 2::-k, mx + k - 2::-k][:h, :w])]


def _trimmed(core):
    rows, cols = np.flatnonzero(core.any(axis=1)), np.flatnonzero(core.any(axis=0))
    if not len(rows):
        return None, (0, 0)
    return core[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1], (int(rows[0]), int(cols[0]))


def _window(a, k: int, op):
    """``op`` (logical or, and) over every k consecutive rows of ``a``: row i of the answer
    joins rows i ... i + k - 1."""
    done = 1  # rows joined so far
    while done < k:
        step = min(done, k - done)
        a, done = op(a[:-step], a[step:]), done + step
    return a


class Page:
    """A page's taken cells, and for each block size their blocks (a block is taken when all
    its cells are) with the blocks' Fourier transform, made when first asked for."""

    def __init__(self, ny: int, nx: int, spectra: dict):
        self.taken = np.zeros((ny, nx), dtype=bool)
        self.free = ny * nx
        self.spectra = spectra  # the cores' transforms, shared by the pages of one packing
        self._blocks: dict = {}

    def may_hold(self, options: Options) -> bool:
        """False when the page has fewer free cells than any turn in ``options`` needs."""
        return self.free >= options.cells

    def add(self, mask, iy: int, ix: int) -> None:
        self.taken[iy:iy + mask.shape[0], ix:ix + mask.shape[1]] |= mask
        self.free = self.taken.size - int(np.count_nonzero(self.taken))
        self._blocks = {}

    def fits(self, k: int, cores) -> list:
        """For each core (of k x k blocks, see :func:`block_cores`): the block places where it
        lies on free blocks only ((rows, columns) bool, trimmed to the places inside the page; no
        place holds a mask that the core does not fit), None for no core (:meth:`places`)."""
        free = self.places(k, cores)
        ny, nx = free.shape[1:]
        return [None if c is None else f[:ny - c.shape[0] + 1, :nx - c.shape[1] + 1]
                for f, c in zip(free, cores)]

    def fits_at(self, k: int, core, rows, columns) -> np.ndarray:
        """:meth:`fits` of ``core`` read at the block places (``rows``, ``columns``) only,
        False elsewhere: the blocks under the core's cells at each place, at once."""
        blocks = self.blocks(k)
        out = np.zeros((blocks.shape[0] - core.shape[0] + 1, blocks.shape[1] - core.shape[1] + 1),
                       dtype=bool)
        keep = (rows >= 0) & (columns >= 0) & (rows < out.shape[0]) & (columns < out.shape[1])
        rows, columns = rows[keep], columns[keep]
        width = blocks.shape[1]  # the blocks read by their numbers, row by row
        under = np.flatnonzero(core.ravel()) + np.arange(core.shape[0]).repeat(core.shape[1])[
            core.ravel()] * (width - core.shape[1])
        out[rows, columns] = ~blocks.ravel()[(rows * width + columns)[:, None] + under].any(
            axis=1)
        return out

    def blocks(self, k: int) -> np.ndarray:
        """The page's k x k blocks (rows, columns) bool: True where all their cells are taken
        (the cells beyond the page's edge are)."""
        if k not in self._blocks:
            ny, nx = self.taken.shape
            taken = np.ones((ny + -ny % k, nx + -nx % k), dtype=bool)  # beyond the page: taken
            taken[:ny, :nx] = self.taken
            columns = taken[:, ::k].copy()  # the blocks' rows, then the blocks
            for i in range(1, k):
                columns &= taken[:, i::k]
            blocks = columns[::k].copy()
            for i in range(1, k):
                blocks &= columns[i::k]
            self._blocks[k] = blocks, None
        return self._blocks[k][0]

    def places(self, k: int, cores) -> np.ndarray:
        """(cores, rows, columns) bool: :meth:`fits` of every core on one grid of the page's
        blocks, False beyond the places inside the page (everywhere for no core). All cores
        at once: one inverse FFT of the page's transform times each core's."""
        blocks = self.blocks(k)
        if self._blocks[k][1] is None:
            shape = tuple(fast_len(n) for n in blocks.shape)  # no wrap where it is read
            self._blocks[k] = blocks, (shape, rfft2(blocks.astype(np.float32), shape))
        shape, page = self._blocks[k][1]
        ny, nx = blocks.shape
        key = (k, shape, *map(id, cores))
        if key not in self.spectra:
            stack = np.zeros((len(cores), *shape), dtype=np.float32)
            for s, c in zip(stack, cores):
                if c is not None:
                    s[:c.shape[0], :c.shape[1]] = c
            size = np.array([(ny + 1, nx + 1) if c is None else c.shape for c in cores],
                            dtype=np.int64).reshape(-1, 2)
            inside = (np.arange(ny)[:, None] <= ny - size[:, :1, None]) & \
                (np.arange(nx) <= nx - size[:, 1:, None])  # the places inside the page
            self.spectra[key] = cores, np.conj(rfft2(stack, shape)), inside  # keeps cores alive
        _, spectrum, inside = self.spectra[key]
        return (irfft2(page * spectrum, shape)[:, :ny, :nx] < 0.5) & inside


def start_cells(k: int, fits, offset, size, page, axis: int):
    """The cells (iy, ix) where a mask of ``size`` (rows, columns) may start on a page of
    ``page`` cells: those of the k x k blocks at the places ``fits`` leaves less ``offset``
    (see :func:`block_cores`; None: everywhere), least along ``axis`` first, then across."""
    last = [p - s for p, s in zip(page, size)]  # the farthest start
    fits = np.ones((last[0] + 1, last[1] + 1), dtype=bool) if fits is None else fits
    fits = fits if axis == 1 else fits.T  # (across, along)
    for b in np.flatnonzero(fits.any(axis=0)).tolist():
        across = (np.flatnonzero(fits[:, b]) - offset[1 - axis])[:, None] * k + np.arange(k)
        across = across[(across >= 0) & (across <= last[1 - axis])].tolist()
        for along in range(max((b - offset[axis]) * k, 0), (b - offset[axis] + 1) * k):
            if along > last[axis]:
                return
            for c in across:
                yield (c, along) if axis == 1 else (along, c)
