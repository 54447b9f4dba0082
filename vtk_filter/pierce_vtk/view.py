"""pierce_vtk.show_thickness: in pvpython and pvbatch, the view the ParaView GUI gives Pierce
Thickness on its first Apply (the plugin's GUI behaviour does not run there).

    from pierce_vtk import show_thickness
    display = show_thickness(thickness)   # a Pierce Thickness pipeline object
"""


def show_thickness(thickness, view=None):
    """Shows `thickness` (a Pierce Thickness pipeline object) in `view` (default: the active
    view) coloured by its Thickness array over the range in its field data ThicknessColorRange,
    values beyond it in the end colours, with the colour bar; the colour map's automatic rescaling
    is set to Never so later updates keep that range. Returns the display."""
    from paraview import simple
    view = view or simple.GetActiveViewOrCreate("RenderView")
    display = simple.Show(thickness, view)
    info = thickness.GetDataInformation()
    association = "POINTS" if info.GetPointDataInformation().GetArrayInformation("Thickness") else "CELLS"
    simple.ColorBy(display, (association, "Thickness"))
    lut = simple.GetColorTransferFunction("Thickness")
    colour_range = info.GetFieldDataInformation().GetArrayInformation("ThicknessColorRange")
    if colour_range is not None:
        lo, hi = colour_range.GetComponentRange(0)[0], colour_range.GetComponentRange(1)[1]
        lut.RescaleTransferFunction(lo, hi)
        simple.GetOpacityTransferFunction("Thickness").RescaleTransferFunction(lo, hi)
        lut.AutomaticRescaleRangeMode = "Never"
    display.SetScalarBarVisibility(view, True)
    return display
