"""Run by `paraview --script=...` (make_screenshot.sh): loads the Pierce plugin, opens the model,
applies Pierce Thickness coloured by Thickness, then writes the marker file so the caller knows
the GUI is ready to be captured. Paths come from the environment: PIERCE_PLUGIN, PIERCE_MODEL,
PIERCE_MARKER, and PYTHONPATH for thickness_view.py next to this script."""
import os

from paraview.simple import GetActiveViewOrCreate, Hide, LoadPlugin, OpenDataFile, Render, SetActiveSource
from thickness_view import show_thickness

LoadPlugin(os.environ["PIERCE_PLUGIN"], ns=globals())
model = OpenDataFile(os.environ["PIERCE_MODEL"])
thickness = PierceThickness(Input=model)  # noqa: F821 (defined by LoadPlugin)
thickness.SampleAt = "Cells"
thickness.MinThickness = 3.0

view = GetActiveViewOrCreate("RenderView")
Hide(model, view)
display = show_thickness(thickness, view, [26, -22, 20], [5, 5, 1.5])
display.SetScalarBarVisibility(view, True)
view.CameraParallelScale = 7
SetActiveSource(thickness)
Render(view)

with open(os.environ["PIERCE_MARKER"], "w") as f:
    f.write("ready\n")
