"""freecadcmd check of the installed FreeCAD workbench (packaging/test-deb.sh): the workbench's
package comes from FreeCAD's system Mod directory, finds the installed `pierce` module with no
path file, and computes a thickness map (a 10 mm cube is 10 thick everywhere).

    PIERCE_EXPECT_MOD=/usr/share/freecad/Mod/Pierce PIERCE_EXPECT_PYDIR=/usr/lib/python3/dist-packages \
        freecadcmd fc_installed.py
"""
import os

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def under(path, directory):
    return os.path.realpath(path).startswith(os.path.realpath(directory) + os.sep)


def body():
    import FreeCAD
    import Part
    import numpy as np

    mod, pydir = os.environ["PIERCE_EXPECT_MOD"], os.environ["PIERCE_EXPECT_PYDIR"]
    import pierce_fc
    check(under(pierce_fc.__file__, mod), "pierce_fc from %s (expected under %s)" % (pierce_fc.__file__, mod))
    check(not os.path.exists(os.path.join(mod, "pierce_path.txt")), "no pierce_path.txt in the installed workbench")
    from pierce_fc.locate import import_pierce
    pierce = import_pierce()
    check(under(pierce.__file__, pydir), "pierce from %s (expected under %s)" % (pierce.__file__, pydir))

    from pierce_fc import thickness_map
    from pierce_fc.thickness_map import ThicknessOptions
    doc = FreeCAD.newDocument("PierceInstalled")
    cube = doc.addObject("Part::Feature", "Cube")
    cube.Shape = Part.makeBox(10, 10, 10)
    doc.recompute()
    run = thickness_map.run([cube], ThicknessOptions(per="face"), doc=doc)
    values = run.solids[0].values
    check(abs(float(np.nanmin(values)) - 10.0) < 1e-4 and abs(float(np.nanmax(values)) - 10.0) < 1e-4,
          "cube thickness 10 (min %g, max %g)" % (np.nanmin(values), np.nanmax(values)))


try:
    body()
except BaseException as e:  # noqa: B902  (report anything, then fail)
    import traceback
    traceback.print_exc()
    failures.append("exception: %r" % e)
print("freecadcmd checks: %d failures" % len(failures), flush=True)
raise SystemExit(1 if failures else 0)
