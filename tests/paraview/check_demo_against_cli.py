"""Runs the README's pvbatch demo (plugins/paraview/pierce_demo.py) and the `pierce` CLI on the same
model and checks that they agree: per-triangle thickness exactly, interference pairs (count, max
depth, penetration) and contact pairs.

    /usr/bin/python3 check_demo_against_cli.py --pvbatch pvbatch --demo pierce_demo.py \
        --plugin PierceParaView.so --pierce build/bin/pierce --model assembly.step --out DIR

The demo's .vtm/.vtp files are read here with the standard library (xml.etree + base64), not with
VTK's XML reader: Debian 12's VTK 9.2 reader feeds expat incrementally and stops it at an
<AppendedData> section, which Debian's expat 2.5.0-1+deb12u2 and later (reparse deferral, the
CVE-2023-52425 fix) do not honour, so files with raw appended data (ParaView's default) fail to read back with
"not well-formed (invalid token)" depending on where the data bytes fall. The demo writes inline
base64 (DataMode=Binary); this check asserts that (no <AppendedData>), so a regression is reported
as such instead of as an intermittent reader error, and it then parses the whole document in one go.
"""
import base64
import csv
import math
import os
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET
import zlib

import pvbatch_main

# VTK XML DataArray types -> struct format characters.
VTK_TYPES = {"Int8": "b", "UInt8": "B", "Int16": "h", "UInt16": "H", "Int32": "i", "UInt32": "I",
             "Int64": "q", "UInt64": "Q", "Float32": "f", "Float64": "d"}


def run(cmd):
    print("+ " + " ".join(cmd))
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(done.stdout[-4000:])
    if done.returncode != 0:
        raise SystemExit("command failed with status %d" % done.returncode)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


class VtkXmlError(Exception):
    pass


def parse_vtk_xml(path):
    """The root element of a VTK XML file with inline data, after checking it has no appended data."""
    with open(path, "rb") as f:
        data = f.read()
    if b"<AppendedData" in data:
        raise VtkXmlError("%s has an <AppendedData> section: the demo must write inline data "
                          "(DataMode=Binary), which every XML parser reads" % path)
    try:
        root = ET.fromstring(data)
    except ET.ParseError as e:
        raise VtkXmlError("%s is not well-formed XML (%s; %d bytes)" % (path, e, len(data)))
    if root.tag != "VTKFile":
        raise VtkXmlError("%s: root element is <%s>, not <VTKFile>" % (path, root.tag))
    return root


def decode_array(root, array, path):
    """The values of one inline DataArray (format ascii or binary, zlib-compressed or not)."""
    name, kind = array.get("Name"), array.get("type")
    fmt = array.get("format", "ascii")
    text = (array.text or "").strip()
    if kind not in VTK_TYPES:
        raise VtkXmlError("%s: array %s has unsupported type %s" % (path, name, kind))
    if fmt == "ascii":
        convert = float if kind.startswith("Float") else int
        return [convert(v) for v in text.split()]
    if fmt != "binary":
        raise VtkXmlError("%s: array %s has format %s (expected inline ascii or binary)" % (path, name, fmt))
    order = "<" if root.get("byte_order", "LittleEndian") == "LittleEndian" else ">"
    header = VTK_TYPES[root.get("header_type", "UInt32")]
    header_size = struct.calcsize(header)
    item = VTK_TYPES[kind]
    if root.get("compressor"):
        if root.get("compressor") != "vtkZLibDataCompressor":
            raise VtkXmlError("%s: unsupported compressor %s" % (path, root.get("compressor")))
        # Header (block count, block size, last block size, compressed sizes) and the compressed
        # blocks are two base64 streams one after the other.
        first = base64.b64decode(text[:4 * ((3 * header_size + 2) // 3)])
        blocks = struct.unpack(order + header, first[:header_size])[0]
        header_chars = 4 * (((3 + blocks) * header_size + 2) // 3)
        sizes = struct.unpack(order + header * (3 + blocks), base64.b64decode(text[:header_chars]))
        payload = base64.b64decode(text[header_chars:])
        raw, at = b"", 0
        for size in sizes[3:]:
            raw += zlib.decompress(payload[at:at + size])
            at += size
    else:
        blob = base64.b64decode(text)
        size = struct.unpack(order + header, blob[:header_size])[0]
        raw = blob[header_size:header_size + size]
        if len(raw) != size:
            raise VtkXmlError("%s: array %s is truncated (%d of %d bytes)" % (path, name, len(raw), size))
    count = len(raw) // struct.calcsize(item)
    return list(struct.unpack(order + item * count, raw[:count * struct.calcsize(item)]))


def cell_arrays(path):
    """{name: values} of the cell data of a .vtp file with one piece."""
    root = parse_vtk_xml(path)
    pieces = root.findall("./PolyData/Piece")
    if len(pieces) != 1:
        raise VtkXmlError("%s: %d pieces, expected 1" % (path, len(pieces)))
    arrays = {}
    for array in pieces[0].findall("./CellData/DataArray"):
        arrays[array.get("Name")] = decode_array(root, array, path)
    return arrays


def demo_thickness(path):
    """{(solid, triangle): thickness} from the demo's thickness.vtm (one block per solid)."""
    root = parse_vtk_xml(path)
    values = {}
    blocks = root.findall("./vtkMultiBlockDataSet/DataSet")
    if not blocks:
        raise VtkXmlError("%s: no blocks" % path)
    for block in blocks:
        solid = int(block.get("index"))
        arrays = cell_arrays(os.path.join(os.path.dirname(path), block.get("file")))
        if "Thickness" not in arrays:
            raise VtkXmlError("%s: block %d has no cell array Thickness" % (path, solid))
        for c, value in enumerate(arrays["Thickness"]):
            values[(solid, c)] = value
    return values


def demo_bounds(path):
    """(x0, x1, y0, y1, z0, z1) of every block's points in the demo's thickness.vtm: the model's
    bounds, which the demo's ray grid is built from."""
    root = parse_vtk_xml(path)
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for block in root.findall("./vtkMultiBlockDataSet/DataSet"):
        file = os.path.join(os.path.dirname(path), block.get("file"))
        sub = parse_vtk_xml(file)
        for array in sub.findall("./PolyData/Piece/Points/DataArray"):
            xyz = decode_array(sub, array, file)
            for i, v in enumerate(xyz):
                lo[i % 3], hi[i % 3] = min(lo[i % 3], v), max(hi[i % 3], v)
    return (lo[0], hi[0], lo[1], hi[1], lo[2], hi[2])


def demo_rays(bounds, n=16):
    """The demo's rays: the points of its Plane source (float coordinates, x fastest), along +z."""
    (x0, x1, y0, y1, z0, z1) = bounds
    margin = 0.01 * max(x1 - x0, y1 - y0, z1 - z0)
    origin = (x0 + margin, y0 + margin, z0 - margin)
    p1 = (x1 - margin, y0 + margin, z0 - margin)
    p2 = (x0 + margin, y1 - margin, z0 - margin)
    as_float = lambda v: struct.unpack("f", struct.pack("f", v))[0]  # noqa: E731
    rays = []
    for j in range(n + 1):
        for i in range(n + 1):
            rays.append(tuple(as_float(origin[k] + i / n * (p1[k] - origin[k]) + j / n * (p2[k] - origin[k]))
                              for k in range(3)))
    return rays


def compare_partitions(pv_rows, cli_rows, failures):
    """ParaView's partitions.csv against `pierce shot --format csv` on the same rays: per ray the
    same intervals (kind, solids), at the same distances."""
    def key(kind, names):
        return (kind, tuple(sorted(n for n in names.split("+") if n)))
    pv = {}
    for r in pv_rows:
        pv.setdefault(int(r["RayId"]), []).append((key(r["Kind"], r["Names"]), float(r["TIn"]), float(r["TOut"])))
    cli = {}
    for r in cli_rows:
        cli.setdefault(int(r["ray"]), []).append((key(r["kind"], r["solids"]), float(r["t_in"]), float(r["t_out"])))
    if sorted(pv) != sorted(cli):
        failures.append("rays with partitions: ParaView %d, CLI %d" % (len(pv), len(cli)))
    for ray in sorted(set(pv) & set(cli)):
        a, b = pv[ray], cli[ray]
        if [x[0] for x in a] != [x[0] for x in b]:
            failures.append("ray %d: ParaView %s, CLI %s" % (ray, [x[0] for x in a], [x[0] for x in b]))
            continue
        for (k, t0, t1), (_, u0, u1) in zip(a, b):
            if abs(t0 - u0) > 1e-9 or abs(t1 - u1) > 1e-9:
                failures.append("ray %d %s: ParaView [%r, %r], CLI [%r, %r]" % (ray, k, t0, t1, u0, u1))
    return len(pv_rows)


def vtk_reads(path):
    """Whether ParaView's own VTK reads the file back without an error (what a user opening it
    does); with inline data this does not depend on expat's chunking."""
    from vtkmodules.vtkIOXML import vtkXMLGenericDataObjectReader
    errors = []
    reader = vtkXMLGenericDataObjectReader()
    reader.AddObserver("ErrorEvent", lambda obj, event: errors.append(event))
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutputDataObject(0)
    if errors or data is None:
        return False
    return data.GetNumberOfBlocks() > 0 if data.IsA("vtkMultiBlockDataSet") else data.GetNumberOfCells() > 0


def same(a, b):
    return (math.isnan(a) and math.isnan(b)) or a == b


def main():
    args = pvbatch_main.required_options("pvbatch", "demo", "plugin", "pierce", "model", "out")
    os.makedirs(args.out, exist_ok=True)
    out = lambda name: os.path.join(args.out, name)  # noqa: E731

    run([args.pvbatch, args.demo, args.model, "--plugin", args.plugin, "--out", args.out, "--force"])
    run([args.pierce, "thickness", args.model, "--per", "face", "-o", out("cli_thickness.csv"), "--force"])
    run([args.pierce, "overlaps", args.model, "-o", out("cli_overlaps.csv"), "--force"])
    try:
        rays = demo_rays(demo_bounds(out("thickness.vtm")))
    except VtkXmlError as e:
        print("FAIL: %s" % e)
        return 1
    with open(out("cli_rays.csv"), "w") as f:
        for o in rays:
            f.write("%.17g,%.17g,%.17g,0,0,1\n" % o)
    run([args.pierce, "shot", args.model, "--rays", out("cli_rays.csv"), "--format", "csv",
         "-o", out("cli_shot.csv"), "--force"])

    failures = []
    try:
        vtk_values = demo_thickness(out("thickness.vtm"))
        partitions = cell_arrays(out("partitions.vtp"))
    except VtkXmlError as e:
        print("FAIL: %s" % e)
        return 1
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

    # The ray partitions file carries its arrays, one value per segment, as the demo's table.
    rows = read_csv(out("partitions.csv"))
    for name in ("RayId", "SolidId", "SolidCount", "Depth"):
        if name not in partitions:
            failures.append("partitions.vtp lacks " + name)
        elif len(partitions[name]) != len(rows):
            failures.append("partitions.vtp %s: %d values, partitions.csv %d rows" % (name, len(partitions[name]), len(rows)))
        else:
            for i, row in enumerate(rows):
                if float(row[name]) != float(partitions[name][i]):
                    failures.append("partition %d %s: vtp %r, csv %r" % (i, name, partitions[name][i], row[name]))
                    break

    # The partitions are the CLI's shotlines on the same rays.
    compared = compare_partitions(rows, read_csv(out("cli_shot.csv")), failures)
    if compared == 0:
        failures.append("the demo's rays should cross the model (no partitions)")

    # And VTK itself reads the XML files back (inline data: no expat chunking issue).
    for name in ("thickness.vtm", "overlaps.vtm", "partitions.vtp"):
        if not vtk_reads(out(name)):
            failures.append("VTK's XML reader cannot read " + name)

    for f in failures[:20]:
        print("FAIL: " + f)
    if failures:
        return 1
    print("ParaView demo and CLI agree on %d triangles, %d pairs and %d partitions" % (
        len(cli_rows), len(cli_pairs), compared))
    return 0


if __name__ == "__main__":
    sys.exit(main())
