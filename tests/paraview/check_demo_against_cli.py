"""Runs the README's pvbatch demo (plugins/paraview/pierce_demo.py) and the `pierce` CLI on the same
model and checks that they agree: per-triangle thickness exactly, interference pairs (count, max
depth, penetration) and contact pairs.

    /usr/bin/python3 check_demo_against_cli.py --pvbatch pvbatch --demo pierce_demo.py \
        --plugin PierceParaView.so --pierce build/bin/pierce --model assembly.step --out DIR
"""
import argparse
import csv
import math
import os
import subprocess
import sys

from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader, vtkXMLPolyDataReader


def run(cmd):
    print("+ " + " ".join(cmd))
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(done.stdout[-4000:])
    if done.returncode != 0:
        raise SystemExit("command failed with status %d" % done.returncode)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def demo_thickness(path):
    """{(solid, triangle): thickness} from the demo's thickness.vtm."""
    reader = vtkXMLMultiBlockDataReader()
    reader.SetFileName(path)
    reader.Update()
    mb = reader.GetOutput()
    values = {}
    for solid in range(mb.GetNumberOfBlocks()):
        array = mb.GetBlock(solid).GetCellData().GetArray("Thickness")
        for c in range(array.GetNumberOfTuples()):
            values[(solid, c)] = array.GetTuple1(c)
    return values


def same(a, b):
    return (math.isnan(a) and math.isnan(b)) or a == b


def main():
    p = argparse.ArgumentParser()
    for name in ("pvbatch", "demo", "plugin", "pierce", "model", "out"):
        p.add_argument("--" + name, required=True)
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    out = lambda name: os.path.join(args.out, name)  # noqa: E731

    run([args.pvbatch, args.demo, args.model, "--plugin", args.plugin, "--out", args.out, "--force"])
    run([args.pierce, "thickness", args.model, "--per", "face", "-o", out("cli_thickness.csv"), "--force"])
    run([args.pierce, "overlaps", args.model, "-o", out("cli_overlaps.csv"), "--force"])

    failures = []
    vtk_values = demo_thickness(out("thickness.vtm"))
    cli_rows = read_csv(out("cli_thickness.csv"))
    if len(cli_rows) != len(vtk_values):
        failures.append("%d CLI rows, %d triangles from ParaView" % (len(cli_rows), len(vtk_values)))
    for row in cli_rows:
        key = (int(row["solid"]), int(row["element"]))
        cli = float(row["thickness"])
        if key not in vtk_values or not same(vtk_values[key], cli):
            failures.append("thickness of solid %d triangle %d: CLI %r, ParaView %r" % (key + (cli, vtk_values.get(key))))

    cli_pairs = {(r["kind"], r["name_a"], r["name_b"]): r for r in read_csv(out("cli_overlaps.csv"))}
    pv_pairs = {(r["Kind"], r["NameA"], r["NameB"]): r for r in read_csv(out("overlap_pairs.csv"))}
    for kind in ("interference", "contact"):
        cli_keys = sorted(k for k in cli_pairs if k[0] == kind)
        pv_keys = sorted(k for k in pv_pairs if k[0] == kind)
        if cli_keys != pv_keys:
            failures.append("%s pairs: CLI %s, ParaView %s" % (kind, cli_keys, pv_keys))
            continue
        for k in cli_keys:
            if int(cli_pairs[k]["count"]) != int(pv_pairs[k]["Count"]):
                failures.append("%s count: CLI %s, ParaView %s" % (k, cli_pairs[k]["count"], pv_pairs[k]["Count"]))
            if kind == "interference":
                for cli_col, pv_col in (("max_depth", "MaxDepth"), ("penetration", "Penetration")):
                    a, b = float(cli_pairs[k][cli_col]), float(pv_pairs[k][pv_col])
                    if abs(a - b) > 1e-12 * max(1.0, abs(a)):
                        failures.append("%s %s: CLI %r, ParaView %r" % (k, cli_col, a, b))
    if not any(k[0] == "interference" for k in cli_pairs):
        failures.append("the model should have an interference (plate/clash)")

    # The ray partitions file is there and carries its arrays.
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(out("partitions.vtp"))
    reader.Update()
    cells = reader.GetOutput().GetCellData()
    for name in ("RayId", "SolidId", "SolidCount", "Depth"):
        if cells.GetArray(name) is None:
            failures.append("partitions.vtp lacks " + name)

    for f in failures[:20]:
        print("FAIL: " + f)
    if failures:
        return 1
    print("ParaView demo and CLI agree on %d triangles and %d pairs" % (len(cli_rows), len(cli_pairs)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
