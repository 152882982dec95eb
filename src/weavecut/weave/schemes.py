"""The weave that belongs to each subdivision scheme (paper 5.3), for every level of a run.

snub: octagon strands; Catmull-Clark: its quad two-colouring; Loop and butterfly: triangles
glued across c2-c2 edges with the colouring carried from level to level; sqrt3: triangles glued
across the just-flipped edges; any scheme with ``face_split=True`` or without a weave of its own:
the general face-split weave (Mercat's Celtic links).
"""

from __future__ import annotations

from ..subdivision.hierarchy import Hierarchy
from .face_split import face_split_weave
from .model import Weave
from .quad import quad_weave
from .snub_weave import snub_weaves
from .triangles import sqrt3_weave, triangle_weave
from .two_colouring import catmull_clark_colouring, triangle_colouring_step, triangle_three_colouring

NATURAL = {"snub": "octagon strands", "catmull-clark": "two-coloured quads",
           "loop": "glued triangles", "butterfly": "glued triangles",
           "sqrt3": "triangles glued across flipped edges"}


def scheme_weaves(hierarchy: Hierarchy, scheme: str, face_split: bool = False) -> list[Weave]:
    """Weaves of levels 1..N (snub: with lineage), or of level 0..N for the face-split weave."""
    if face_split or scheme not in NATURAL:
        return [face_split_weave(level.mesh) for level in hierarchy]
    if scheme == "snub":
        return snub_weaves(hierarchy)
    if scheme == "catmull-clark":
        return [quad_weave(level.mesh, catmull_clark_colouring(level)) for level in hierarchy[1:]]
    if scheme == "sqrt3":
        return [sqrt3_weave(level, parent.mesh.n_vertices)
                for parent, level in zip(hierarchy, hierarchy[1:])]
    c1 = triangle_three_colouring(hierarchy[0].mesh)
    weaves = []
    for parent, level in zip(hierarchy, hierarchy[1:]):
        c1 = triangle_colouring_step(parent.mesh, c1)
        weaves.append(triangle_weave(level.mesh, c1))
    return weaves
