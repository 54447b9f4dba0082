"""FreeCAD GUI test (under xvfb-run) of the overlap panel on a 36-solid assembly, as a STEP import
shows one: a compound with a long name whose solids are the tree objects Solid, Solid001, ...
Solid035. A 6 x 6 grid of 4 x 4 x 3 blocks 5 apart (1 mm gaps), except: Solid001 is moved to touch
Solid (contact), Solid008 sinks 0.5 into Solid007 (clash), Solid015 comes 0.3 from Solid014
(clearance 0.3 below the 0.5 asked for). The panel must name the solids by their tree Labels, the
compound once in its header, number rows from 1, and choosing the contact row must leave the
contact in sight: the pair opaque, the others see-through, the point marked and framed.

    QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a -s "-screen 0 1024x768x24 -noreset" freecad test_gui_overlaps.py
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402

OUT = os.environ.get("PIERCE_TEST_OUT", os.getcwd())
COMPOUND = "USB_C_Receptacle_16P_TopMnt_Horizontal_GCT_USB4105-xx-A"


def assembly(doc):
    import FreeCAD
    import Part
    solids = []
    for k in range(36):
        x, y = 5.0 * (k % 6), 5.0 * (k // 6)
        if k == 1:
            x = 4.0  # touches Solid along x = 4
        elif k == 8:
            x = 5.0 * (7 % 6) + 3.5  # sinks 0.5 into Solid007 (x 5..9)
        elif k == 15:
            x = 5.0 * (14 % 6) + 4.3  # 0.3 from Solid014 (x 10..14)
        o = doc.addObject("Part::Feature", "Solid" if k == 0 else "Solid%03d" % k)
        o.Shape = Part.makeBox(4, 4, 3, FreeCAD.Vector(x, y, 0))
        solids.append(o)
    comp = doc.addObject("Part::Compound", "Compound")
    comp.Label = COMPOUND
    comp.Links = solids
    doc.recompute()
    return comp, solids


def cyan_near(path, x, y, radius=8):
    """Whether the image at `path` has a highlight-cyan pixel within `radius` of (x, y)."""
    from PySide2 import QtGui
    img = QtGui.QImage(path)
    for yy in range(max(0, y - radius), min(img.height(), y + radius + 1)):
        for xx in range(max(0, x - radius), min(img.width(), x + radius + 1)):
            c = img.pixel(xx, yy)
            r, g, b = (c >> 16) & 255, (c >> 8) & 255, c & 255
            if r < 60 and g > 180 and b > 200:
                return True
    return False


def body(c):
    import FreeCAD
    import FreeCADGui as Gui
    from PySide2 import QtWidgets

    Gui.activateWorkbench("PierceWorkbench")
    doc = FreeCAD.newDocument("PierceGuiOverlaps")
    comp, parts = assembly(doc)
    Gui.SendMsgToActiveView("ViewFit")
    Gui.ActiveDocument.ActiveView.viewIsometric()

    from pierce_fc.gui.task_overlaps import OverlapPanel
    panel = OverlapPanel()
    Gui.Control.showDialog(panel)
    c.check(not panel.markers.isChecked(), "markers are off by default")
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(comp)
    panel.clearance.setValue(0.5)
    panel.on_run()
    run = panel.last_result
    c.check(run is not None and len(run.model.solids) == 36, "36 solids checked: %r" % panel.message.text())
    if run is None:
        return
    rows = [[panel.table.item(r, k).text() for k in range(panel.table.columnCount())]
            for r in range(panel.table.rowCount())]
    got = sorted((r[1], r[2]) for r in rows)
    c.check(got == [("clash", "Solid007 / Solid008"), ("clearance", "Solid014 / Solid015"),
                    ("contact", "Solid / Solid001")], "pairs named as the tree names them: %s" % rows)
    c.check([r[0] for r in rows] == [str(k + 1) for k in range(len(rows))], "rows numbered from 1")
    c.check(all(r[4].startswith("(") for r in rows), "each row has its point: %s" % [r[4] for r in rows])
    header = panel.header.text().replace("\u200b", "")
    c.check(header.count(COMPOUND) == 1 and "36 solids" in header, "the header names the compound once: %r" % header)
    for _ in range(3):
        QtWidgets.QApplication.processEvents()
    bad, width = fc_check.clipped_widgets(panel.form)
    c.check(not bad, "the panel with its results fits the %d px task view: %s" % (width, bad))
    c.check(all(COMPOUND not in r[2] for r in rows), "rows do not repeat the compound's name")
    summary = panel.summary.toPlainText()
    c.check(summary.count("\n") + 1 >= 3 + len(rows) and "1 clash, 1 contact, 1 clearance" in summary,
            "the full summary is in the panel (%d lines)" % (summary.count("\n") + 1))
    clear = [r for r in rows if r[1] == "clearance"]
    c.check(bool(clear) and abs(float(clear[0][3]) - 0.3) < 1e-9, "clearance gap 0.3: %s" % clear)

    # Choosing the contact row: the pair opaque, the rest see-through, the point marked and framed.
    contact = [k for k, r in enumerate(rows) if r[1] == "contact"]
    if contact:
        panel.table.selectRow(contact[0])
        for _ in range(3):
            QtWidgets.QApplication.processEvents()
        pair = run.pairs[contact[0]]
        involved = {"Solid", "Solid001"}
        c.check(all(doc.getObject(n).ViewObject.Visibility and doc.getObject(n).ViewObject.Transparency <= 20
                    for n in involved), "the pair's solids are shown nearly opaque")
        c.check(comp.ViewObject.Transparency >= 80, "the rest of the assembly is see-through (%d%%)"
                % comp.ViewObject.Transparency)
        picked = {(s.ObjectName, n) for s in Gui.Selection.getSelectionEx() for n in s.SubElementNames}
        c.check(bool(picked), "the contact's faces are selected: %s" % sorted(picked))
        view = Gui.ActiveDocument.ActiveView
        size = view.getSize()
        shot = os.path.join(OUT, "freecad-overlaps-contact-view.png")
        view.saveImage(shot, size[0], size[1], "Current")
        px = view.getPointOnScreen(FreeCAD.Vector(*pair.point))
        c.check(0 <= px[0] < size[0] and 0 <= px[1] < size[1], "the contact point is in the view: %s" % (tuple(px),))
        c.check(cyan_near(shot, int(px[0]), int(size[1] - 1 - px[1])) or cyan_near(shot, int(px[0]), int(px[1])),
                "the contact point is marked in the screenshot")
        c.check(fc_check.window_screenshot(os.path.join(OUT, "freecad-overlaps-contact.png")), "window screenshot")
    panel.reject()  # the panel's Close button
    c.check(comp.ViewObject.Transparency < 80 and not doc.getObject("Solid").ViewObject.Visibility,
            "closing the panel restores the view")


fc_check.run_in_gui("gui_overlaps", body)
