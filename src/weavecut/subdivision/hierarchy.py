"""Levels of a subdivision and their provenance."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh


@dataclass(frozen=True, eq=False)
class Level:
    """One refinement level: a mesh plus where each of its faces and edges came from.

    Level 0 (the input) has no provenance (all ``None``).

    Parameters
    ----------
    mesh : Mesh
    parent_face : (F,) int32, the parent face every face lies in
    parent_corner : (F,) int32, the corner of the parent face it was made for
    parent_edge : (E,) int32, the parent edge an edge descends from, or the parent face for
        edges born inside a face (see the scheme's ``EDGE_PARTS``)
    edge_part : (E,) int8, which part of its parent the edge is (scheme-specific codes)
    """

    mesh: Mesh
    parent_face: NDArray[np.int32] | None = None
    parent_corner: NDArray[np.int32] | None = None
    parent_edge: NDArray[np.int32] | None = None
    edge_part: NDArray[np.int8] | None = None


Hierarchy = tuple[Level, ...]
