"""The workbench's commands: each opens its task panel."""
import FreeCAD
import FreeCADGui as Gui

from . import icons

NAMES = ["Pierce_ThicknessMap", "Pierce_OverlapCheck", "Pierce_Shotline"]


class _OpenPanel:
    def __init__(self, menu, tip, icon, factory):
        self.menu, self.tip, self.icon, self.factory = menu, tip, icon, factory

    def GetResources(self):
        return {"Pixmap": icons.path(self.icon), "MenuText": self.menu, "ToolTip": self.tip}

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        if Gui.Control.activeDialog():
            Gui.Control.closeDialog()
        Gui.Control.showDialog(self.factory())


def _thickness():
    from .task_thickness import ThicknessPanel
    return ThicknessPanel()


def _overlaps():
    from .task_overlaps import OverlapPanel
    return OverlapPanel()


def _shotline():
    from .task_shotline import ShotlinePanel
    return ShotlinePanel()


def register():
    Gui.addCommand("Pierce_ThicknessMap", _OpenPanel(
        "Thickness map", "Wall thickness of the selected solids as a false-colour mesh, with thin regions "
        "highlighted", "PierceThickness.svg", _thickness))
    Gui.addCommand("Pierce_OverlapCheck", _OpenPanel(
        "Overlap check", "Interpenetrating solids with their depth, coplanar contacts and coincident faces "
        "of the selected solids or assembly", "PierceOverlap.svg", _overlaps))
    Gui.addCommand("Pierce_Shotline", _OpenPanel(
        "Shotline", "Solids, overlaps and gaps along a ray or a grid of rays through a face, with entry/exit "
        "points and depths", "PierceShotline.svg", _shotline))
