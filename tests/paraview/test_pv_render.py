"""Rendering test (run under `xvfb-run -a pvbatch`): the STEP assembly's thickness shown by
pierce_vtk.show_thickness, rendered to a PNG; the colour map must span ThicknessColorRange and the
image must show the model, not a blank background, with both ends of the colour map (2 mm walls
blue, the plate's 10 mm sides red).

    xvfb-run -a pvbatch test_pv_render.py --plugin PierceParaView.so --step assembly.step --png out.png
"""
import os
import sys

from paraview.simple import CreateView, GetColorTransferFunction, LoadPlugin, OpenDataFile, ResetCamera, SaveScreenshot
from vtkmodules.vtkIOImage import vtkPNGReader

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import pvbatch_main  # noqa: E402
from pierce_vtk import show_thickness  # noqa: E402

BACKGROUND = (1.0, 1.0, 1.0)


def pixel_stats(path):
    """(share of pixels that differ from the background, share of those that are red, share blue)."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    bg = tuple(int(round(255 * c)) for c in BACKGROUND)
    foreground = red = blue = 0
    n = scalars.GetNumberOfTuples()
    for i in range(n):
        r, g, b = (int(v) for v in scalars.GetTuple(i)[:3])
        if (r, g, b) != bg:
            foreground += 1
            red += r > 60 and r > 2 * max(g, b)
            blue += b > 60 and b > 2 * max(r, g)
    return foreground / float(n), red / max(foreground, 1.0), blue / max(foreground, 1.0)


def main():
    args = pvbatch_main.required_options("plugin", "step", "png")

    LoadPlugin(args.plugin, ns=globals())
    reader = OpenDataFile(args.step)
    thickness = PierceThickness(Input=reader, SampleAt="Cells")  # noqa: F821

    view = CreateView("RenderView")
    view.ViewSize = [400, 300]
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = list(BACKGROUND)
    show_thickness(thickness, view)
    view.CameraPosition = [25, -20, 18]
    view.CameraFocalPoint = [5, 5, 1]
    view.CameraViewUp = [0, 0, 1]
    ResetCamera(view)
    colour_range = thickness.GetDataInformation().GetFieldDataInformation().GetArrayInformation("ThicknessColorRange")
    expected = (colour_range.GetComponentRange(0)[0], colour_range.GetComponentRange(1)[1])
    lut = GetColorTransferFunction("Thickness")
    points = lut.RGBPoints
    print("ThicknessColorRange %g to %g; colour map %g to %g (%s)"
          % (expected[0], expected[1], points[0], points[-4], lut.AutomaticRescaleRangeMode))
    if abs(points[0] - expected[0]) > 1e-9 or abs(points[-4] - expected[1]) > 1e-9:
        print("FAIL: the colour map does not span ThicknessColorRange")
        return 1
    if os.path.exists(args.png):
        os.remove(args.png)  # the test's own output from a previous run
    SaveScreenshot(args.png, view, ImageResolution=[400, 300])

    if not os.path.isfile(args.png):
        print("FAIL: no image written")
        return 1
    share, red, blue = pixel_stats(args.png)
    print("foreground %.1f%% of the image: %.1f%% red, %.1f%% blue" % (100 * share, 100 * red, 100 * blue))
    if share < 0.05:
        print("FAIL: the image is (nearly) blank")
        return 1
    # ParaView's default map, blue (the plate's top, the 2 mm parts) to red (the plate's sides).
    if red < 0.05 or blue < 0.05:
        print("FAIL: the model is not colour-mapped by thickness")
        return 1
    print("render ok")
    return 0


if __name__ == "__main__":
    pvbatch_main.run(main)
