"""FreeCAD GUI of the Pierce workbench: commands and task panels (PySide2)."""
