"""Where non-convex faces occur (paper section 3.2 and its open question on smoothing).

For every level: how many faces are non-convex, whether they are inner faces or touch the
boundary, and at which kind of vertex the reflex corner sits: an input vertex, a face centre
or a Z vertex (the snub numbering tells them apart), outer or inner, and of which degree.
The counts use :func:`analysis.stats.nonconvex_faces`, so they agree with ``weave-cut stats``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh, outer_vertices, vertex_degrees
from ..mesh_geometry import corner_angles
from .stats import REFLEX_EPS, nonconvex_faces

ORIGINS = ("input", "z", "centre")
ORIGIN_NAMES = ("input vertices", "Z vertices", "face centres")


def vertex_origins(hierarchy) -> list[NDArray[np.int8]]:
    """Per level, (V,) index into ORIGINS: how each vertex was born (snub numbering)."""
    out = [np.zeros(hierarchy[0].mesh.n_vertices, dtype=np.int8)]
    for t in range(1, len(hierarchy)):
        parent = hierarchy[t - 1].mesh
        n_v, n_e = parent.n_vertices, parent.topology.n_edges
        origin = np.empty(hierarchy[t].mesh.n_vertices, dtype=np.int8)
        if len(origin) != n_v + 2 * n_e + parent.n_faces:
            raise ValueError("vertex origins follow the snub numbering; this is another scheme")
        origin[:n_v] = out[-1]
        origin[n_v:n_v + 2 * n_e] = 1
        origin[n_v + 2 * n_e:] = 2
        out.append(origin)
    return out


def boundary_faces(mesh: Mesh) -> NDArray[np.bool_]:
    """(F,) True for faces with an edge on the boundary."""
    topo = mesh.topology
    on_boundary = topo.boundary_edges[topo.half_edge_edge]
    return np.bincount(mesh.half_edge_face[on_boundary], minlength=mesh.n_faces) > 0


def reflex_corners(mesh: Mesh) -> NDArray[np.bool_]:
    """(H,) True at corners with an interior angle above 180 degrees (the stats threshold)."""
    return corner_angles(mesh) > np.pi + REFLEX_EPS


CHUNK = 1 << 18  # faces per batch in reflex_corner_ids


def reflex_corner_ids(mesh: Mesh) -> NDArray[np.int64]:
    """Ids of the corners :func:`reflex_corners` marks, found batch by batch of faces: only
    corners whose edges turn right get an angle, and no (H,)-sized temporary is made, so
    checking a level of millions of faces costs little time and memory next to building it."""
    v, fi, offsets = mesh.vertices, mesh.face_indices, mesh.face_offsets
    found = [np.zeros(0, dtype=np.int64)]
    for f0 in range(0, mesh.n_faces, CHUNK):  # a loop over batches of faces
        bounds = offsets[f0:min(f0 + CHUNK, mesh.n_faces) + 1]
        h0, starts, ends = bounds[0], bounds[:-1] - bounds[0], bounds[1:] - bounds[0]
        nxt = np.arange(1, ends[-1] + 1)
        nxt[ends - 1] = starts
        prv = np.empty_like(nxt)
        prv[nxt] = np.arange(len(nxt))
        p = v[fi[h0:h0 + ends[-1]]]
        a = p[prv] - p
        b = p[nxt] - p
        cross = b[:, 0] * a[:, 1] - b[:, 1] * a[:, 0]   # as in corner_angles
        turn = np.flatnonzero(cross < 0)
        angle = np.mod(np.arctan2(cross[turn], (a[turn] * b[turn]).sum(axis=1)), 2 * np.pi)
        found.append(h0 + turn[angle > np.pi + REFLEX_EPS])
    return np.concatenate(found)


def level_convexity(mesh: Mesh, level: int, origin: NDArray[np.int8]) -> dict:
    """The convexity findings of one level (see the module docstring)."""
    bad = nonconvex_faces(mesh)
    at_boundary = boundary_faces(mesh)
    reflex = reflex_corners(mesh)
    verts = mesh.face_indices[reflex]
    outer = outer_vertices(mesh)[verts]
    degrees = vertex_degrees(mesh)[verts]
    kinds = origin[verts]
    by_kind = {}
    for k, name in enumerate(ORIGINS):
        for where, mask in (("inner", ~outer), ("outer", outer)):
            n = int(((kinds == k) & mask).sum())
            if n:
                by_kind[f"{name} {where}"] = n
    angles = corner_angles(mesh)
    return {
        "level": level,
        "faces": mesh.n_faces,
        "nonconvex_faces": int(bad.sum()),
        "nonconvex_inner_faces": int((bad & ~at_boundary).sum()),
        "nonconvex_boundary_faces": int((bad & at_boundary).sum()),
        "reflex_corners": int(reflex.sum()),
        "reflex_at": by_kind,
        "reflex_vertex_degrees": {str(d): int(c) for d, c in
                                  zip(*np.unique(degrees, return_counts=True))},
        "max_angle_deg": round(math.degrees(float(angles.max())), 6) if len(angles) else 0.0,
    }


def convexity_report(hierarchy) -> list[dict]:
    """:func:`level_convexity` for every level of a snub hierarchy."""
    origins = vertex_origins(hierarchy)
    return [level_convexity(lv.mesh, t, o) for t, (lv, o) in enumerate(zip(hierarchy, origins))]


def nonconvex_levels(hierarchy, first: int = 1) -> list[dict]:
    """Every level from ``first`` on that has non-convex faces, and where their reflex corners are.

    Returns
    -------
    list of dict ``{"level", "faces", "nonconvex_faces", "where"}``, where ``where`` lists
    ``(faces, description)`` pairs such as ``(72, "outer Z vertices of degree 3")``: the
    number of non-convex faces with a reflex corner at that kind of vertex (input vertex,
    Z vertex or face centre for a snub hierarchy; for other schemes only inner/outer and
    degree). A face with reflex corners of two kinds counts in both.

    Examples
    --------
    >>> from weavecut import inputs
    >>> from weavecut.subdivision import subdivide
    >>> nonconvex_levels(subdivide(inputs.get("ngon:24"), 5))[0]["where"]
    [(72, 'outer Z vertices of degree 3')]
    """
    reflex = [reflex_corner_ids(lv.mesh) if t >= first else np.zeros(0, dtype=np.int64)
              for t, lv in enumerate(hierarchy)]
    if not any(len(r) for r in reflex):
        return []
    try:
        origins = vertex_origins(hierarchy)
    except ValueError:  # another scheme: no origin classes
        origins = [None] * len(hierarchy)
    rows = []
    for t, corners in enumerate(reflex):  # a loop over levels
        if len(corners):
            mesh = hierarchy[t].mesh
            faces = np.searchsorted(mesh.face_offsets, corners, side="right") - 1
            rows.append({"level": t, "faces": mesh.n_faces,
                         "nonconvex_faces": int(len(np.unique(faces))),
                         "where": _where(mesh, corners, faces, origins[t])})
    return rows


def _where(mesh: Mesh, corners, faces, origin: NDArray[np.int8] | None) -> list[tuple[int, str]]:
    """(faces, description) per class of the vertex at the reflex ``corners`` (of ``faces``),
    most faces first."""
    verts = mesh.face_indices[corners]
    outer = outer_vertices(mesh)[verts].astype(np.int64)
    degree = vertex_degrees(mesh)[verts]
    kind = np.full(len(verts), len(ORIGINS)) if origin is None else origin[verts].astype(np.int64)
    cls = (kind * 2 + outer) * (int(degree.max()) + 1) + degree
    pairs = np.unique(np.column_stack([cls, faces]), axis=0)
    classes, n_faces = np.unique(pairs[:, 0], return_counts=True)
    order = np.lexsort((classes, -n_faces))
    out = []
    for c, n in zip(classes[order].tolist(), n_faces[order].tolist()):  # a loop over classes
        rest, d = divmod(c, int(degree.max()) + 1)
        k, o = divmod(rest, 2)
        name = ORIGIN_NAMES[k] if k < len(ORIGINS) else "vertices"
        out.append((n, f"{'outer' if o else 'inner'} {name} of degree {d}"))
    return out


SEE = "; see weave-cut convexity"  # ends a non-convex warning: for the terminal, not the
# workshop (a maker can do nothing about a face of the subdivision)


def nonconvex_message(row: dict) -> str:
    """One line for a row of :func:`nonconvex_levels`, e.g. ``level 5: 72 of 15,000 faces are
    non-convex (72 at outer Z vertices of degree 3)``."""
    where = "; ".join(f"{n:,} at {text}" for n, text in row["where"])
    return (f"level {row['level']}: {row['nonconvex_faces']:,} of {row['faces']:,} faces are "
            f"non-convex ({where})")
