"""`from pierce_vtk import ...` works (run under /usr/bin/python3 and under pvpython with
PYTHONPATH=<build>/python) and the filters run: a 1 x 2 x 3 box's per-cell thickness is its
extent along each face's normal."""
import sys

from pierce_vtk import vtkPierceCADReader, vtkPierceOverlaps, vtkPierceRayClassify, vtkPierceThickness  # noqa: F401
from vtkmodules.vtkFiltersSources import vtkCubeSource

cube = vtkCubeSource()
cube.SetBounds(0, 1, 0, 2, 0, 3)
f = vtkPierceThickness()
f.SetSampleAt(vtkPierceThickness.CELLS)
f.SetInputConnection(cube.GetOutputPort())
f.Update()
array = f.GetOutputDataObject(0).GetCellData().GetArray("Thickness")
values = sorted(round(array.GetValue(i), 9) for i in range(array.GetNumberOfTuples()))
expected = [1.0] * 4 + [2.0] * 4 + [3.0] * 4
if values != expected:
    print("FAIL: thickness %s, expected %s" % (values, expected))
    sys.exit(1)
print("pierce_vtk ok under " + sys.executable)
