"""Where a white plate with a label goes near a spot: the first free place round it, clear of
the labels, plates and leader lines already on the page (:class:`Obstacles`, a list read
through a spatial index)."""

from __future__ import annotations

import numpy as np
import shapely

from ..layout.labels import MIN_CAP, centred_text, text_width


def free_spot(at, label: str, obstacles, frame, size: float, step: float = 30.0,
              reach: float = 8.0, lead: float = 0.0):
    """(text, white plate, leader line) near ``at``: neither the plate nor its leader line
    touches an obstacle, the leader at least ``lead`` long; None if there is no such place. The
    spots are tried ring by ring outwards (out to ``reach`` times ``size``), each ring round
    every ``step`` degrees from half a step: the first free one wins (the first three rings
    are tested together, then the others: most plates find a spot there). Where ``at`` itself
    touches an obstacle, none is tried: every leader ends there (or its plate holds it), so
    :func:`search_spot` would find none."""
    obstacles = obstacles if isinstance(obstacles, Obstacles) else Obstacles(obstacles)
    if obstacles and obstacles.hits([shapely.Point(at)])[0]:
        return None
    return search_spot(at, label, obstacles, frame, size, step, reach, lead)


def search_spot(at, label: str, obstacles, frame, size: float, step: float = 30.0,
                reach: float = 8.0, lead: float = 0.0):
    """:func:`free_spot`, every spot tried."""
    plate_pad = 0.8
    half = np.array([text_width(label, MIN_CAP) / 2 + plate_pad, MIN_CAP * 0.65 + plate_pad])
    at = np.asarray(at, dtype=float)
    r = (np.arange(1.0, reach, 0.75) * max(size, 2 * half[1]))[:, None]
    a = np.radians(np.arange(0, 360, step) + step / 2)[None, :]
    spots = 3 * a.shape[1]  # the first three rings, then all others at once
    c = np.stack([at[0] + r * np.cos(a), at[1] + r * np.sin(a)], axis=-1).reshape(-1, 2)
    x0, y0, x1, y1 = frame.bounds
    c = c[(c[:, 0] - half[0] >= x0) & (c[:, 1] - half[1] >= y0) & (c[:, 0] + half[0] <= x1)
          & (c[:, 1] + half[1] <= y1)]
    plates = shapely.box(*(c - half).T, *(c + half).T)
    leaders = shapely.linestrings(np.stack([np.clip(at, c - half, c + half),
                                            np.broadcast_to(at, c.shape)], axis=1))
    first = None
    obstacles = obstacles if isinstance(obstacles, Obstacles) else Obstacles(obstacles)
    for ring, end in ((0, spots), (spots, len(c))):  # the nearest spots first, then the rest
        free = np.flatnonzero(~obstacles.hits(plates[ring:end])) + ring if obstacles \
            else np.arange(ring, min(end, len(c)))
        free = free[~obstacles.hits(leaders[free])] if obstacles else free
        free = free[shapely.length(leaders[free]) >= lead]
        if len(free):
            first = int(free[0])
            break
    if first is None:
        return None
    return centred_text(c[first], label, MIN_CAP, 0.0, "#000000"), plates[first], leaders[first]


REINDEX = 12  # obstacles added before the index is made again


class Obstacles(list):
    """The shapes later labels keep clear of (a list): :meth:`hits` reads a spatial index of
    them, made again only when many were added since (those are tested one by one)."""

    def hits(self, shapes) -> np.ndarray:
        """(n,) whether each of ``shapes`` touches an obstacle."""
        if len(self) - getattr(self, "_indexed", -REINDEX - 1) > REINDEX:
            self._tree, self._indexed = shapely.STRtree(list(self)), len(self)
        hit = np.zeros(len(shapes), dtype=bool)
        if len(shapes) and self._indexed:
            hit[self._tree.query(shapes, predicate="intersects")[0]] = True
        if len(shapes) and len(self) > self._indexed:
            new = np.array(self[self._indexed:], dtype=object)
            hit |= shapely.intersects(np.asarray(shapes)[:, None], new[None, :]).any(axis=1)
        return hit
