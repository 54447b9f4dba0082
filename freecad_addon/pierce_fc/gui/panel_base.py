"""Common task-panel frame: options on top, Run / Stop, a message line, results below.

Runs happen on the GUI thread; Pierce works on its own threads meanwhile and calls back a few
times a second, when the progress bar moves and Qt events are processed (so Stop and the progress
bar's abort work). Errors the user can fix are shown in the message line, never as a traceback.
"""
import traceback

import FreeCAD
import FreeCADGui as Gui

from ..errors import UserError
from ..progress import Progress
from .qt import QtCore, QtWidgets


class PanelBase:
    TITLE = "Pierce"
    RUN_TEXT = "Run"

    def __init__(self):
        self.form = QtWidgets.QWidget()
        self.form.setWindowTitle(self.TITLE)
        self.layout = QtWidgets.QVBoxLayout(self.form)
        # The task view frames the panel already; its own margins would cost the default Combo
        # View (264 px) the width of a field.
        self.layout.setContentsMargins(0, 0, 0, 0)
        self.build_options(self.layout)
        row = QtWidgets.QHBoxLayout()
        self.run_button = QtWidgets.QPushButton(self.RUN_TEXT)
        self.stop_button = QtWidgets.QPushButton("Stop")
        self.stop_button.setEnabled(False)
        row.addWidget(self.run_button)
        row.addWidget(self.stop_button)
        self.layout.addLayout(row)
        self.message = QtWidgets.QLabel("")
        self.message.setWordWrap(True)
        self.message.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        self.layout.addWidget(self.message)
        self.build_results(self.layout)
        self.run_button.clicked.connect(self.on_run)
        self.stop_button.clicked.connect(self.on_stop)
        self.token = None
        self.last_result = None

    # --- for subclasses ---
    def build_options(self, layout):
        pass

    def build_results(self, layout):
        pass

    def compute(self, progress, cancel):
        """Runs the analysis and returns its result; raise UserError for messages."""
        raise NotImplementedError

    def show_result(self, result):
        pass

    # --- running ---
    def set_message(self, text, error=False):
        self.message.setStyleSheet("color: #b00020;" if error else "")
        self.message.setText(wrappable(text))

    def on_run(self):
        from ..locate import PierceUnavailable, import_pierce
        try:
            pierce = import_pierce()
        except PierceUnavailable as e:
            self.set_message(str(e), error=True)
            return
        self.token = pierce.CancelToken()
        self.run_button.setEnabled(False)
        self.stop_button.setEnabled(True)
        self.set_message("Running...")
        QtWidgets.QApplication.processEvents()
        try:
            with Progress(self.TITLE, cancel=self.token,
                          process_events=QtWidgets.QApplication.processEvents) as progress:
                result = self.compute(progress, self.token)
            self.last_result = result
            self.show_result(result)
        except UserError as e:
            self.set_message(str(e), error=True)
        except pierce.Cancelled:
            self.set_message("Stopped; nothing was added to the document.")
        except Exception as e:  # a bug: say so in the panel, details in the Report view
            FreeCAD.Console.PrintError("Pierce: %s\n%s" % (e, traceback.format_exc()))
            self.set_message("Unexpected error: %s (details in the Report view)" % e, error=True)
        finally:
            self.token = None
            self.run_button.setEnabled(True)
            self.stop_button.setEnabled(False)

    def on_stop(self):
        if self.token is not None:
            self.token.cancel()
            self.set_message("Stopping...")

    def report(self, text):
        FreeCAD.Console.PrintMessage(text + "\n")

    # --- helpers for build_options() and compute() ---
    def options_form(self, layout, title):
        """A group box called `title` added to `layout`; returns its form layout for the rows."""
        box = QtWidgets.QGroupBox(title)
        layout.addWidget(box)
        form = QtWidgets.QFormLayout(box)
        # In the default Combo View (264 px) a label and a wide field do not fit on one line: the
        # field goes below its label.
        form.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
        form.setFieldGrowthPolicy(QtWidgets.QFormLayout.AllNonFixedFieldsGrow)
        return form

    def collapsible_form(self, layout, title, expanded=False):
        """A form under a button `title` that shows or hides it (hidden unless `expanded`), added
        to `layout`: options most runs leave alone, so that the results fit on the first screen.
        Returns the form layout for the rows."""
        button = QtWidgets.QToolButton()
        button.setText(title)
        button.setCheckable(True)
        button.setChecked(expanded)
        button.setToolButtonStyle(QtCore.Qt.ToolButtonTextBesideIcon)
        button.setArrowType(QtCore.Qt.DownArrow if expanded else QtCore.Qt.RightArrow)
        button.setAutoRaise(True)
        box = QtWidgets.QGroupBox()
        box.setVisible(expanded)

        def toggle(on):
            box.setVisible(on)
            button.setArrowType(QtCore.Qt.DownArrow if on else QtCore.Qt.RightArrow)
        button.toggled.connect(toggle)
        layout.addWidget(button)
        layout.addWidget(box)
        form = QtWidgets.QFormLayout(box)
        form.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
        form.setFieldGrowthPolicy(QtWidgets.QFormLayout.AllNonFixedFieldsGrow)
        form.toggle_button = button
        return form

    def scroll_to(self, widget):
        """Scrolls the task view so that `widget` (a result) is in sight."""
        area = self.form.parent()
        while area is not None and not isinstance(area, QtWidgets.QScrollArea):
            area = area.parent()
        if area is not None:
            QtWidgets.QApplication.processEvents()
            area.ensureWidgetVisible(widget, 0, 0)

    def results_table(self, layout, columns):
        """A read-only table with a header of `columns`, added to `layout`; rows are filled by
        show_result()."""
        table = QtWidgets.QTableWidget(0, len(columns))
        table.setHorizontalHeaderLabels(columns)
        table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
        table.setMinimumHeight(160)
        layout.addWidget(table)
        return table

    def solids_to_analyse(self, whole_document=False):
        """The objects a run works on: every visible solid of the active document, or the
        current selection (a group or App::Part selects its contents)."""
        if whole_document:
            return visible_solids(FreeCAD.ActiveDocument)
        return selected_objects()

    def in_transaction(self, name, work):
        """Calls work(doc) on the active document inside one undo step called `name`: committed
        when it returns, aborted when it raises (a failure, or Stop), so that a run that did not
        finish leaves nothing in the document. Returns what work returned."""
        doc = FreeCAD.ActiveDocument
        doc.openTransaction(name)
        try:
            result = work(doc)
        except BaseException:
            doc.abortTransaction()
            raise
        doc.commitTransaction()
        return result

    # --- task dialog protocol ---
    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Close)

    def reject(self):
        self.on_stop()
        Gui.Control.closeDialog()
        return True

    def isAllowedAlterSelection(self):
        return True

    def isAllowedAlterView(self):
        return True

    def isAllowedAlterDocument(self):
        return True


def wrappable(text):
    """`text` with a zero-width space after each '_', '-', '/' and '.', so that a word-wrapped
    label can break long names (a STEP part's name has no spaces) instead of widening the panel."""
    for ch in "_-/.":
        text = text.replace(ch, ch + "\u200b")
    return text


def selected_objects():
    return list(Gui.Selection.getSelection())


def check_box(text, checked=False, tooltip=None):
    """A QCheckBox labelled `text`, ticked when `checked`."""
    w = QtWidgets.QCheckBox(text)
    w.setChecked(checked)
    if tooltip:
        w.setToolTip(tooltip)
    return w


def double_spin(value, minimum, maximum, decimals=4, suffix=" mm", special=None, step=None):
    w = QtWidgets.QDoubleSpinBox()
    w.setDecimals(decimals)
    w.setRange(minimum, maximum)
    w.setValue(value)
    if suffix:
        w.setSuffix(suffix)
    if special:
        w.setSpecialValueText(special)
    if step:
        w.setSingleStep(step)
    return w


def visible_solids(doc):
    """Visible objects of the document that hold solids (PartDesign features whose Body is also
    visible are dropped later by the selection logic)."""
    out = []
    for o in doc.Objects:
        shape = getattr(o, "Shape", None)
        if shape is None or not getattr(o, "Visibility", True):
            continue
        try:
            if shape.Solids:
                out.append(o)
        except Exception:  # objects whose Shape is not a Part shape
            continue
    return out
