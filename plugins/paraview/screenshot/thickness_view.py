"""The thickness view that the docs' screenshot (gui_thickness.py) shows and the rendering test
(tests/paraview/test_pv_render.py) checks, written once."""
from paraview.simple import ColorBy, GetColorTransferFunction, ResetCamera, Show


def show_thickness(thickness, view, position, focal_point):
    """Shows Pierce Thickness's output in `view` coloured by its cell array Thickness, Jet from 2 to
    10 (the sample assembly's 2 mm parts blue, the plate's 10 mm sides red), seen from `position`
    towards `focal_point` with z up; returns the display."""
    display = Show(thickness, view)
    ColorBy(display, ("CELLS", "Thickness"))
    lut = GetColorTransferFunction("Thickness")
    lut.ApplyPreset("Jet", True)
    lut.RescaleTransferFunction(2.0, 10.0)
    view.CameraPosition = position
    view.CameraFocalPoint = focal_point
    view.CameraViewUp = [0, 0, 1]
    ResetCamera(view)
    return display
