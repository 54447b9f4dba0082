"""FreeCAD GUI check (under xvfb-run) of the installed workbench: FreeCAD lists the Pierce
workbench, activates it and registers its commands. Exits with the result (os._exit: the GUI
would otherwise keep running) and writes a report to $PIERCE_TEST_REPORT.

    PIERCE_TEST_REPORT=report.txt QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a -s "-screen 0 1280x1024x24" freecad fc_gui_installed.py
"""
import os
import sys
import traceback


def main():
    failures = []

    def check(cond, what):
        print(("ok   " if cond else "FAIL ") + what, flush=True)
        if not cond:
            failures.append(what)

    try:
        import FreeCADGui as Gui
        check("PierceWorkbench" in Gui.listWorkbenches(), "the Pierce workbench is listed")
        Gui.activateWorkbench("PierceWorkbench")
        check(Gui.activeWorkbench().MenuText == "Pierce", "the Pierce workbench is active")
        cmds = Gui.listCommands()
        for name in ("Pierce_ThicknessMap", "Pierce_OverlapCheck", "Pierce_Shotline"):
            check(name in cmds, "command %s registered" % name)
        import pierce_fc
        check(os.path.realpath(pierce_fc.__file__).startswith(os.path.realpath(os.environ["PIERCE_EXPECT_MOD"]) + os.sep),
              "workbench from %s" % pierce_fc.__file__)
    except BaseException:  # noqa: B902
        traceback.print_exc()
        failures.append("exception")
    summary = "freecad GUI checks: %d failures" % len(failures)
    print(summary, flush=True)
    sys.stdout.flush()
    # The GUI may redirect stdout to its report view: the caller reads this file.
    with open(os.environ["PIERCE_TEST_REPORT"], "w") as f:
        f.write("\n".join(["FAIL " + what for what in failures] + [summary]) + "\n")
    os._exit(1 if failures else 0)


from PySide2 import QtCore  # noqa: E402
QtCore.QTimer.singleShot(0, main)
