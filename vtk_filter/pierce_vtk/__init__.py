"""Pierce's VTK filters: exact multi-hit ray analyses on vtkPolyData and multiblock solids.

    from pierce_vtk import vtkPierceThickness, vtkPierceOverlaps, vtkPierceRayClassify
    from pierce_vtk import vtkPierceCADReader  # STEP, IGES, BREP
    from pierce_vtk import report              # the HTML report (docs/REPORT.md)
    from pierce_vtk import show_thickness      # pvpython: colour by Thickness over its default range

Works under /usr/bin/python3 and pvpython with ParaView's VTK (the `vtkmodules` package).
"""
from vtkmodules import vtkCommonExecutionModel as _vtkCommonExecutionModel  # base classes first

from .PierceVTK import *  # noqa: F401,F403
from .report import report  # noqa: F401
from .view import show_thickness  # noqa: F401

try:  # built when the core's OpenCASCADE loader is
    from .PierceVTKCAD import *  # noqa: F401,F403
except ImportError:
    pass
