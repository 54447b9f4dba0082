"""pvbatch test: ParaView's findings equal the CLI's on the STEP assembly (tests/vtk/step_assembly.h):

- Pierce Thickness (per triangle, Min Thickness 3, Max Thickness 5): the region table in the
  output's field data and the Region ids equal `pierce thickness --per face --min 3 --max 5`'s
  thin_regions and thick_regions; ThicknessColorRange is 0 to 4 x Min Thickness;
- Pierce Overlaps (Clearance 1, Rays Per Axis 32): the Pair* field data equal
  `pierce overlaps --clearance 1 --rays axes:n=32`'s pairs (kind, solids, gap, depth, point).

    pvbatch test_pv_findings.py --plugin PierceParaView.so --step assembly.step --cli pierce --out DIR
"""
import json
import math
import os
import subprocess
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin, OpenDataFile, UpdatePipeline

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pvbatch_main
from pvbatch_main import check  # noqa: E402

def same(a, b, rel=1e-9):
    if a is None or b is None:
        return (a is None or math.isnan(a)) and (b is None or math.isnan(b))
    return abs(a - b) <= rel * max(1.0, abs(a), abs(b))


def field_rows(data, names):
    """The tuples of the field data arrays `names` as rows of Python values."""
    fd = data.GetFieldData()
    arrays = [fd.GetAbstractArray(n) for n in names]
    for n, a in zip(names, arrays):
        check(a is not None, "field data %s present" % n)
    if any(a is None for a in arrays):
        return []
    rows = []
    for i in range(arrays[0].GetNumberOfTuples()):
        row = []
        for a in arrays:
            if a.IsA("vtkStringArray"):
                row.append(a.GetValue(i))
            elif a.GetNumberOfComponents() > 1:
                row.append(list(a.GetTuple(i)))
            else:
                row.append(a.GetTuple1(i))
        rows.append(row)
    return rows


def cli_json(cli, out, *args):
    p = subprocess.run([cli] + list(args) + ["-o", out, "--force"], capture_output=True, text=True)
    check(p.returncode == 0, "%s ran: %s" % (" ".join(args[:1]), p.stderr.strip()))
    return json.load(open(out)) if p.returncode == 0 else {}


def main():
    args = pvbatch_main.required_options("plugin", "step", "cli", "out")
    LoadPlugin(args.plugin, ns=globals())
    reader = OpenDataFile(args.step)
    UpdatePipeline(proxy=reader)

    # Regions.
    j = cli_json(args.cli, os.path.join(args.out, "findings_thickness.json"), "thickness", args.step,
                 "--per", "face", "--min", "3", "--max", "5")
    thickness = PierceThickness(Input=reader, SampleAt="Cells", MinThickness=3.0, MaxThickness=5.0)  # noqa: F821
    data = servermanager.Fetch(thickness)
    rows = field_rows(data, ["RegionThick", "RegionSolid", "RegionThickness", "RegionArea", "RegionSamples",
                             "RegionPoint", "RegionExit"])
    cli_rows = [(0, g, "min_thickness") for g in j.get("thin_regions", [])] + \
               [(1, g, "max_thickness") for g in j.get("thick_regions", [])]
    check(len(cli_rows) > 0, "the CLI finds regions: %d thin, %d thick" % (
        len(j.get("thin_regions", [])), len(j.get("thick_regions", []))))
    check(len(rows) == len(cli_rows), "ParaView lists %d regions, the CLI %d" % (len(rows), len(cli_rows)))
    for k, (row, (thick, g, key)) in enumerate(zip(rows, cli_rows)):
        ok = (row[0] == thick and row[1] == g["solid"] and same(row[2], g[key]) and same(row[3], g["area"]) and
              row[4] == g["samples"] and all(same(a, b) for a, b in zip(row[5], g["point"])) and
              all(same(a, b) for a, b in zip(row[6], g["exit"])))
        check(ok, "region %d: ParaView %s, CLI %s" % (k, row, g))
    # The Region ids on the surfaces count each region's samples.
    counts = {}
    for i in range(data.GetNumberOfBlocks()):
        block = data.GetBlock(i)
        region = block.GetCellData().GetArray("Region") if block else None
        if region is None:
            continue
        for c in range(region.GetNumberOfTuples()):
            r = int(region.GetTuple1(c))
            if r >= 0:
                counts[r] = counts.get(r, 0) + 1
    check(all(counts.get(k, 0) == row[4] for k, row in enumerate(rows)) and len(counts) == len(rows),
          "Region ids on the cells match the table: %s" % counts)
    # docs/PARAVIEW.md's recipe: Threshold on Region extracts one region's cells.
    if rows:
        from paraview.simple import Threshold
        k = len(rows) - 1
        region = Threshold(Input=thickness, Scalars=["CELLS", "Region"], LowerThreshold=k, UpperThreshold=k,
                           ThresholdMethod="Between")
        cells = servermanager.Fetch(region)
        n = sum(cells.GetBlock(i).GetNumberOfCells() for i in range(cells.GetNumberOfBlocks())
                if cells.GetBlock(i) is not None)
        check(n == rows[k][4], "Threshold on Region = %d extracts its %d cells: %d" % (k, rows[k][4], n))
    colour = data.GetFieldData().GetArray("ThicknessColorRange")
    check(colour is not None and colour.GetTuple(0) == (0.0, 12.0),
          "ThicknessColorRange 0 to 4 x Min Thickness: %s" % (colour and colour.GetTuple(0),))

    # Pairs.
    j = cli_json(args.cli, os.path.join(args.out, "findings_overlaps.json"), "overlaps", args.step,
                 "--clearance", "1", "--rays", "axes:n=32")
    overlaps = PierceOverlaps(Input=reader, RaysPerAxis=32, Clearance=1.0)  # noqa: F821
    data = servermanager.Fetch(overlaps)
    rows = field_rows(data, ["PairKind", "PairSolidA", "PairSolidB", "PairGap", "PairDepth", "PairPoint"])
    cli_pairs = j.get("pairs", [])
    check(len(cli_pairs) > 0 and {p["kind"] for p in cli_pairs} >= {"clash", "contact"},
          "the CLI finds pairs: %s" % [(p["kind"], p["solid_a"], p["solid_b"]) for p in cli_pairs])
    check(len(rows) == len(cli_pairs), "ParaView lists %d pairs, the CLI %d" % (len(rows), len(cli_pairs)))
    for row, p in zip(rows, cli_pairs):
        ok = (row[0] == p["kind"] and row[1] == p["solid_a"] and row[2] == p["solid_b"] and
              same(row[3], p["gap"]) and same(row[4], p["depth"]) and
              all(same(a, b) for a, b in zip(row[5], p["point"] or [None] * 3)))
        check(ok, "pair %s: ParaView %s, CLI %s" % (p["kind"], row, p))

    return pvbatch_main.status()


if __name__ == "__main__":
    pvbatch_main.run(main)
