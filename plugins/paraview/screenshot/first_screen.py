"""The ParaView GUI's first screen with Pierce: opens a model, clicks Apply, picks Filters ▸ Pierce ▸
Pierce Thickness and clicks Apply with its default properties, as a user does, then saves the
GUI's state (File ▸ Save State). The clicks are a QtTesting event script played by the real GUI
(paraview --test-script). Run under an X server (xvfb-run); used by make_screenshot.sh and the
test paraview.gui_first_screen.

    python3 first_screen.py --plugin-dir DIR --model samples/blob.stl --state out.pvsm [--shot out.png]

Without --shot, ParaView exits when the clicks are played. With --shot, the screen is grabbed
(Pillow) once the state is saved and the GUI has painted, then ParaView is closed.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time
from xml.sax.saxutils import quoteattr

PANEL_APPLY = "pqClientMainWindow/propertiesDock/propertiesPanel/Accept"


def events(state):
    """The clicks, in order: (object path, command, arguments)."""
    return [
        (PANEL_APPLY, "activate", ""),  # the reader of the file given with --data
        ("pqClientMainWindow/menubar/menuFilters/Pierce", "activate", "PierceThickness"),
        (PANEL_APPLY, "activate", ""),  # Pierce Thickness, default properties
        ("pqClientMainWindow/menubar/menu_File", "activate", "actionFileSaveServerState"),
        ("pqClientMainWindow/FileSaveServerStateDialog", "filesSelected", state),
    ]


def write_events(path, state):
    with open(path, "w") as f:
        f.write('<?xml version="1.0" ?>\n<pqevents>\n')
        for obj, command, arguments in events(state):
            f.write("  <pqevent object=%s command=%s arguments=%s />\n"
                    % (quoteattr(obj), quoteattr(command), quoteattr(arguments)))
        f.write("</pqevents>\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--paraview", default="paraview")
    parser.add_argument("--plugin-dir", required=True, help="directory of PierceParaView.so")
    parser.add_argument("--model", required=True)
    parser.add_argument("--state", required=True, help="the .pvsm to write")
    parser.add_argument("--shot", help="grab the screen into this PNG")
    parser.add_argument("--paint-seconds", type=float, default=8.0,
                        help="with --shot: wait this long after the state is saved for the GUI to paint")
    args = parser.parse_args()

    state = os.path.abspath(args.state)
    if os.path.exists(state):
        os.remove(state)
    with tempfile.TemporaryDirectory() as work:
        script = os.path.join(work, "first_screen.xml")
        write_events(script, state)
        env = dict(os.environ, PV_PLUGIN_PATH=os.path.abspath(args.plugin_dir))
        command = [args.paraview, "--dr", "--data=" + os.path.abspath(args.model), "--test-script=" + script]
        if not args.shot:
            result = subprocess.run(command + ["--exit"], env=env)
            if result.returncode != 0 or not os.path.isfile(state):
                print("first_screen: ParaView failed (exit %d, state %s)"
                      % (result.returncode, "written" if os.path.isfile(state) else "missing"))
                return 1
            return 0
        gui = subprocess.Popen(command, env=env)
        try:
            for _ in range(480):
                if os.path.isfile(state) or gui.poll() is not None:
                    break
                time.sleep(0.5)
            if not os.path.isfile(state):
                print("first_screen: ParaView did not save the state")
                return 1
            time.sleep(args.paint_seconds)
            from PIL import ImageGrab
            ImageGrab.grab().save(args.shot)
        finally:
            gui.terminate()
            gui.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
