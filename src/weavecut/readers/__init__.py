"""The file formats weave-cut reads: mesh files (OBJ, weave-cut's JSON) and drawings (SVG and
DXF outlines as faces, or one outline meshed inside); ``mesh_io`` opens the files.

Modules: ``obj`` (with ``obj_tokens``) and ``mesh_json`` parse mesh files within
``MAX_FACES`` and ``MAX_VERTICES``; ``svg`` and ``dxf`` read closed outlines in mm, ``rings``
checks them, finds holes and welds faces, ``outline_mesh`` meshes an outline (from the cells
``tessellations`` lays out), ``drawing`` puts them together. The drawing modules load on first
use (svgelements, ezdxf's reader and scipy's spatial tools take a while to import).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..mesh import Mesh

SUFFIXES = (".svg", ".dxf")
KINDS = ("hex", "quad", "tri", "voronoi")  # ways to mesh an outline (outline_mesh)
MESH_CHOICES = ("auto", "none", *KINDS)
DEFAULT_FLATTEN = 0.2  # mm
DEFAULT_KIND = "hex"
MAX_FACES = 2**24  # read from a mesh file: 16.8 million, 1.7 times the pentagon's level 10
MAX_VERTICES = 2**25


def read_drawing(path: str | Path, *, flatten: float = DEFAULT_FLATTEN, layer: str | None = None,
                 mesh: str = "auto", cell: float | None = None, runs: bool = False,
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
    from .drawing import read

    return read(Path(path), flatten=flatten, layer=layer, mesh=mesh, cell=cell, runs=runs,
                allow_nonconvex=allow_nonconvex, report=report)
