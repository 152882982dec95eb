"""A drawing as a mesh: its closed outlines (``svg.read_rings``, ``dxf.read_rings``) checked,
holes found (``rings``), then the faces welded as drawn or the outline meshed inside
(``outline_mesh``)."""

from __future__ import annotations

import importlib
import re
from collections.abc import Callable
from pathlib import Path

import numpy as np
import shapely

from ..errors import MeshError, MeshFileError
from ..mesh import Mesh
from ..text import counted
from ..validation import validate
from . import DEFAULT_FLATTEN, DEFAULT_KIND, MESH_CHOICES, outline_mesh
from .rings import Ring, checked, enclosed_faces, nesting, split_t_junctions, weld

READERS = {".svg": "svg", ".dxf": "dxf"}  # the module of each; imported when one is read (ezdxf
# takes longer to import than an SVG takes to read)
MAX_BYTES = 64 * 2**20  # an untrusted drawing is read whole into memory


def read_drawing(path: str | Path, *, flatten: float = DEFAULT_FLATTEN,
                 layer: str | None = None, mesh: str = "auto", cell: float | None = None, runs: bool = False,
                 allow_nonconvex: bool = False,
                 report: Callable[[str], None] | None = None) -> Mesh:
    """Read an SVG or DXF drawing as a mesh in millimetres.

    Parameters
    ----------
    path : ``.svg`` or ``.dxf`` file
    flatten : largest distance (mm) between a curve and its polyline; points of neighbouring
        faces closer than this are merged into one vertex
    layer : read only this layer (DXF layer; SVG Inkscape layer or group, by label or id)
    mesh : ``auto`` meshes a drawing of one outline (holes allowed) and keeps the faces of any
        other drawing; ``none`` always keeps the faces as drawn; one of KINDS meshes the inside
        of the whole drawing
    cell : face size for meshing (mm); default: about 60 faces
    runs : when meshing, first redraw the outline as straight runs of one length, about a
        cell edge, between its corners (``outline_mesh._even_runs``; the puzzle's ring)
    allow_nonconvex : accept faces drawn non-convex (a meshed outline's faces are convex)
    report : called with one line saying what was read (counts, merges, mesh quality)
    """
    path = Path(path)
    if not path.is_file():
        raise MeshFileError(f"cannot read {path}: no such file")
    if path.stat().st_size > MAX_BYTES:
        raise MeshFileError(f"{path}: {path.stat().st_size / 2**20:.0f} MiB is more than a "
                            f"drawing of faces needs (at most {MAX_BYTES // 2**20} MiB)")
    reader = importlib.import_module(f".{READERS[path.suffix.lower()]}", __package__)
    found, pieces = reader.read_rings(path, flatten, layer)
    if not found and not pieces:
        raise MeshFileError(f"{path}: no outlines found")
    try:
        if pieces:
            found = enclosed_faces(found, pieces, flatten)
            if not found:  # lines of no length
                raise MeshFileError("its lines and arcs enclose no face")
        rings = checked(found, flatten)
        parent = nesting(rings, flatten)
        outer = np.flatnonzero(parent < 0)
        kind = _kind(mesh, len(outer), len(rings) - len(outer), rings, parent)
        if kind == "none":
            result, merged = weld([r.points for r in rings], flatten)
            result = _labelled(rings, validate, split_t_junctions(result, flatten),
                               allow_nonconvex=allow_nonconvex)
            line = (f"{path.name}: {result.n_faces} faces, {result.n_vertices} vertices "
                    f"({merged} points within {flatten:g} mm merged)")
        else:
            region = _region(rings, parent)
            cell = outline_mesh.default_cell(region) if cell is None else cell
            result = outline_mesh.mesh_outline(region, kind, cell, flatten, runs)
            q = outline_mesh.quality(result, cell)
            line = (f"{path.name}: {counted(len(outer), 'outline')}, "
                    f"{counted(len(rings) - len(outer), 'hole')}, "
                    f"{region.area:.0f} mm², meshed {kind} with cell {cell:.3g} mm: "
                    f"{q['faces']} faces, angles {q['min_angle']:.0f}-{q['max_angle']:.0f}°, "
                    f"size {q['min_size']:.2f}-{q['max_size']:.2f} × cell")
    except MeshError as exc:
        raise type(exc)(f"{path}: {exc}") from None
    if report is not None:
        report(line)
    return result


def _labelled(rings: list[Ring], check, mesh: Mesh, **options) -> Mesh:
    """``check(mesh)``, with every "face N" in its error followed by the element it was drawn
    as (faces keep the order of ``rings``)."""
    try:
        return check(mesh, **options)
    except MeshError as exc:
        text = re.sub(r"face (\d+)", lambda m: f"{m.group(0)} ({rings[int(m.group(1))].label})",
                      str(exc))
        raise type(exc)(text) from None


def _kind(mesh: str, n_outer: int, n_holes: int, rings: list[Ring], parent) -> str:
    if mesh not in MESH_CHOICES:
        raise MeshError(f"unknown --mesh {mesh!r}; choose one of {', '.join(MESH_CHOICES)}")
    if mesh == "auto":
        return DEFAULT_KIND if n_outer == 1 or n_holes else "none"
    if mesh == "none" and n_holes:
        hole = int(np.flatnonzero(parent >= 0)[0])
        raise MeshFileError(f"{rings[hole].label} lies inside {rings[parent[hole]].label}: a "
                            "face cannot have a hole; give --mesh KIND to mesh the drawing")
    return mesh


def _region(rings: list[Ring], parent: np.ndarray):
    """The drawing's inside: every outer ring minus its holes (one shapely geometry)."""
    outer = np.flatnonzero(parent < 0)
    polygons = [shapely.Polygon(rings[o].points,
                                [rings[h].points for h in np.flatnonzero(parent == o)])
                for o in outer]
    return shapely.union_all(polygons)
