"""The "Export report..." button of the thickness and overlap panels: the HTML report of
`pierce report` (pierce_fc.html_report, docs/REPORT.md) for the panel's solids and options."""
from .. import html_report
from ..errors import UserError
from ..locate import PierceUnavailable
from .qt import QtWidgets


def add_export_button(panel, layout, report_arguments):
    """Adds "Export report..." to `layout`: asks for an HTML file (the dialog confirms replacing
    one) and writes there the report of report_arguments() -> (objects, keyword arguments of
    html_report.export); the outcome goes to the panel's message line."""
    button = QtWidgets.QPushButton("Export report...")
    button.setToolTip("One self-contained HTML file to share: the 3D thickness map, thin walls, contact, clash "
                      "and clearance between solids, statistics and model checks")

    def export():
        path, _ = QtWidgets.QFileDialog.getSaveFileName(None, "Export report", "pierce_report.html",
                                                        "HTML files (*.html)")
        if not path:
            return
        panel.set_message("Writing the report...")
        QtWidgets.QApplication.processEvents()
        try:
            objects, kwargs = report_arguments()
            html_report.export(objects, path, **kwargs)
        except (UserError, PierceUnavailable) as e:
            panel.set_message(str(e), error=True)
            return
        panel.set_message("Report written: %s" % path)

    button.clicked.connect(export)
    layout.addWidget(button)
    return button
