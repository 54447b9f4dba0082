"""Qt for the panels: FreeCAD 0.20 ships PySide2."""
try:
    from PySide2 import QtCore, QtGui, QtWidgets  # noqa: F401
except ImportError:  # FreeCAD's PySide shim (QtGui also holds the widgets there)
    from PySide import QtCore, QtGui  # noqa: F401
    QtWidgets = QtGui
