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

# The enum options also take core's names (the codes are positions in core's tables), and an
# unknown name leaves the option as it was.
g = vtkPierceThickness()
g.SetMethod("cone")
g.SetSampleAt("face")
g.SetConeAggregate("median")
names = (g.GetMethodAsString(), g.GetSampleAtAsString(), g.GetConeAggregateAsString())
codes = (g.GetMethod(), g.GetSampleAt(), g.GetConeAggregate())
if names != ("cone", "face", "median") or codes != (vtkPierceThickness.CONE, vtkPierceThickness.CELLS,
                                                    vtkPierceThickness.MEDIAN):
    print("FAIL: options by name gave %s %s" % (names, codes))
    sys.exit(1)
g.GlobalWarningDisplayOff()  # the error for the unknown name below is expected
g.SetMethod("laser")
if g.GetMethod() != vtkPierceThickness.CONE:
    print("FAIL: an unknown method name changed the method to %d" % g.GetMethod())
    sys.exit(1)
print("pierce_vtk ok under " + sys.executable)
