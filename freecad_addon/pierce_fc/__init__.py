"""Pierce for FreeCAD: wall-thickness maps, overlap checks and shotlines on Part solids.

The analysis logic (selection, tessellation, running Pierce, building result objects) lives in
this package and needs no GUI, so freecadcmd scripts and tests can call it directly; pierce_fc.gui
holds the commands and task panels.
"""

__version__ = "0.1.0"
