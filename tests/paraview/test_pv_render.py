"""Rendering test (run under `xvfb-run -a pvbatch`): the STEP assembly's thickness, colour-mapped,
rendered to a PNG; the image must show the model in more than one colour of the map, not a blank
background.

    xvfb-run -a pvbatch test_pv_render.py --plugin PierceParaView.so --step assembly.step --png out.png
"""
import argparse
import os
import sys

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, LoadPlugin, OpenDataFile,
                             ResetCamera, SaveScreenshot, Show)
from vtkmodules.vtkIOImage import vtkPNGReader

BACKGROUND = (1.0, 1.0, 1.0)


def pixel_stats(path):
    """(share of pixels that differ from the background, distinct colours among them)."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    bg = tuple(int(round(255 * c)) for c in BACKGROUND)
    foreground, colours = 0, set()
    n = scalars.GetNumberOfTuples()
    for i in range(n):
        rgb = tuple(int(v) for v in scalars.GetTuple(i)[:3])
        if rgb != bg:
            foreground += 1
            colours.add(rgb)
    return foreground / float(n), len(colours)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--plugin", required=True)
    p.add_argument("--step", required=True)
    p.add_argument("--png", required=True)
    args = p.parse_args()

    LoadPlugin(args.plugin, ns=globals())
    reader = OpenDataFile(args.step)
    thickness = PierceThickness(Input=reader, SampleAt="Cells")  # noqa: F821

    view = CreateView("RenderView")
    view.ViewSize = [400, 300]
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = list(BACKGROUND)
    display = Show(thickness, view)
    ColorBy(display, ("CELLS", "Thickness"))
    lut = GetColorTransferFunction("Thickness")
    lut.ApplyPreset("Jet", True)
    lut.RescaleTransferFunction(2.0, 10.0)
    view.CameraPosition = [25, -20, 18]
    view.CameraFocalPoint = [5, 5, 1]
    view.CameraViewUp = [0, 0, 1]
    ResetCamera(view)
    if os.path.exists(args.png):
        os.remove(args.png)  # the test's own output from a previous run
    SaveScreenshot(args.png, view, ImageResolution=[400, 300])

    if not os.path.isfile(args.png):
        print("FAIL: no image written")
        return 1
    share, colours = pixel_stats(args.png)
    print("foreground %.1f%%, %d distinct colours" % (100 * share, colours))
    if share < 0.05:
        print("FAIL: the image is (nearly) blank")
        return 1
    if colours < 3:
        print("FAIL: the model is not colour-mapped")
        return 1
    print("render ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
