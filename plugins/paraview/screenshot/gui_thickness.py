"""Run by `paraview --script=...` (make_screenshot.sh): loads the Pierce plugin, opens the model,
applies Pierce Thickness coloured by Thickness, then writes the marker file so the caller knows
the GUI is ready to be captured. Paths come from the environment: PIERCE_PLUGIN, PIERCE_MODEL,
PIERCE_MARKER."""
import os

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, GetDisplayProperties,
                             Hide, LoadPlugin, OpenDataFile, Render, ResetCamera, SetActiveSource, Show)

LoadPlugin(os.environ["PIERCE_PLUGIN"], ns=globals())
model = OpenDataFile(os.environ["PIERCE_MODEL"])
thickness = PierceThickness(Input=model)  # noqa: F821 (defined by LoadPlugin)
thickness.SampleAt = "Cells"
thickness.MinThickness = 3.0

view = GetActiveViewOrCreate("RenderView")
Hide(model, view)
display = Show(thickness, view)
ColorBy(display, ("CELLS", "Thickness"))
display.SetScalarBarVisibility(view, True)
lut = GetColorTransferFunction("Thickness")
lut.ApplyPreset("Jet", True)
lut.RescaleTransferFunction(2.0, 10.0)
view.CameraPosition = [26, -22, 20]
view.CameraFocalPoint = [5, 5, 1.5]
view.CameraViewUp = [0, 0, 1]
ResetCamera(view)
view.CameraParallelScale = 7
SetActiveSource(thickness)
Render(view)

with open(os.environ["PIERCE_MARKER"], "w") as f:
    f.write("ready\n")
