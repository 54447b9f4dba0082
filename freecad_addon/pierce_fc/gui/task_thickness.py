"""Task panel: thickness map of the selected solids."""
import math

import FreeCAD

from .. import thickness_map
from ..locate import PierceUnavailable
from ..thickness_map import ThicknessOptions
from .export_report import add_export_button
from .legend import Legend
from .panel_base import PanelBase, check_box, double_spin
from .qt import QtWidgets


class ThicknessPanel(PanelBase):
    TITLE = "Pierce thickness map"
    RUN_TEXT = "Compute thickness"

    def build_options(self, layout):
        box = QtWidgets.QGroupBox("Options")
        f = QtWidgets.QFormLayout(box)
        self.method = QtWidgets.QComboBox()
        try:
            self.method.addItems(list(thickness_map.method_names()))
        except PierceUnavailable:  # the panel still opens; Run says why nothing can be computed
            self.method.setEnabled(False)
        self.method.setToolTip("ray: along the inward normal to where the ray leaves the solid; cone: shape "
                               "diameter function over 30 rays; sphere: largest inscribed ball")
        self.per = QtWidgets.QComboBox()
        self.per.addItems(["faces", "vertices"])
        self.per.setToolTip("faces: one value per triangle; vertices: smooth colours (on the B-rep a vertex on "
                            "an edge shows the smaller of its faces' walls; on FreeCAD's mesh it uses an "
                            "averaged normal)")
        self.deflection = double_spin(0.0, 0.0, 1e6, special="automatic (0.1% of size)", step=0.01)
        self.angular = double_spin(15.0, 1.0, 90.0, decimals=1, suffix=" deg")
        try:
            has_cad = thickness_map.has_cad()
        except PierceUnavailable:
            has_cad = False
        self.on_brep = check_box("On the exact B-rep", has_cad,
                                 tooltip="Samples start on the exact faces and exits are refined on them; the "
                                         "tessellation is checked against the B-rep (no false thin spots from "
                                         "the mesh). Off: FreeCAD's mesh, measured as a mesh")
        self.split = check_box("Split triangle edges longer than", True,
                               tooltip="More samples on large flat faces (whose CAD triangles are few and "
                                       "big); on the B-rep the split triangles stay on their faces")
        self.max_edge = double_spin(0.0, 0.0, 1e6, special="automatic (4% of size)", step=0.1)
        self.split.toggled.connect(self.max_edge.setEnabled)
        self.threshold = double_spin(0.0, 0.0, 1e6, special="off", step=0.1)
        self.threshold.setToolTip("Samples thinner than this are coloured magenta")
        self.auto_range = check_box("from the results", True)
        self.range_min = double_spin(0.0, -1e9, 1e9)
        self.range_max = double_spin(10.0, -1e9, 1e9)
        self.range_min.setEnabled(False)
        self.range_max.setEnabled(False)
        self.auto_range.toggled.connect(lambda on: (self.range_min.setEnabled(not on), self.range_max.setEnabled(not on)))
        self.hide_sources = check_box("Hide the analysed solids", True)
        f.addRow("Method", self.method)
        f.addRow("Samples", self.per)
        f.addRow("Deflection", self.deflection)
        f.addRow("Angular deflection", self.angular)
        f.addRow(self.on_brep)
        f.addRow(self.split, self.max_edge)
        f.addRow("Thin below", self.threshold)
        f.addRow("Legend range", self.auto_range)
        f.addRow("  min (red)", self.range_min)
        f.addRow("  max (blue)", self.range_max)
        f.addRow(self.hide_sources)
        layout.addWidget(box)

    def build_results(self, layout):
        self.legend = Legend()
        layout.addWidget(self.legend)
        # Caliper: while on, a point picked on a face reads the wall there on the exact B-rep.
        self.caliper_button = QtWidgets.QPushButton("Caliper: pick points on faces")
        self.caliper_button.setCheckable(True)
        self.caliper_button.setToolTip("While on, click a point on a face in the 3D view to read the wall "
                                       "thickness there (exact B-rep); readings go to the summary below")
        self.caliper_button.toggled.connect(self.set_caliper)
        self._caliper_observer = None
        layout.addWidget(self.caliper_button)
        self.summary = QtWidgets.QPlainTextEdit()
        self.summary.setReadOnly(True)
        self.summary.setMinimumHeight(100)
        layout.addWidget(self.summary)
        self.export_button = add_export_button(self, layout, lambda: (self.solids_to_analyse(), dict(
            min_thickness=self.threshold.value(), method=self.method.currentText(),
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
        doc = FreeCAD.getDocument(doc_name)
        obj = doc.getObject(obj_name) if doc else None
        if obj is None or not sub or not hasattr(obj, "Shape"):
            return None
        try:
            reading = thickness_map.caliper(obj, sub, pnt)
        except Exception as e:  # a bad pick is a message, never a crash of the panel
            self.set_message(str(e), error=True)
            return None
        text = reading.text()
        self.summary.appendPlainText(text)
        self.report(text)
        self.set_message(text)
        return reading

    def reject(self):
        self.set_caliper(False)  # the observer goes with the panel
        return super().reject()

    def options(self):
        auto = self.auto_range.isChecked()
        return ThicknessOptions(method=self.method.currentText(),
                                per="face" if self.per.currentIndex() == 0 else "vertex",
                                deflection=self.deflection.value(), angular_deflection=self.angular.value(),
                                max_edge=(self.max_edge.value() or None) if self.split.isChecked() else 0.0,
                                on_brep=self.on_brep.isChecked(),
                                threshold=self.threshold.value(),
                                color_min=None if auto else self.range_min.value(),
                                color_max=None if auto else self.range_max.value())

    def compute(self, progress, cancel):
        objects = self.solids_to_analyse()
        options = self.options()
        return self.in_transaction("Pierce thickness map", lambda doc: thickness_map.run(
            objects, options, doc=doc, progress=progress, cancel=cancel))

    def show_result(self, run):
        lo, hi = run.color_range
        self.legend.set_range(lo, hi, run.options.threshold)
        text = run.summary()
        self.summary.setPlainText(text)
        self.report(text)
        if self.hide_sources.isChecked():
            for s in run.solids:
                vo = getattr(s.meshed.ref.obj, "ViewObject", None)
                if vo is not None:
                    vo.Visibility = False
        mins = [s.stats.summary.min for s in run.solids if s.stats.summary.count]
        self.set_message("Thickness of %d solid(s): minimum %.4g mm. Results: '%s' in the tree." % (
            len(run.solids), min(mins) if mins else math.nan, run.group.Label if run.group else "-"))


class _CaliperObserver:
    def __init__(self, panel):
        self.panel = panel

    def addSelection(self, doc, obj, sub, pnt):
        self.panel.caliper_pick(doc, obj, sub, pnt)
