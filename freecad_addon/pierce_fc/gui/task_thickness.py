"""Task panel: thickness map of the selected solids."""
import math

import FreeCAD
import numpy as np

from .. import thickness_map
from ..locate import PierceUnavailable
from ..thickness_map import ThicknessOptions
from .export_report import add_export_button
from .legend import Legend
from .panel_base import PanelBase, check_box, double_spin
from .qt import QtWidgets
from .view import Highlight, frame


class ThicknessPanel(PanelBase):
    TITLE = "Pierce thickness map"
    RUN_TEXT = "Compute thickness"

    def build_options(self, layout):
        f = self.options_form(layout, "Options")
        self.method = QtWidgets.QComboBox()
        try:
            self.method.addItems(list(thickness_map.method_names()))
        except PierceUnavailable:  # the panel still opens; Run says why nothing can be computed
            self.method.setEnabled(False)
        self.method.setToolTip("ray: along the inward normal to where the ray leaves the solid; cone: shape "
                               "diameter function over 30 rays; sphere: largest inscribed ball")
        self.per = QtWidgets.QComboBox()
        self.per.addItems(["faces", "vertices"])
        try:  # Pierce's default, as in the CLI and Python
            defaults = thickness_map.thickness_defaults()
            self.method.setCurrentText(defaults["method"])
            self.per.setCurrentIndex(0 if defaults["per"] == "face" else 1)
        except PierceUnavailable:
            pass
        self.per.setToolTip("faces: one value per triangle; vertices: smooth colours (on the B-rep a vertex on "
                            "an edge shows the smaller of its faces' walls; on FreeCAD's mesh it uses an "
                            "averaged normal)")
        self.threshold = double_spin(0.0, 0.0, 1e6, special="off", step=0.1)
        self.threshold.setToolTip("Samples strictly thinner than this are coloured magenta and grouped into "
                                  "thin regions, listed below thinnest first")
        self.thick_above = double_spin(0.0, 0.0, 1e6, special="off", step=0.1)
        self.thick_above.setToolTip("Samples strictly thicker than this are grouped into thick regions (sink "
                                    "marks in moulding), listed below thickest first")
        self.auto_range = check_box("Automatic legend", True,
                                    tooltip="With a thin threshold T: 0 to 4 x T; otherwise the 2nd to 98th "
                                            "percentile of the samples (pierce.default_color_range, as the CLI "
                                            "and ParaView). Walls beyond an end take its colour")
        self.range_min = double_spin(0.0, -1e9, 1e9)
        self.range_max = double_spin(10.0, -1e9, 1e9)
        # The range fields show only while the automatic legend is off.
        self.range_box = QtWidgets.QWidget()
        rf = QtWidgets.QFormLayout(self.range_box)
        rf.setContentsMargins(0, 0, 0, 0)
        rf.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
        rf.addRow("Legend min", self.range_min)
        rf.addRow("Legend max", self.range_max)
        self.range_box.setVisible(False)
        self.auto_range.toggled.connect(lambda on: self.range_box.setVisible(not on))
        self.hide_sources = check_box("Hide the analysed solids", True)
        self.keep_previous = check_box("Keep previous results", False,
                                       tooltip="Otherwise a new map replaces the previous thickness map of the "
                                               "same solids")
        f.addRow("Method", self.method)
        f.addRow("Samples", self.per)
        f.addRow("Thin below", self.threshold)
        f.addRow("Thick above", self.thick_above)
        f.addRow(self.auto_range)
        f.addRow(self.range_box)
        f.addRow(self.hide_sources)
        f.addRow(self.keep_previous)

        # Meshing: the same defaults as the CLI and Python (pierce.tessellation_defaults()).
        m = self.collapsible_form(layout, "Mesh options")
        defaults = _tessellation_defaults()
        self.deflection = double_spin(defaults["linear_deflection"], 0.0, 1e6, special="auto", step=0.01)
        self.deflection.setToolTip("Largest distance between the surface and its triangles; auto: 0.1% of the "
                                   "selection's diagonal (as the CLI's --deflection 0)")
        self.angular = double_spin(defaults["angular_deflection"], 1.0, 90.0, decimals=1, suffix=" deg")
        try:
            has_cad = thickness_map.has_cad()
        except PierceUnavailable:
            has_cad = False
        self.on_brep = check_box("On the exact B-rep", has_cad,
                                 tooltip="Samples start on the exact faces and exits are refined on them; the "
                                         "tessellation is checked against the B-rep (no false thin spots from "
                                         "the mesh). Off: FreeCAD's mesh, measured as a mesh")
        self.split = check_box("Split long triangle edges", defaults["max_edge"] > 0,
                               tooltip="More samples on large flat faces (whose CAD triangles are few and "
                                       "big); on the B-rep the split triangles stay on their faces. Off by "
                                       "default, as in the CLI (--max-edge), so both give the same samples")
        self.max_edge = double_spin(defaults["max_edge"], 0.0, 1e6, special="auto (4%)", step=0.1)
        self.max_edge.setToolTip("Longest triangle edge; auto: 4% of the selection's diagonal")
        self.max_edge.setEnabled(self.split.isChecked())
        self.split.toggled.connect(self.max_edge.setEnabled)
        m.addRow("Deflection", self.deflection)
        m.addRow("Angular", self.angular)
        m.addRow(self.on_brep)
        m.addRow(self.split)
        m.addRow("Longest edge", self.max_edge)

    def build_results(self, layout):
        self.legend = Legend()
        layout.addWidget(self.legend)
        # Thin regions thinnest first, or thick ones thickest first (the selector): choosing one
        # selects its faces, frames it and highlights it.
        self.region_kind = QtWidgets.QComboBox()
        self.region_kind.addItems(["Thin regions", "Thick regions"])
        self.region_kind.setToolTip("Which regions the list shows: thin (below 'Thin below') or thick (above "
                                    "'Thick above')")
        self.region_kind.setEnabled(False)
        self.region_kind.currentIndexChanged.connect(lambda _: self.fill_regions())
        layout.addWidget(self.region_kind)
        self.regions_label = QtWidgets.QLabel("Thin regions")
        self.regions_label.setWordWrap(True)
        layout.addWidget(self.regions_label)
        self.regions = QtWidgets.QListWidget()
        self.regions.setWordWrap(True)
        self.regions.setMinimumHeight(90)
        self.regions.setToolTip("Choose a region to select its faces and zoom to it")
        self.regions.currentRowChanged.connect(self.on_region)
        layout.addWidget(self.regions)
        self.zoom_button = QtWidgets.QPushButton("Zoom to thinnest")
        self.zoom_button.setToolTip("Frames the thinnest wall (the first thin region, else the thinnest sample)")
        self.zoom_button.setEnabled(False)
        self.zoom_button.clicked.connect(self.zoom_to_thinnest)
        layout.addWidget(self.zoom_button)
        self._highlight = Highlight()
        # Caliper: while on, a point picked on a face reads the wall there on the exact B-rep.
        self.caliper_button = QtWidgets.QPushButton("Caliper: pick points")
        self.caliper_button.setCheckable(True)
        self.caliper_button.setToolTip("While on, click a point on a solid or on the thickness map in the 3D view "
                                       "to read the wall thickness there (exact B-rep); readings go to the "
                                       "summary below")
        self.caliper_button.toggled.connect(self.set_caliper)
        self._caliper_observer = None
        layout.addWidget(self.caliper_button)
        self.summary = QtWidgets.QPlainTextEdit()
        self.summary.setReadOnly(True)
        self.summary.setMinimumHeight(100)
        layout.addWidget(self.summary)
        self.export_button = add_export_button(self, layout, lambda: (self.solids_to_analyse(), dict(
            min_thickness=self.threshold.value(), max_thickness=self.thick_above.value() or None,
            method=self.method.currentText(),
            per="face" if self.per.currentIndex() == 0 else "vertex", deflection=self.deflection.value(),
            angular_deflection=self.angular.value())))

    def set_caliper(self, on):
        import FreeCADGui
        if on and self._caliper_observer is None:
            self._caliper_observer = _CaliperObserver(self)
            FreeCADGui.Selection.addObserver(self._caliper_observer)
        elif not on and self._caliper_observer is not None:
            FreeCADGui.Selection.removeObserver(self._caliper_observer)
            self._caliper_observer = None

    def caliper_pick(self, doc_name, obj_name, sub, pnt):
        """One caliper reading (the selection observer calls this)."""
        if getattr(self, "_selecting", False):  # the panel's own selection of a region's faces
            return None
        doc = FreeCAD.getDocument(doc_name)
        obj = doc.getObject(obj_name) if doc else None
        if obj is None:
            return None
        try:
            if hasattr(obj, "SourceObject") and hasattr(obj, "Thickness"):  # a click on a thickness map
                reading = thickness_map.caliper_on_map(obj, pnt)
            elif not sub or not hasattr(obj, "Shape"):
                raise thickness_map.UserError("Caliper: '%s' is not a solid or a thickness map; pick a point on "
                                              "a face." % obj.Label)
            else:
                reading = thickness_map.caliper(obj, sub, pnt)
        except Exception as e:  # a bad pick is a message, never a crash of the panel
            self.set_message(str(e), error=True)
            return None
        text = reading.text()
        self.summary.appendPlainText(text)
        self.report(text)
        self.set_message(text)
        return reading

    def options(self):
        auto = self.auto_range.isChecked()
        return ThicknessOptions(method=self.method.currentText(),
                                per="face" if self.per.currentIndex() == 0 else "vertex",
                                deflection=self.deflection.value(), angular_deflection=self.angular.value(),
                                max_edge=(self.max_edge.value() or "auto") if self.split.isChecked() else 0.0,
                                on_brep=self.on_brep.isChecked(),
                                threshold=self.threshold.value(), max_thickness=self.thick_above.value(),
                                color_min=None if auto else self.range_min.value(),
                                color_max=None if auto else self.range_max.value(),
                                keep_previous=self.keep_previous.isChecked())

    def compute(self, progress, cancel):
        objects = self.solids_to_analyse()
        options = self.options()
        return self.in_transaction("Pierce thickness map", lambda doc: thickness_map.run(
            objects, options, doc=doc, progress=progress, cancel=cancel))

    def show_result(self, run):
        lo, hi = run.color_range
        self.legend.set_range(lo, hi, run.options.threshold, run.clamped)
        text = run.summary()
        self.summary.setPlainText(text)
        self.report(text)
        if self.hide_sources.isChecked():
            for s in run.solids:
                vo = getattr(s.meshed.ref.obj, "ViewObject", None)
                if vo is not None:
                    vo.Visibility = False
        self._highlight.clear()
        thick_only = run.options.max_thickness > 0 and not run.options.threshold > 0
        self.region_kind.blockSignals(True)
        self.region_kind.setCurrentIndex(1 if thick_only else 0)
        self.region_kind.blockSignals(False)
        self.region_kind.setEnabled(run.options.max_thickness > 0)
        regions = self.fill_regions()
        self.zoom_button.setEnabled(any(s.stats.summary.count for s in run.solids))
        self.scroll_to(self.regions if regions else self.legend)
        mins = [s.stats.summary.min for s in run.solids if s.stats.summary.count]
        self.set_message("Thickness of %d solid(s): minimum %.4g mm. Results: '%s' in the tree." % (
            len(run.solids), min(mins) if mins else math.nan, run.group.Label if run.group else "-"))

    def showing_thick(self):
        """Whether the region list shows the thick regions (else the thin ones)."""
        return self.region_kind.currentIndex() == 1

    def fill_regions(self):
        """Fills the list with the last result's thin or thick regions (as the selector says);
        returns them."""
        run = self.last_result
        self._highlight.clear()
        self.regions.blockSignals(True)
        self.regions.clear()
        thick = self.showing_thick()
        regions = [] if run is None else (run.thick_regions if thick else run.thin_regions) or []
        for k, g in enumerate(regions):
            self.regions.addItem("%d. %s: %s %.4g mm, %.4g mm\u00b2, %d samples" % (
                k + 1, run.region_label(g), "max" if thick else "min", g.thickness, g.area, g.samples))
        self.regions.setCurrentRow(-1)
        self.regions.blockSignals(False)
        if run is None:
            return regions
        if thick:
            self.regions_label.setText("%d thick region(s), thickness > %.4g mm, thickest first (area: both sides):"
                                       % (len(regions), run.options.max_thickness))
        elif run.options.threshold > 0:
            self.regions_label.setText("%d thin region(s), thickness < %.4g mm, thinnest first (area: both sides):"
                                       % (len(regions), run.options.threshold))
        else:
            self.regions_label.setText("Thin regions: set 'Thin below' to list them.")
        return regions

    def on_region(self, row):
        """Selects the faces of the region in list row `row`, frames it in the 3D view and
        highlights it."""
        run = self.last_result
        regions = None if run is None else run.thick_regions if self.showing_thick() else run.thin_regions
        if not regions or not 0 <= row < len(regions):
            return
        self.show_region(run.region_id(self.showing_thick(), row))

    def show_region(self, k):
        """Region k (ThicknessRun.region: thin ones first, then thick ones) selected, framed and
        outlined."""
        import FreeCADGui as Gui
        run = self.last_result
        obj, faces = run.region_faces(k)
        self._selecting = True  # the caliper does not read these selections
        try:
            Gui.Selection.clearSelection()
            for f in faces:
                Gui.Selection.addSelection(obj, f)
        finally:
            self._selecting = False
        centre, radius, normal = run.region_view(k)
        g = run.region(k)
        s = run.region_solid(g)
        self._highlight.show(_region_edges(run, s, k), [g.point, g.exit])
        frame(centre, radius, direction=None if normal is None else tuple(-c for c in normal))
        number = k - len(run.thin_regions or []) + 1 if g.thick else k + 1
        self.set_message("%s %d: '%s', %s %.4g mm at (%.4g, %.4g, %.4g); highlighted in cyan%s." % (
            "Thick region" if g.thick else "Region", number, run.region_label(g), "max" if g.thick else "min",
            g.thickness, g.point[0], g.point[1], g.point[2],
            ", faces %s selected" % ", ".join(faces) if faces else ""))

    def zoom_to_thinnest(self):
        """Frames the thinnest region (or, without a threshold, the thinnest sample)."""
        run = self.last_result
        if run is None:
            return
        if run.thin_regions:
            if self.showing_thick():
                self.region_kind.setCurrentIndex(0)  # the list shows the thin regions again
            if self.regions.currentRow() == 0:
                self.show_region(0)
            else:
                self.regions.setCurrentRow(0)
            return
        best = None
        for s in run.solids:
            vals = np.where(np.isfinite(s.values), s.values, np.inf)
            if len(vals) and (best is None or vals.min() < best[0]):
                best = (float(vals.min()), s, int(np.argmin(vals)))
        if best is None or not math.isfinite(best[0]):
            self.set_message("No thickness was found: nothing to zoom to.", error=True)
            return
        value, s, i = best
        p = s.points[i]
        n = s.normals[i]
        size = max(value, 1e-3 * float(np.linalg.norm(s.meshed.vertices.max(axis=0) - s.meshed.vertices.min(axis=0))))
        self._highlight.show([], [p])
        frame(tuple(p), 2.0 * size, direction=tuple(-c for c in n) if np.linalg.norm(n) > 0.5 else None)
        self.set_message("Thinnest wall: %.4g mm on '%s' at (%.4g, %.4g, %.4g); highlighted in cyan." % (
            value, s.label, p[0], p[1], p[2]))

    def reject(self):
        self.set_caliper(False)  # the observer and the highlight go with the panel
        self._highlight.clear()
        return super().reject()


def _region_edges(run, solid, k):
    """The outline of region k's samples as segments: the edges of its triangles (per face)
    or of the triangles around its vertices (per vertex), each once."""
    if solid is None:
        return []
    m = solid.meshed
    ids = np.nonzero(solid.region == k)[0]
    if run.options.per == "face":
        tris = m.triangles[ids]
    else:
        tris = m.triangles[np.isin(m.triangles, ids).any(axis=1)]
    edges = {tuple(sorted((int(a), int(b)))) for t in tris for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
    return [(m.vertices[a], m.vertices[b]) for a, b in sorted(edges)]


def _tessellation_defaults():
    """Pierce's shared tessellation defaults; while Pierce cannot be loaded, the fields start at
    0 (automatic / off) and Run says why nothing can be computed."""
    from ..tessellate import tessellation_defaults
    try:
        return tessellation_defaults()
    except PierceUnavailable:
        return {"linear_deflection": 0.0, "angular_deflection": 15.0, "max_edge": 0.0}


class _CaliperObserver:
    def __init__(self, panel):
        self.panel = panel

    def addSelection(self, doc, obj, sub, pnt):
        self.panel.caliper_pick(doc, obj, sub, pnt)
