"""FreeCAD GUI test (under xvfb-run) of the thickness panel's caliper: with the button on, a point
selected on a face (as a click in the 3D view selects it) is read on the exact B-rep and written to
the panel's summary; with it off, selections are not read.

    QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a -s "-screen 0 1024x768x24 -noreset" freecad test_gui_caliper.py
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402


def body(c):
    import FreeCAD
    import FreeCADGui as Gui
    import Part
    from PySide2 import QtWidgets

    Gui.activateWorkbench("PierceWorkbench")
    doc = FreeCAD.newDocument("PierceCaliperGui")
    obj = doc.addObject("Part::Feature", "Slab")
    obj.Shape = Part.makeBox(40, 30, 4)
    doc.recompute()
    from pierce_fc.gui.task_thickness import ThicknessPanel
    panel = ThicknessPanel()
    Gui.Control.showDialog(panel)
    QtWidgets.QApplication.processEvents()
    top = [i for i, f in enumerate(obj.Shape.Faces) if abs(f.normalAt(0, 0).z - 1) < 1e-9][0]
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, obj.Name, "Face%d" % (top + 1), 12.0, 9.0, 4.0)
    QtWidgets.QApplication.processEvents()
    c.check("wall" not in panel.summary.toPlainText(), "caliper off: a selection is not read")
    panel.caliper_button.setChecked(True)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, obj.Name, "Face%d" % (top + 1), 12.0, 9.0, 4.0)
    QtWidgets.QApplication.processEvents()
    text = panel.summary.toPlainText()
    c.check("Pierce caliper: wall 4 mm on 'Slab' Face%d" % (top + 1) in text, "caliper reads the 4 mm slab: %r" % text)
    panel.caliper_button.setChecked(False)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, obj.Name, "Face%d" % (top + 1), 20.0, 10.0, 4.0)
    QtWidgets.QApplication.processEvents()
    c.check(panel.summary.toPlainText().count("Pierce caliper") == 1, "caliper off again: no further reading")
    Gui.Control.closeDialog()


fc_check.run_in_gui("gui_caliper", body)
