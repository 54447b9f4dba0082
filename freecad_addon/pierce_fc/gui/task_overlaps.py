"""Task panel: overlap check; clicking a row selects the faces (or solids) involved."""
import math

import FreeCADGui as Gui

from .. import overlap_check
from ..overlap_check import OverlapOptions
from .export_report import add_export_button
from .panel_base import PanelBase, check_box, double_spin
from .qt import QtWidgets

COLUMNS = ["Finding", "Solid A", "Solid B", "Depth (mm)", "Area (mm²)", "Faces"]


class OverlapPanel(PanelBase):
    TITLE = "Pierce overlap check"
    RUN_TEXT = "Check overlaps"

    def build_options(self, layout):
        f = self.options_form(layout, "Options")
        self.whole_document = check_box(
            "All visible solids of the document",
            tooltip="Otherwise the selected solids (a group or App::Part selects its contents)")
        self.tolerance = double_spin(1e-3, 0.0, 1e6, decimals=6, special="exact only", step=1e-3)
        self.tolerance.setToolTip("Faces closer than this to each other's plane count as coplanar")
        self.grid = QtWidgets.QSpinBox()
        self.grid.setRange(1, 4096)
        self.grid.setValue(64)
        self.grid.setToolTip("Interference is looked for along grid x grid rays in each axis direction")
        self.deflection = double_spin(0.0, 0.0, 1e6, special="automatic (0.1% of size)", step=0.01)
        self.markers = check_box("Add markers to the document", True)
        f.addRow(self.whole_document)
        f.addRow("Coplanar tolerance", self.tolerance)
        f.addRow("Rays per side", self.grid)
        f.addRow("Deflection", self.deflection)
        f.addRow(self.markers)

    def build_results(self, layout):
        self.table = self.results_table(layout, COLUMNS)
        self.table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectRows)
        self.table.setSelectionMode(QtWidgets.QAbstractItemView.SingleSelection)
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.itemSelectionChanged.connect(self.on_row)
        self.export_button = add_export_button(self, layout, lambda: (
            self.solids_to_analyse(self.whole_document.isChecked()), dict(deflection=self.deflection.value())))

    def compute(self, progress, cancel):
        objects = self.solids_to_analyse(self.whole_document.isChecked())
        opts = OverlapOptions(tolerance=self.tolerance.value(), grid=self.grid.value(),
                              deflection=self.deflection.value(), create_objects=self.markers.isChecked())
        return self.in_transaction("Pierce overlap check", lambda doc: overlap_check.run(
            objects, opts, doc=doc, progress=progress, cancel=cancel))

    def show_result(self, run):
        self.table.setRowCount(0)
        for f in run.findings:
            r = self.table.rowCount()
            self.table.insertRow(r)
            depth = "" if f.depth is None else "%.4g" % f.depth
            area = "" if f.kind == "interference" or f.area is None or math.isnan(f.area) else "%.4g" % f.area
            faces = "; ".join("%s: %s" % (o.Label, ", ".join(s)) for o, s in f.selection() if s)
            for col, text in enumerate([f.title, f.a.label, f.b.label if f.b is not f.a else "(same)", depth,
                                        area, faces]):
                self.table.setItem(r, col, QtWidgets.QTableWidgetItem(text))
        self.table.resizeColumnsToContents()
        text = run.summary()
        self.report(text)
        n = len(run.of_kind("interference"))
        self.set_message("%d solids: %d interpenetrating pair(s), %d contact(s), %d coincident, %d duplicate. "
                         "Click a row to select its faces." % (
                             len(run.model.solids), n, len(run.of_kind("contact")),
                             len(run.of_kind("coincident")), len(run.of_kind("duplicate"))))

    def on_row(self):
        rows = {i.row() for i in self.table.selectedItems()}
        if not rows or self.last_result is None:
            return
        select_finding(self.last_result.findings[min(rows)])


def select_finding(finding):
    """Selects the faces of a finding (or whole solids when no face is known)."""
    Gui.Selection.clearSelection()
    for obj, subs in finding.selection():
        if subs:
            for s in subs:
                Gui.Selection.addSelection(obj, s)
        else:
            Gui.Selection.addSelection(obj)
