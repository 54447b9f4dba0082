"""Pierce in pvbatch: load the plugin, open a model, run the three filters, write the results.

    pvbatch plugins/paraview/pierce_demo.py [MODEL] [--plugin PLUGIN] [--out DIR] [--force]

MODEL   a STEP/IGES/BREP file (read by the plugin's CAD reader, one block per solid) or anything
        ParaView reads; default: samples/plate_assembly.step.
PLUGIN  the built plugin; default: build/lib/paraview-plugins/PierceParaView/PierceParaView.so.
DIR     output directory (default: pierce_demo_out); existing outputs are kept unless --force.

Writes, with the arrays ParaView colours by:
  thickness.vtm        per-triangle Thickness, Thin, ThicknessStatus, SolidId (Ray method)
  thickness_stats.csv  per-solid statistics
  overlaps.vtm         per-triangle OverlapCount, CoplanarCount, CoplanarPartner, ... SolidId
  overlap_pairs.csv    interfering, touching and coplanar solid pairs
  partitions.vtp       one segment per ray partition: RayId, SolidId, SolidCount, Depth, ...
  partitions.csv       the same as a table, with solid names
The thickness values are those of `pierce thickness MODEL --per face`, the overlap pairs those of
`pierce overlaps MODEL` on the same model (tests/paraview/check_demo_against_cli.py checks it).
"""
import argparse
import os
import sys

from paraview.simple import (LoadPlugin, OpenDataFile, OutputPort, Plane, SaveData,
                             UpdatePipeline)
from paraview import servermanager

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
OUTPUTS = ["thickness.vtm", "thickness_stats.csv", "overlaps.vtm", "overlap_pairs.csv",
           "partitions.vtp", "partitions.csv"]


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("model", nargs="?", default=os.path.join(ROOT, "samples", "plate_assembly.step"))
    p.add_argument("--plugin", default=os.path.join(
        ROOT, "build", "lib", "paraview-plugins", "PierceParaView", "PierceParaView.so"))
    p.add_argument("--out", default="pierce_demo_out")
    p.add_argument("--rays", type=int, default=16, help="ray grid resolution for the classification")
    p.add_argument("--force", action="store_true", help="overwrite existing outputs")
    return p.parse_args(argv)


def fail(message):
    sys.stderr.write("pierce_demo: %s\n" % message)
    sys.exit(1)


def main(argv):
    args = parse_args(argv)
    if not os.path.isfile(args.plugin):
        fail("plugin not found: %s (build Pierce first, or pass --plugin)" % args.plugin)
    if not os.path.isfile(args.model):
        fail("model not found: %s" % args.model)
    os.makedirs(args.out, exist_ok=True)
    existing = [f for f in OUTPUTS if os.path.exists(os.path.join(args.out, f))]
    if existing and not args.force:
        fail("%s already holds %s; pass --force to overwrite" % (args.out, ", ".join(existing)))

    LoadPlugin(args.plugin, ns=globals())
    model = OpenDataFile(args.model)
    if model is None:
        fail("ParaView has no reader for %s" % args.model)
    UpdatePipeline(proxy=model)

    thickness = PierceThickness(Input=model)  # noqa: F821 (defined by LoadPlugin)
    thickness.Method = "Ray"
    thickness.SampleAt = "Cells"
    overlaps = PierceOverlaps(Input=model)  # noqa: F821

    # A grid of rays along +z under the model's bounds.
    (x0, x1, y0, y1, z0, z1) = model.GetDataInformation().GetBounds()
    margin = 0.01 * max(x1 - x0, y1 - y0, z1 - z0)
    grid = Plane(Origin=[x0 + margin, y0 + margin, z0 - margin],
                 Point1=[x1 - margin, y0 + margin, z0 - margin],
                 Point2=[x0 + margin, y1 - margin, z0 - margin],
                 XResolution=args.rays, YResolution=args.rays)
    classify = PierceRayClassify(Input=model, Rays=grid)  # noqa: F821
    classify.RayDirection = [0, 0, 1]
    classify.IncludeGaps = 1

    out = lambda name: os.path.join(args.out, name)  # noqa: E731
    # Inline base64 arrays: files with appended data (ParaView's default) cannot be read back by
    # Debian 12's ParaView since its expat security update ("not well-formed (invalid token)").
    xml = dict(DataMode="Binary")
    csv = dict(Precision=17, UseScientificNotation=1)  # full double precision
    SaveData(out("thickness.vtm"), proxy=OutputPort(thickness, 0), **xml)
    SaveData(out("thickness_stats.csv"), proxy=OutputPort(thickness, 1), **csv)
    SaveData(out("overlaps.vtm"), proxy=OutputPort(overlaps, 0), **xml)
    SaveData(out("overlap_pairs.csv"), proxy=OutputPort(overlaps, 1), **csv)
    SaveData(out("partitions.vtp"), proxy=OutputPort(classify, 0), **xml)
    SaveData(out("partitions.csv"), proxy=OutputPort(classify, 1), **csv)

    stats = servermanager.Fetch(thickness, None, None, 1)
    for row in range(stats.GetNumberOfRows()):
        value = lambda column: stats.GetValueByName(row, column).ToString()  # noqa: E731
        print("%-24s min %-10s median %-10s max %-10s thin %s" % (
            value("Name"), value("Min"), value("P50"), value("Max"), value("Thin")))
    print("pierce_demo: wrote %s to %s" % (", ".join(OUTPUTS), os.path.abspath(args.out)))
    return 0


if __name__ == "__main__":
    # No sys.exit on success: pvbatch would then tear OpenGL down after the X display.
    if main(sys.argv[1:]):
        sys.exit(1)
