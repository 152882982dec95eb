"""A triangle mesh as vtkPolyData and one vtk subdivision filter run on it: shared by the
benchmark (``bench_schemes.py``) and the peer fixtures (``tests/subdivision/peer_fixtures``),
so both run vtk the same way. Imports vtk and numpy only (the fixtures run without weave-cut)."""

from __future__ import annotations

import numpy as np


def subdivided(cls, xyz: np.ndarray, faces: np.ndarray, steps: int):
    """The vtkPolyData ``cls`` (a vtk subdivision filter class) makes of the triangles
    ``faces`` over the (V, 3) points ``xyz`` (given in double precision) in ``steps`` steps."""
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray

    pts = vtk.vtkPoints()
    pts.SetDataTypeToDouble()
    pts.SetData(numpy_to_vtk(np.asarray(xyz, dtype=np.float64), deep=True))
    faces = np.asarray(faces, dtype=np.int64)
    cells = vtk.vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(np.arange(0, faces.size + 1, 3, dtype=np.int64),
                                          deep=True),
                  numpy_to_vtkIdTypeArray(faces.ravel(), deep=True))
    poly = vtk.vtkPolyData()
    poly.SetPoints(pts)
    poly.SetPolys(cells)
    flt = cls()
    flt.SetInputData(poly)
    flt.SetNumberOfSubdivisions(steps)
    flt.Update()
    return flt.GetOutput()
