"""GUI test (run under `xvfb-run -a pvbatch`): the ParaView GUI's first screen with Pierce. The real
GUI plays a user's clicks (plugins/paraview/screenshot/first_screen.py: open samples/blob.stl,
Apply, Filters ▸ Pierce ▸ Pierce Thickness, Apply with the default properties) and saves its
state; this script loads that state and checks what the plugin's GUI behaviour did: the Pierce
Thickness display in the render view is coloured by Thickness, its colour map spans the output's
ThicknessColorRange and is no longer rescaled on Apply, and the view, rendered from the state with
the colour bar hidden, shows more than one colour band.

    xvfb-run -a pvbatch test_gui_first_screen.py --plugin PierceParaView.so --model blob.stl
        --paraview paraview --python /usr/bin/python3 --work DIR
"""
import os
import subprocess
import sys

from paraview.simple import (GetDisplayProperties, GetViews, FindSource, LoadPlugin, LoadState,
                             SaveScreenshot)
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkRenderingCore import vtkDiscretizableColorTransferFunction

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import pvbatch_main  # noqa: E402
from pvbatch_main import check  # noqa: E402

FIRST_SCREEN = os.path.join(HERE, "..", "..", "plugins", "paraview", "screenshot", "first_screen.py")
BACKGROUND = (255, 255, 255)


BANDS = 8


def chromaticity(rgb):
    total = float(sum(rgb)) or 1.0
    return [c / total for c in rgb]


def band_shares(path, lut, colour_range):
    """(share of the pixels that are not background, [share of those in each of BANDS equal bands
    of the colour map]). A pixel belongs to the band whose middle colour is nearest in chromaticity,
    which shading (a factor on all three channels) leaves alone."""
    colours = vtkDiscretizableColorTransferFunction()
    colours.DeepCopy(lut.GetClientSideObject())
    lo, hi = colour_range
    middles = []
    for k in range(BANDS):
        rgb = [0.0, 0.0, 0.0]
        colours.GetColor(lo + (k + 0.5) * (hi - lo) / BANDS, rgb)
        middles.append(chromaticity(rgb))
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    scalars = reader.GetOutput().GetPointData().GetScalars()
    n = scalars.GetNumberOfTuples()
    counts = [0] * BANDS
    for i in range(n):
        rgb = tuple(int(v) for v in scalars.GetTuple(i)[:3])
        if rgb == BACKGROUND:
            continue
        c = chromaticity(rgb)
        distances = [sum((a - b) ** 2 for a, b in zip(c, m)) for m in middles]
        counts[distances.index(min(distances))] += 1
    foreground = sum(counts)
    return foreground / float(n), [k / max(foreground, 1.0) for k in counts]


def main():
    args = pvbatch_main.required_options("plugin", "model", "paraview", "python", "work")
    state = os.path.join(args.work, "first_screen.pvsm")
    clicks = subprocess.run([args.python, FIRST_SCREEN, "--paraview", args.paraview,
                             "--plugin-dir", os.path.dirname(args.plugin), "--model", args.model,
                             "--state", state])
    if clicks.returncode != 0:
        print("FAIL: the GUI did not play the clicks")
        return 1

    LoadPlugin(args.plugin, ns=globals())
    LoadState(state)
    thickness = FindSource("PierceThickness1")
    if thickness is None:
        print("FAIL: no PierceThickness1 in the GUI's state")
        return 1
    check(thickness.SampleAt == "Points" and thickness.MinThickness == 0 and thickness.MaxThickness == 0,
          "Pierce Thickness applied with its default properties")
    views = [v for v in GetViews() if v.GetXMLName() == "RenderView"]
    check(len(views) == 1, "one render view (%d)" % len(views))
    if not views:
        return pvbatch_main.status()
    view = views[0]
    display = GetDisplayProperties(thickness, view)
    check(display.Visibility == 1, "the Thickness output is shown")
    check(list(display.ColorArrayName) == ["POINTS", "Thickness"],
          "coloured by point array Thickness (%s)" % list(display.ColorArrayName))

    thickness.UpdatePipeline()  # a loaded state has not run the pipeline yet
    info = thickness.GetDataInformation().GetFieldDataInformation().GetArrayInformation("ThicknessColorRange")
    lut = display.LookupTable
    if info is None or lut is None:
        print("FAIL: no ThicknessColorRange (%s) or no colour map (%s)" % (info, lut))
        return 1
    expected = (info.GetComponentRange(0)[0], info.GetComponentRange(1)[1])
    points = lut.RGBPoints
    data_range = thickness.GetDataInformation().GetPointDataInformation().GetArrayInformation(
        "Thickness").GetComponentRange(0)
    print("Thickness %g to %g; ThicknessColorRange %g to %g; colour map %g to %g"
          % (data_range[0], data_range[1], expected[0], expected[1], points[0], points[-4]))
    check(abs(points[0] - expected[0]) < 1e-9 and abs(points[-4] - expected[1]) < 1e-9,
          "the colour map spans ThicknessColorRange")
    check(expected[0] > data_range[0] or expected[1] < data_range[1],
          "ThicknessColorRange is narrower than the data range (so the check above can tell them apart)")
    check(lut.AutomaticRescaleRangeMode == "Never",
          "the colour map is not rescaled on Apply (%s)" % lut.AutomaticRescaleRangeMode)

    display.SetScalarBarVisibility(view, False)
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [c / 255.0 for c in BACKGROUND]
    png = os.path.join(args.work, "first_screen_view.png")
    if os.path.exists(png):
        os.remove(png)
    SaveScreenshot(png, view, ImageResolution=[400, 400])
    share, bands = band_shares(png, lut, expected)
    print("foreground %.1f%% of the view; per band of the colour map: %s"
          % (100 * share, " ".join("%.1f%%" % (100 * b) for b in bands)))
    check(share > 0.05, "the model is in the view")
    shown = sum(b > 0.02 for b in bands)
    check(shown >= 2, "more than one colour band: %d of %d bands on 2%% of the model or more" % (shown, BANDS))
    return pvbatch_main.status()


if __name__ == "__main__":
    pvbatch_main.run(main)
