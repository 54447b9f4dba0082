"""Task panel: overlap check; clicking a row selects the faces (or solids) involved."""
import FreeCADGui as Gui

from .. import overlap_check
from ..overlap_check import OverlapOptions
from .export_report import add_export_button
from .panel_base import PanelBase, check_box, double_spin, wrappable
from .qt import QtWidgets
from .view import Highlight, frame

COLUMNS = ["#", "Kind", "Solids", "mm", "Point"]


class OverlapPanel(PanelBase):
    TITLE = "Pierce overlap check"
    RUN_TEXT = "Check overlaps"

    def build_options(self, layout):
        f = self.options_form(layout, "Options")
        self.whole_document = check_box(
            "All visible solids",
            tooltip="Otherwise the selected solids (a group or App::Part selects its contents)")
        self.clearance = double_spin(0.0, 0.0, 1e6, special="off", step=0.1)
        self.clearance.setToolTip("Pairs of solids closer than this are listed as clearance, with the exact gap "
                                  "(as pierce overlaps --clearance); clashes and contacts are always listed")
        self.tolerance = double_spin(1e-3, 0.0, 1e6, decimals=6, special="exact only", step=1e-3)
        self.tolerance.setToolTip("Faces closer than this to each other's plane count as coplanar")
        self.grid = QtWidgets.QSpinBox()
        self.grid.setRange(1, 4096)
        self.grid.setValue(64)
        self.grid.setToolTip("Interference is looked for along grid x grid rays in each axis direction")
        self.deflection = double_spin(0.0, 0.0, 1e6, special="auto", step=0.01)
        self.deflection.setToolTip("Largest distance between the surface and its triangles; auto: 0.1% of the "
                                   "selection's diagonal")
        self.markers = check_box("Add markers", False,
                                 tooltip="Adds the findings to the document as marker objects, in one group "
                                         "'Overlap check' (replaced when checking the same solids again)")
        f.addRow(self.whole_document)
        f.addRow("Clearance", self.clearance)
        f.addRow(self.markers)
        more = self.collapsible_form(layout, "More options")
        more.addRow("Coplanar tolerance", self.tolerance)
        more.addRow("Rays per side", self.grid)
        more.addRow("Deflection", self.deflection)

    def build_results(self, layout):
        self.header = QtWidgets.QLabel("")
        self.header.setWordWrap(True)
        layout.addWidget(self.header)
        self.table = self.results_table(layout, COLUMNS)
        self.table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectRows)
        self.table.setSelectionMode(QtWidgets.QAbstractItemView.SingleSelection)
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.verticalHeader().setVisible(False)
        self.table.setWordWrap(False)
        self.table.itemSelectionChanged.connect(self.on_row)
        self.summary = QtWidgets.QPlainTextEdit()
        self.summary.setReadOnly(True)
        self.summary.setMinimumHeight(100)
        self.summary.setLineWrapMode(QtWidgets.QPlainTextEdit.NoWrap)
        layout.addWidget(self.summary)
        self._highlight = Highlight()
        self._transparency = {}  # object name -> its transparency before a row was chosen
        self.export_button = add_export_button(self, layout, lambda: (
            self.solids_to_analyse(self.whole_document.isChecked()), dict(deflection=self.deflection.value())))

    def compute(self, progress, cancel):
        objects = self.solids_to_analyse(self.whole_document.isChecked())
        opts = OverlapOptions(tolerance=self.tolerance.value(), grid=self.grid.value(),
                              deflection=self.deflection.value(), create_objects=self.markers.isChecked(),
                              clearance=self.clearance.value())
        return self.in_transaction("Pierce overlap check", lambda doc: overlap_check.run(
            objects, opts, doc=doc, progress=progress, cancel=cancel))

    def show_result(self, run):
        self.restore_view()
        self.table.setRowCount(0)
        for p in run.pairs:
            r = self.table.rowCount()
            self.table.insertRow(r)
            value = p.depth if p.kind == "clash" else (p.gap or 0.0)
            point = "(%.4g, %.4g, %.4g)" % p.point
            for col, text in enumerate([str(p.number), p.kind, "%s / %s" % (p.a.label, p.b.label),
                                        "%.4g" % value if value is not None else "", point]):
                item = QtWidgets.QTableWidgetItem(text)
                item.setToolTip(p.describe())
                self.table.setItem(r, col, item)
        self.table.resizeColumnsToContents()
        self.header.setText(wrappable("%s: %d clash, %d contact, %d clearance. Choose a row to see it." % (
            run.header(), len(run.pairs_of_kind("clash")), len(run.pairs_of_kind("contact")),
            len(run.pairs_of_kind("clearance")))))
        text = run.summary()
        self.summary.setPlainText(text)
        self.report(text)
        self.set_message("%d pair(s): mm = clash depth or gap." % len(run.pairs))
        self.scroll_to(self.table)

    def on_row(self):
        rows = {i.row() for i in self.table.selectedItems()}
        if not rows or self.last_result is None:
            return
        self.show_pair(self.last_result.pairs[min(rows)])

    def show_pair(self, pair):
        """Selects the pair's faces (or solids), makes every other analysed object transparent,
        marks the point (and the gap) in cyan and frames it."""
        run = self.last_result
        select_finding(pair)
        self.restore_view()
        # The pair's objects (for solids of a compound: the tree objects they come from) stay
        # nearly opaque; every other analysed object turns see-through.
        involved = [r.tree_obj or r.obj for r in (pair.a, pair.b)]
        others = [m.ref.obj for m in run.model.solids]
        for o in involved + others:
            vo = getattr(o, "ViewObject", None)
            if vo is None or o.Name in self._transparency:
                continue
            self._transparency[o.Name] = (vo.Transparency, vo.Visibility)
            vo.Visibility = True
            vo.Transparency = 20 if any(o is x for x in involved) else 85
        points = [pair.point] + ([pair.point_b] if pair.point_b else [])
        segments = [(pair.point, pair.point_b)] if pair.point_b else []
        if pair.finding is not None:  # the shared triangles of a contact, the deepest interval of a clash
            for tri in pair.finding.triangles:
                segments.extend((tri[k], tri[(k + 1) % 3]) for k in range(3))
            if pair.finding.segment is not None:
                segments.append(pair.finding.segment)
        self._highlight.show(segments, points)
        sizes = [min(r.shape.BoundBox.XLength, r.shape.BoundBox.YLength, r.shape.BoundBox.ZLength)
                 for r in (pair.a, pair.b)]
        radius = max(min(sizes), pair.gap or 0.0, pair.depth or 0.0)
        frame(pair.point, radius)
        self.set_message(pair.describe())

    def restore_view(self):
        """Puts back the transparency and visibility of objects changed by show_pair()."""
        import FreeCAD
        self._highlight.clear()
        doc = FreeCAD.ActiveDocument
        for name, (transparency, visible) in self._transparency.items():
            o = doc.getObject(name) if doc is not None else None
            vo = getattr(o, "ViewObject", None)
            if vo is not None:
                vo.Transparency = transparency
                vo.Visibility = visible
        self._transparency = {}

    def reject(self):
        self.restore_view()
        return super().reject()


def select_finding(finding):
    """Selects the faces of a finding or pair (or whole solids when no face is known)."""
    Gui.Selection.clearSelection()
    for obj, subs in finding.selection():
        if subs:
            for s in subs:
                Gui.Selection.addSelection(obj, s)
        else:
            Gui.Selection.addSelection(obj)
