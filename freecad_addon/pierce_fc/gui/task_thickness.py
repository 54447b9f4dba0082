"""Task panel: thickness map of the selected solids."""
import math

from .. import thickness_map
from ..locate import PierceUnavailable
from ..thickness_map import ThicknessOptions
from .legend import Legend
from .panel_base import PanelBase, double_spin
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
        self.per.setToolTip("faces: one value per triangle (exact on flat walls); vertices: smooth colours, "
                            "but vertices on sharp edges use an averaged normal")
        self.deflection = double_spin(0.0, 0.0, 1e6, special="automatic (0.1% of size)", step=0.01)
        self.angular = double_spin(15.0, 1.0, 90.0, decimals=1, suffix=" deg")
        self.split = QtWidgets.QCheckBox("Split triangle edges longer than")
        self.split.setChecked(True)
        self.split.setToolTip("More samples on large flat faces (whose CAD triangles are few and big)")
        self.max_edge = double_spin(0.0, 0.0, 1e6, special="automatic (4% of size)", step=0.1)
        self.split.toggled.connect(self.max_edge.setEnabled)
        self.threshold = double_spin(0.0, 0.0, 1e6, special="off", step=0.1)
        self.threshold.setToolTip("Samples thinner than this are coloured magenta")
        self.auto_range = QtWidgets.QCheckBox("from the results")
        self.auto_range.setChecked(True)
        self.range_min = double_spin(0.0, -1e9, 1e9)
        self.range_max = double_spin(10.0, -1e9, 1e9)
        self.range_min.setEnabled(False)
        self.range_max.setEnabled(False)
        self.auto_range.toggled.connect(lambda on: (self.range_min.setEnabled(not on), self.range_max.setEnabled(not on)))
        self.hide_sources = QtWidgets.QCheckBox("Hide the analysed solids")
        self.hide_sources.setChecked(True)
        f.addRow("Method", self.method)
        f.addRow("Samples", self.per)
        f.addRow("Deflection", self.deflection)
        f.addRow("Angular deflection", self.angular)
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
        self.summary = QtWidgets.QPlainTextEdit()
        self.summary.setReadOnly(True)
        self.summary.setMinimumHeight(100)
        layout.addWidget(self.summary)

    def options(self):
        auto = self.auto_range.isChecked()
        return ThicknessOptions(method=self.method.currentText(),
                                per="face" if self.per.currentIndex() == 0 else "vertex",
                                deflection=self.deflection.value(), angular_deflection=self.angular.value(),
                                max_edge=(self.max_edge.value() or None) if self.split.isChecked() else 0.0,
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
