"""pvbatch check of the installed ParaView plugin (packaging/test-deb.sh): loads it by name, as a
user would, checks it is the installed file with the project version, and runs Thickness on the
bundled STEP sample (a 10 x 10 x 2 plate: every plate triangle is 2 or 10 thick).

    pvbatch pv_installed.py PLUGIN_DIR VERSION /usr/share/doc/pierce/samples/plate_assembly.step
"""
import os
import sys

from paraview import servermanager
from paraview.simple import LoadDistributedPlugin, OpenDataFile

plugin_dir, version, step = sys.argv[1:4]
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


LoadDistributedPlugin("PierceParaView", ns=globals())
info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
found = [i for i in range(info.GetNumberOfPlugins()) if info.GetPluginName(i) == "PierceParaView"]
check(len(found) == 1, "PierceParaView listed once by the plugin manager")
if found:
    i = found[0]
    expected = os.path.join(plugin_dir, "PierceParaView", "PierceParaView.so")
    check(os.path.realpath(info.GetPluginFileName(i)) == os.path.realpath(expected),
          "loaded from %s (expected %s)" % (info.GetPluginFileName(i), expected))
    check(info.GetPluginLoaded(i), "plugin loaded")
    check(info.GetPluginVersion(i) == version, "plugin version %r == %r" % (info.GetPluginVersion(i), version))

reader = OpenDataFile(step)
check(reader is not None and reader.GetXMLName() == "PierceCADReader", "STEP opened by PierceCADReader")
thickness = PierceThickness(Input=reader, SampleAt="Cells", MinThickness=3.0)  # noqa: F821
result = servermanager.Fetch(thickness)
blocks = {result.GetMetaData(b).Get(result.NAME()): result.GetBlock(b) for b in range(result.GetNumberOfBlocks())}
plates = [block for name, block in blocks.items() if name.endswith("/plate")]
check(len(plates) == 1, "one plate solid among %s" % sorted(blocks))
if plates:
    arr = plates[0].GetCellData().GetArray("Thickness")
    values = [arr.GetTuple1(k) for k in range(arr.GetNumberOfTuples())] if arr else []
    check(len(values) > 0 and all(abs(v - 2.0) < 1e-6 or abs(v - 10.0) < 1e-6 for v in values),
          "plate thickness is 2 or 10 on %d triangles" % len(values))
print("pvbatch checks: %d failures" % len(failures), flush=True)
sys.exit(1 if failures else 0)
