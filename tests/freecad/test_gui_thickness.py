"""FreeCAD GUI test (under xvfb-run) of the thickness panel at FreeCAD's default window layout
(Combo View at its default width), on a heatsink-like sheet part:

- every Pierce task panel fits the Combo View: no widget reaches past the visible width and none
  is squeezed below its minimum size;
- the first map with default options shows the sheet in more than one colour band;
- with a thin threshold the region list lists the thin spot; "Zoom to thinnest" frames it, and
  its thin colour fills a good part of the view;
- re-running leaves one result, labelled with the part's Label;
- the caliper reads the wall where the map is clicked;
- with a thick threshold too, the selector above the list shows the thick regions; choosing one
  selects its faces and frames it; "Zoom to thinnest" goes back to the thin ones.

Screenshots (window and view) go to $PIERCE_TEST_OUT.

    QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a -s "-screen 0 1024x768x24 -noreset" freecad test_gui_thickness.py
"""
import colorsys
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fc_check  # noqa: E402

OUT = os.environ.get("PIERCE_TEST_OUT", os.getcwd())
DEFAULT_COMBO_WIDTH = 264  # FreeCAD 0.20's Combo View at its default layout


def hue_bands(path):
    """Shares of the strongly coloured pixels of an image in the thickness ramp's hue bands (red,
    orange, yellow, green, blue) and magenta (thin), sampling every 2nd pixel."""
    from PySide2 import QtGui
    img = QtGui.QImage(path)
    bands = {"red": 0, "orange": 0, "yellow": 0, "green": 0, "blue": 0, "magenta": 0, "cyan": 0}
    total = vivid = 0
    for y in range(0, img.height(), 2):
        for x in range(0, img.width(), 2):
            c = img.pixel(x, y)
            r, g, b = ((c >> 16) & 255) / 255.0, ((c >> 8) & 255) / 255.0, (c & 255) / 255.0
            total += 1
            h, s, v = colorsys.rgb_to_hsv(r, g, b)
            if s < 0.45 or v < 0.25:
                continue
            vivid += 1
            deg = h * 360
            name = ("red" if deg < 18 or deg >= 340 else "orange" if deg < 42 else "yellow" if deg < 70 else
                    "green" if deg < 160 else "cyan" if deg < 195 else "blue" if deg < 260 else "magenta")
            bands[name] += 1
    return {k: v / float(max(vivid, 1)) for k, v in bands.items()}, vivid / float(max(total, 1))


def body(c):
    import FreeCAD
    import FreeCADGui as Gui
    from PySide2 import QtWidgets

    import solids
    Gui.activateWorkbench("PierceWorkbench")
    mw = Gui.getMainWindow()
    QtWidgets.QApplication.processEvents()
    combo = [d for d in mw.findChildren(QtWidgets.QDockWidget) if d.objectName() in ("Combo View", "ComboView")]
    c.check(bool(combo), "the Combo View is there")
    if not combo:
        return
    c.check(combo[0].width() <= DEFAULT_COMBO_WIDTH + 40,
            "the Combo View has about its default width: %d px (default %d)" % (combo[0].width(), DEFAULT_COMBO_WIDTH))

    doc = FreeCAD.newDocument("PierceGuiThickness")
    part = solids.heatsink(doc)
    part.Label = "Fillet006"  # a Label ending in digits, as PartDesign features have
    doc.recompute()
    Gui.SendMsgToActiveView("ViewFit")
    Gui.ActiveDocument.ActiveView.viewIsometric()

    from pierce_fc.gui.task_overlaps import OverlapPanel
    from pierce_fc.gui.task_shotline import ShotlinePanel
    from pierce_fc.gui.task_thickness import ThicknessPanel

    # Every panel fits the default Combo View.
    for cls in (ThicknessPanel, OverlapPanel, ShotlinePanel):
        panel = cls()
        Gui.Control.showDialog(panel)
        for _ in range(3):
            QtWidgets.QApplication.processEvents()
        bad, width = fc_check.clipped_widgets(panel.form)
        c.check(not bad, "%s fits the %d px task view: %s" % (cls.__name__, width, bad))
        fc_check.window_screenshot(os.path.join(OUT, "freecad-panel-%s.png" % cls.__name__.replace("Panel", "").lower()))
        Gui.Control.closeDialog()

    # The first map with default options (one click).
    panel = ThicknessPanel()
    Gui.Control.showDialog(panel)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(part)
    panel.on_run()
    run = panel.last_result
    c.check(run is not None and run.group is not None, "default thickness map: %r" % panel.message.text())
    if run is None:
        return
    lo, hi = run.color_range
    st = run.solids[0].stats.summary
    c.check(st.min < 0.1 and lo > st.min, "the default legend starts above the knife edge's slivers: %.4g to %.4g "
            "(samples %.4g to %.4g)" % (lo, hi, st.min, st.max))
    shot = fc_check.fitted_view_shot(os.path.join(OUT, "freecad-thickness-default-view.png"), 1000, 700)
    view = Gui.ActiveDocument.ActiveView
    bands, vivid = hue_bands(shot)
    wide = sorted(k for k, v in bands.items() if v > 0.05 and k not in ("magenta", "cyan"))
    c.check(len(wide) >= 2, "the default map shows more than one colour band: %s (%s)" % (
        wide, ", ".join("%s %.0f%%" % (k, 100 * v) for k, v in sorted(bands.items()))))
    for _ in range(3):
        QtWidgets.QApplication.processEvents()
    c.check(fc_check.window_screenshot(os.path.join(OUT, "freecad-thickness-default.png")), "window screenshot saved")
    bad, width = fc_check.clipped_widgets(panel.form)
    c.check(not bad, "the panel with its results fits the %d px task view: %s" % (width, bad))

    # Thin below 0.15: the 0.1 mm pocket floor is a region; re-running replaced the first map.
    panel.threshold.setValue(0.15)
    panel.on_run()
    run = panel.last_result
    groups = [o for o in doc.Objects if getattr(o, "PierceAnalysis", None) == "thickness"]
    c.check(len(groups) == 1, "re-running leaves one result: %s" % [g.Label for g in groups])
    mesh_obj = run.solids[0].result_object
    c.check(mesh_obj.Label == "Thickness Fillet006", "the map is labelled with the source's Label: %r" % mesh_obj.Label)
    c.check(panel.regions.count() == len(run.thin_regions) >= 1,
            "the region list shows the thin regions: %d rows, %d regions" % (panel.regions.count(),
                                                                            len(run.thin_regions)))
    floor = [k for k, g in enumerate(run.thin_regions) if abs(g.thickness - 0.1) < 1e-6]
    c.check(bool(floor), "the 0.1 mm pocket floor is a thin region: %s" % [
        "%.4g at %s" % (g.thickness, g.point) for g in run.thin_regions])
    c.check(panel.regions.item(0).text().startswith("1. Fillet006: min"), "rows are numbered from 1 and name the "
            "source by Label: %r" % panel.regions.item(0).text())

    # Zoom to thinnest: the thinnest region fills the view and its thin colour is visible.
    panel.zoom_button.click()
    for _ in range(3):
        QtWidgets.QApplication.processEvents()
    g = run.thin_regions[0]
    c.check(panel.regions.currentRow() == 0 and "Region 1" in panel.message.text(),
            "zoom to thinnest chooses region 1: %r" % panel.message.text())
    size = view.getSize()
    px = view.getPointOnScreen(FreeCAD.Vector(*g.point))
    c.check(0 <= px[0] < size[0] and 0 <= px[1] < size[1], "the region's point is in the view: %s of %s" % (
        tuple(px), tuple(size)))
    # Framed: the region's size (its box's half diagonal) spans a good part of the view.
    centre, radius, _ = run.region_view(0)
    right = view.getCameraNode().orientation.getValue().multVec(__import__("pivy").coin.SbVec3f(1, 0, 0))
    ends = [view.getPointOnScreen(FreeCAD.Vector(*[c0 + sgn * radius * r for c0, r in zip(centre, right)]))
            for sgn in (-1, 1)]
    extent = abs(ends[1][0] - ends[0][0])
    c.check(0.2 * min(size) < extent <= 1.0 * min(size), "the region (%.3g mm across) spans %d px of the %d px view" % (
        2 * radius, extent, min(size)))
    # Visible, not hidden behind other walls: picking the view at the region's point hits the map there.
    panel._highlight.clear()  # the highlight is drawn over everything: judge the map itself
    QtWidgets.QApplication.processEvents()
    # (Picked a little inside a triangle at the region's point: a pick exactly on a corner can miss.)
    import numpy as np
    m = run.solids[0].meshed
    k = int(np.argmin(np.linalg.norm(m.vertices - np.asarray(g.point), axis=1)))
    tri = m.triangles[np.nonzero((m.triangles == k).any(axis=1))[0][0]]
    target = 0.9 * m.vertices[k] + 0.05 * m.vertices[tri[tri != k][0]] + 0.05 * m.vertices[tri[tri != k][1]]
    tp = view.getPointOnScreen(FreeCAD.Vector(*target))
    info = view.getObjectInfo((int(tp[0]), int(tp[1])))
    hit = bool(info) and info.get("Object") == mesh_obj.Name and (
        FreeCAD.Vector(info["x"], info["y"], info["z"]) - FreeCAD.Vector(*g.point)).Length <= 2 * radius
    c.check(hit, "the thinnest region is in sight: the view picks %s, within %.3g mm of its point %s" % (
        info, 2 * radius, tuple(g.point)))

    # Choosing the pocket floor in the list frames it: its thin colour fills a good part of the view.
    if floor:
        panel.regions.setCurrentRow(floor[0])
        QtWidgets.QApplication.processEvents()
        c.check(panel.message.text().startswith("Region %d:" % (floor[0] + 1)), "row %d chosen: %r" % (
            floor[0] + 1, panel.message.text()))
        panel._highlight.clear()
        shot = os.path.join(OUT, "freecad-thickness-region.png")
        view.saveImage(shot, 1000, 700, "White")
        bands, vivid = hue_bands(shot)
        c.check(bands["magenta"] * vivid > 0.05, "the pocket floor's magenta covers %.0f%% of the view" % (
            100 * bands["magenta"] * vivid))
        panel.show_region(floor[0])  # highlighted again, for the window screenshot
        c.check(fc_check.window_screenshot(os.path.join(OUT, "freecad-thickness-regions.png")),
                "window screenshot saved")
    panel.zoom_button.click()
    c.check(fc_check.window_screenshot(os.path.join(OUT, "freecad-thickness-thinnest.png")), "window screenshot saved")

    # The caliper on the map: a click on the map over a fin (0.8 mm) reads the fin on the solid.
    view.viewIsometric()
    view.fitAll()
    panel.caliper_button.setChecked(True)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, mesh_obj.Name, "Facet0", 3.0, 15.0, 6.0)
    QtWidgets.QApplication.processEvents()
    text = panel.summary.toPlainText()
    c.check("Pierce caliper: wall 0.8 mm on 'Fillet006'" in text, "the caliper reads the fin through the map: %r"
            % text.splitlines()[-1:])
    panel.caliper_button.setChecked(False)

    # Thick above 1.2 mm as well: the 1.5 mm base; the selector lists the thick regions.
    c.check(not panel.region_kind.isEnabled(), "without a thick threshold the region selector is off")
    panel.thick_above.setValue(1.2)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(part)
    panel.on_run()
    run = panel.last_result
    c.check(run.options.max_thickness == 1.2 and bool(run.thick_regions),
            "thick above 1.2 mm finds thick regions: %d (%r)" % (len(run.thick_regions or []), panel.message.text()))
    c.check(panel.region_kind.isEnabled() and not panel.showing_thick() and
            panel.regions.count() == len(run.thin_regions), "the list still shows the %d thin region(s) first: "
            "%d rows" % (len(run.thin_regions), panel.regions.count()))
    panel.region_kind.setCurrentIndex(1)
    QtWidgets.QApplication.processEvents()
    c.check(panel.regions.count() == len(run.thick_regions), "Thick regions: the list shows the %d thick "
            "region(s): %d rows" % (len(run.thick_regions), panel.regions.count()))
    c.check(panel.regions.count() > 0 and panel.regions.item(0).text().startswith("1. Fillet006: max"),
            "thick rows are numbered from 1 with their maximum: %r" % (
                panel.regions.item(0).text() if panel.regions.count() else None))
    c.check("thick region" in panel.regions_label.text(), "the label says thick: %r" % panel.regions_label.text())
    bad, width = fc_check.clipped_widgets(panel.form)
    c.check(not bad, "the panel with the thick regions fits the %d px task view: %s" % (width, bad))
    if run.thick_regions:
        panel.regions.setCurrentRow(0)
        for _ in range(3):
            QtWidgets.QApplication.processEvents()
        g = run.thick_regions[0]
        k = run.region_id(True, 0)
        c.check(panel.message.text().replace("\u200b", "").startswith(  # the message's wrap points dropped
            "Thick region 1: 'Fillet006', max %.4g mm" % g.thickness),
                "choosing thick region 1 says so: %r" % panel.message.text())
        obj, faces = run.region_faces(k)
        selected = sorted(n for sel in Gui.Selection.getSelectionEx() for n in sel.SubElementNames)
        c.check(bool(faces) and selected == sorted(faces), "its faces are selected: %s (region: %s)" % (
            selected, faces))
        view = Gui.ActiveDocument.ActiveView
        size = view.getSize()
        px = view.getPointOnScreen(FreeCAD.Vector(*g.point))
        c.check(0 <= px[0] < size[0] and 0 <= px[1] < size[1], "the thick region's point is in the view: %s of %s"
                % (tuple(px), tuple(size)))
        centre, radius, _ = run.region_view(k)
        right = view.getCameraNode().orientation.getValue().multVec(__import__("pivy").coin.SbVec3f(1, 0, 0))
        ends = [view.getPointOnScreen(FreeCAD.Vector(*[c0 + sgn * radius * r for c0, r in zip(centre, right)]))
                for sgn in (-1, 1)]
        extent = abs(ends[1][0] - ends[0][0])
        c.check(0.2 * min(size) < extent <= 1.0 * min(size), "the thick region (%.3g mm across) spans %d px of "
                "the %d px view" % (2 * radius, extent, min(size)))
        c.check(fc_check.window_screenshot(os.path.join(OUT, "freecad-thickness-thick.png")), "window screenshot saved")
    panel.zoom_button.click()
    QtWidgets.QApplication.processEvents()
    c.check(not panel.showing_thick() and panel.regions.currentRow() == 0 and "Region 1" in panel.message.text(),
            "zoom to thinnest goes back to the thin regions: %r" % panel.message.text())
    Gui.Control.closeDialog()


fc_check.run_in_gui("gui_thickness", body)
