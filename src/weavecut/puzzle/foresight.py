"""What a puzzle will be, read from its last snub level before it is built: how many pieces it
has and bounds on its smallest piece. ``workshop.drawing_defaults`` builds only the
candidates these leave open (building one costs about a hundred times more).

A piece is an octagon (two pentagons glued along their Z middle edge, local edge 1 of both) or
a boundary pentagon (alone, or with its ring hexagon), so the pieces number the faces less the
octagons. An octagon piece is its two pentagons' corners, scaled by the puzzle's scale (and
snapped by far less than the slack below). That scale is at most ``(size - frame_width) / W``
with W the level's width: the frame's outer outline is the ring's outer boundary (which holds
every face) offset by ``frame_width`` on both sides (round joins, so by a little less than
``frame_width`` where they are polygons) and measures ``size`` across. A bound under the
workshop's limits therefore proves the puzzle is not comfortable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely
from numpy.typing import NDArray

from ..mesh import Mesh

SLACK = 1e-6  # relative: the bounds are raised by this much (snapping, rounding)


@dataclass(frozen=True, eq=False)
class Foresight:
    """What the puzzle of snub level ``mesh`` (pentagons) at ``size`` mm wide with a
    ``frame_width`` mm frame (``build_puzzle(..., "width")``) will be: ``pieces``, its piece
    count (exact); ``across``, ``width``: mm, at least its smallest piece's size across and
    width (``workshop.piece_sizes``), each found when first asked for."""

    mesh: Mesh
    size: float
    frame_width: float

    @cached_property
    def _octagons(self) -> NDArray[np.float64]:
        """(O, 10, 2) the corners of each octagon's two pentagons, model units."""
        mesh = self.mesh
        faces = mesh.dense_faces()
        edge = mesh.face_offsets[:-1] + 1  # each pentagon's Z middle edge
        twin = mesh.topology.twin[edge]
        other = np.where(twin >= 0, mesh.half_edge_face[np.maximum(twin, 0)], -1)
        glued = (twin >= 0) & (twin - mesh.face_offsets[np.maximum(other, 0)] == 1)
        first = np.flatnonzero(glued & (np.arange(len(faces)) < other))
        return mesh.vertices[np.concatenate([faces[first], faces[other[first]]], axis=1)]

    @cached_property
    def pieces(self) -> int:
        return self.mesh.n_faces - len(self._octagons)

    @cached_property
    def _scale(self) -> float:
        """At least the puzzle's mm per model unit, raised by SLACK twice."""
        wide = float(np.ptp(self.mesh.vertices[:, 0]))
        return (self.size - self.frame_width) / wide * (1.0 + SLACK) ** 2

    @cached_property
    def across(self) -> float:
        corners = self._octagons
        if len(corners) == 0:
            return math.inf
        return float(np.linalg.norm(corners[:, :, None] - corners[:, None], axis=3).max(
            axis=(1, 2)).min()) * self._scale

    @cached_property
    def width(self) -> float:
        corners = self._octagons
        if len(corners) == 0:
            return math.inf
        box = shapely.minimum_rotated_rectangle(shapely.multipoints(corners))
        ring = shapely.get_coordinates(shapely.get_exterior_ring(box)).reshape(len(box), -1, 2)
        return float(np.linalg.norm(ring[:, 1:3] - ring[:, 0:2], axis=2).min()) * self._scale


def foresee(mesh: Mesh, size: float, frame_width: float) -> Foresight:
    """The Foresight of the puzzle of snub level ``mesh`` at ``size`` mm wide with a
    ``frame_width`` mm frame."""
    return Foresight(mesh, size, frame_width)
