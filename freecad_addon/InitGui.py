# Pierce workbench: wall-thickness maps, overlap checks and shotlines on Part/PartDesign solids.
# FreeCAD runs this file at GUI start-up (without __file__); the commands live in pierce_fc.gui.


class PierceWorkbench(Workbench):  # noqa: F821  (Workbench is provided by FreeCAD)
    MenuText = "Pierce"
    ToolTip = "Wall thickness, overlaps and shotlines with Pierce's exact ray traversal"

    def __init__(self):
        import pierce_fc.gui.icons as icons
        self.__class__.Icon = icons.path("Pierce.svg")

    def Initialize(self):
        from pierce_fc.gui import commands
        commands.register()
        self.appendToolbar("Pierce", commands.NAMES)
        self.appendMenu("&Pierce", commands.NAMES)

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def GetClassName(self):
        return "Gui::PythonWorkbench"


Gui.addWorkbench(PierceWorkbench())  # noqa: F821  (Gui is provided by FreeCAD)
