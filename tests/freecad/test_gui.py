"""FreeCAD GUI test (run under xvfb-run): activates the Pierce workbench, runs Thickness map from its
task panel on a solid, checks bad selections give a panel message, and saves a screenshot of the 3D
view (checked not blank) plus one of the whole window, into $PIERCE_TEST_OUT.

    QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a -s "-screen 0 1600x1000x24" freecad test_gui.py
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402

OUT = os.environ.get("PIERCE_TEST_OUT", os.getcwd())


def image_stats(path):
    """(share of pixels equal to the most common colour (the background), number of colours,
    share of strongly coloured pixels (false colours, not greys)), sampling every 4th pixel."""
    from PySide2 import QtGui
    img = QtGui.QImage(path)
    if img.isNull():
        return 1.0, 0, 0.0
    counts = {}
    vivid = 0
    step = 4
    for y in range(0, img.height(), step):
        for x in range(0, img.width(), step):
            c = img.pixel(x, y)
            counts[c] = counts.get(c, 0) + 1
            r, g, b = (c >> 16) & 255, (c >> 8) & 255, c & 255
            vivid += max(r, g, b) - min(r, g, b) > 80
    total = sum(counts.values())
    return max(counts.values()) / total, len(counts), vivid / total


def part(doc):
    """A plate with a boss and a through hole: walls from 2 to 12 mm (solids.bracket)."""
    import solids
    obj = solids.bracket(doc)
    doc.recompute()
    return obj


def body(c):
    import FreeCAD
    import FreeCADGui as Gui
    from PySide2 import QtCore, QtWidgets

    Gui.activateWorkbench("PierceWorkbench")
    c.check(Gui.activeWorkbench().MenuText == "Pierce", "Pierce workbench is active")
    cmds = Gui.listCommands()
    for name in ("Pierce_ThicknessMap", "Pierce_OverlapCheck", "Pierce_Shotline"):
        c.check(name in cmds, "command %s registered" % name)

    doc = FreeCAD.newDocument("PierceGui")
    obj = part(doc)
    Gui.SendMsgToActiveView("ViewFit")

    # The command opens its task panel.
    Gui.Selection.clearSelection()
    Gui.runCommand("Pierce_ThicknessMap")
    c.check(Gui.Control.activeDialog(), "Thickness map opens a task dialog")
    Gui.Control.closeDialog()

    from pierce_fc.gui.task_thickness import ThicknessPanel
    from pierce_fc.gui.task_overlaps import OverlapPanel
    from pierce_fc.gui.task_shotline import ShotlinePanel

    # Bad selections: a message in the panel, no exception, no objects.
    for cls in (ThicknessPanel, OverlapPanel):
        panel = cls()
        Gui.Control.showDialog(panel)
        Gui.Selection.clearSelection()
        panel.on_run()
        c.check("nothing is selected" in panel.message.text().lower(),
                "%s, empty selection: %r" % (cls.__name__, panel.message.text()))
        Gui.Control.closeDialog()
    sketchy = doc.addObject("Part::Feature", "JustAFace")
    sketchy.Shape = obj.Shape.Faces[0]
    panel = ThicknessPanel()
    Gui.Control.showDialog(panel)
    Gui.Selection.addSelection(sketchy)
    panel.on_run()
    c.check("no solid" in panel.message.text().lower(), "face only: %r" % panel.message.text())
    doc.removeObject(sketchy.Name)
    Gui.Control.closeDialog()

    # Thickness map from the panel, thin walls below 3 mm; a wider task view for the window picture.
    mw = Gui.getMainWindow()
    mw.resize(1500, 950)
    combo = [d for d in mw.findChildren(QtWidgets.QDockWidget) if d.objectName() in ("Combo View", "ComboView")]
    if combo:
        mw.resizeDocks(combo, [470], QtCore.Qt.Horizontal)
    panel = ThicknessPanel()
    Gui.Control.showDialog(panel)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(obj)
    panel.per.setCurrentIndex(0)  # faces: exact on flat walls
    panel.deflection.setValue(0.05)
    panel.threshold.setValue(3.0)
    panel.auto_range.setChecked(False)  # the plate's 60 mm length would dominate an automatic range
    panel.range_min.setValue(2.0)
    panel.range_max.setValue(12.0)
    panel.on_run()
    run = panel.last_result
    c.check(run is not None and run.group is not None, "thickness map created: %r" % panel.message.text())
    if run is None:
        return
    mesh_obj = run.solids[0].result_object
    c.check(mesh_obj.ViewObject.Coloring, "the result mesh shows its colours")
    c.check(not obj.ViewObject.Visibility, "the analysed solid is hidden")
    c.check(abs(run.solids[0].stats.summary.min - 2.0) < 0.05, "thinnest wall is the 2 mm rib (%.4g)"
            % run.solids[0].stats.summary.min)
    c.check(run.solids[0].thin_count > 0, "thin vertices below 3 mm are marked")
    c.check("minimum" in panel.message.text().lower(), "panel message: %r" % panel.message.text())
    c.check(panel.legend.range is not None, "legend shows the range %s" % (panel.legend.range,))

    shot = fc_check.fitted_view_shot(os.path.join(OUT, "freecad-thickness-view.png"), 1200, 800)
    c.check(os.path.isfile(shot), "3D view screenshot saved: " + shot)
    bg, colours, vivid = image_stats(shot)
    c.check(bg < 0.9 and colours > 20, "screenshot not blank: %.0f%% background, %d colours" % (100 * bg, colours))
    c.check(vivid > 0.05, "the false colours are visible: %.0f%% coloured pixels" % (100 * vivid))

    window = os.path.join(OUT, "freecad-thickness-panel.png")
    QtWidgets.QApplication.processEvents()
    c.check(panel.form.grab().save(window), "task panel screenshot saved: " + window)
    Gui.Control.closeDialog()

    # Shotline and overlap panels run on the same part.
    panel = ShotlinePanel()
    Gui.Control.showDialog(panel)
    for w, x in zip(panel.origin, (30, 20, 30)):
        w.setValue(x)
    for w, x in zip(panel.direction, (1, 0, -1)):
        w.setValue(x)
    panel.markers.setChecked(False)
    obj.ViewObject.Visibility = True
    panel.on_run()
    c.check(panel.table.rowCount() >= 2, "shotline table rows: %d (%s)" % (panel.table.rowCount(), panel.message.text()))
    Gui.Control.closeDialog()

    # Overlap check: clicking the interpenetration row selects the faces bounding it.
    import Part
    a = doc.addObject("Part::Feature", "BoxA")
    a.Shape = Part.makeBox(10, 10, 10, FreeCAD.Vector(0, 100, 0))
    b = doc.addObject("Part::Feature", "BoxB")
    b.Shape = Part.makeBox(10, 6, 6, FreeCAD.Vector(7.5, 102, 2))  # no shared planes: only the overlap
    doc.recompute()
    panel = OverlapPanel()
    Gui.Control.showDialog(panel)
    panel.grid.setValue(16)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(a)
    Gui.Selection.addSelection(b)
    panel.on_run()
    rows = [panel.table.item(r, 1).text() for r in range(panel.table.rowCount())]
    c.check(rows == ["clash"], "overlap table: %s (%s)" % (rows, panel.message.text()))
    if rows:
        c.check(panel.table.item(0, 3).text() == "2.5", "depth column: %r" % panel.table.item(0, 3).text())
        c.check(panel.table.item(0, 2).text() == "BoxA / BoxB", "solids column: %r" % panel.table.item(0, 2).text())
        Gui.Selection.clearSelection()
        panel.table.selectRow(0)
        QtWidgets.QApplication.processEvents()
        picked = {(s.ObjectName, n) for s in Gui.Selection.getSelectionEx() for n in s.SubElementNames}
        c.check(("BoxA", "Face2") in picked and ("BoxB", "Face1") in picked,
                "clicking the row selects the bounding faces: %s" % sorted(picked))
    Gui.Control.closeDialog()


fc_check.run_in_gui("gui", body)
