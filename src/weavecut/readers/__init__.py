"""The file formats weave-cut reads: mesh files (OBJ, weave-cut's JSON) and drawings (SVG and
DXF outlines as faces, or one outline meshed inside); ``mesh_io`` opens the files.

Modules: ``obj`` (with ``obj_tokens``) and ``mesh_json`` parse mesh files within
``MAX_FACES`` and ``MAX_VERTICES``; ``svg`` and ``dxf`` read closed outlines in mm, ``rings``
checks them, finds holes and welds faces, ``outline_mesh`` meshes an outline (from the cells
``tessellations`` lays out), ``drawing`` puts them together (``drawing.read_drawing``), all
within the limits of ``budgets``. This module holds only the names they share, so that
``mesh_io`` and the command line load without the drawing readers (svgelements, ezdxf's reader
and scipy's spatial tools take a while to import).
"""

from __future__ import annotations

SUFFIXES = (".svg", ".dxf")
KINDS = ("hex", "quad", "tri", "voronoi")  # ways to mesh an outline (outline_mesh)
MESH_CHOICES = ("auto", "none", *KINDS)
DEFAULT_FLATTEN = 0.2  # mm
DEFAULT_KIND = "hex"
MAX_FACES = 2**24  # read from a mesh file: 16.8 million, 1.7 times the pentagon's level 10
MAX_VERTICES = 2**25
