"""One Pierce pipeline, run by pv_mpi_check.py both serially (pvbatch) and under
`mpiexec -n 2 pvbatch --symmetric`: reader -> D3 -> Pierce filter. Every rank writes its own
output piece (every point or cell value with its identity) and its table to OUT/rank<r>.json.

    pvbatch --symmetric pv_mpi_case.py --plugin P.so --cases sphere,step,plates,csg --data DIR --out OUT

writes OUT/<case>/rank<r>.json.

Cases (inputs written to DATA by `--make-inputs`, serially, before the runs):
  sphere  hollow sphere (two concentric UV spheres, wall 0.1), thickness per point and per cell
          with thin regions below 0.1, and per point after a ghost layer (every point compared)
  step    the bundled STEP assembly (Pierce CAD reader), thickness per cell
  brep    MODELS/thin_plate.brep (pierce_make_test_models: a 0.3 sheet with blended edges) through
          the CAD reader: thickness per point and per cell on the exact B-rep, whose minimum is
          0.3 where the bare mesh reads 0.07
  plates  samples/plates.obj as ten blocks (touching plates), overlaps
  lines   line cells only (bad input): refused with an error on every rank
  volume  a Wavelet volume spread by D3 (its pieces' boundaries include the cut): refused
  limit   the hollow sphere with MaxReplicatedMB = 0.5 (refused on 2 ranks)
  csg     two overlapping spheres (two blocks), ray classification of 2 x 64 line rays read
          from a two-piece .pvtp (each rank shoots its piece)
"""
import argparse
import json
import os
import struct

from paraview.simple import (D3, GhostCellsGenerator, LoadPlugin, Wavelet, XMLMultiBlockDataReader, XMLPartitionedPolydataReader,
                             XMLPolyDataReader)
from vtkmodules.vtkParallelCore import vtkMultiProcessController


# Thin thresholds for the hollow sphere, at about the 30th percentile of its samples.
SPHERE_THIN = {"Points": 0.099997, "Cells": 0.09978}


def make_inputs(data, samples):
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkMultiBlockDataSet, vtkPolyData
    from vtkmodules.vtkFiltersCore import vtkAppendPolyData
    from vtkmodules.vtkFiltersSources import vtkSphereSource
    from vtkmodules.vtkFiltersCore import vtkReverseSense
    from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataWriter, vtkXMLPolyDataWriter

    def sphere(radius, center=(0, 0, 0), res=48):
        s = vtkSphereSource()
        s.SetRadius(radius)
        s.SetCenter(*center)
        s.SetThetaResolution(res)
        s.SetPhiResolution(res)
        s.Update()
        return s.GetOutput()

    def write_vtp(poly, path):
        w = vtkXMLPolyDataWriter()
        w.SetInputData(poly)
        w.SetDataModeToBinary()
        w.SetFileName(path)
        w.Write()

    def write_vtm(blocks, path):
        mb = vtkMultiBlockDataSet()
        for i, (name, poly) in enumerate(blocks):
            mb.SetBlock(i, poly)
            mb.GetMetaData(i).Set(mb.NAME(), name)
        w = vtkXMLMultiBlockDataWriter()
        w.SetInputData(mb)
        w.SetDataModeToBinary()
        w.SetFileName(path)
        w.Write()

    # Hollow sphere: outer r = 1 outward, inner r = 0.9 wound inward.
    inner = vtkReverseSense()
    inner.SetInputData(sphere(0.9))
    inner.Update()
    shell = vtkAppendPolyData()
    shell.AddInputData(sphere(1.0))
    shell.AddInputData(inner.GetOutput())
    shell.Update()
    write_vtp(shell.GetOutput(), os.path.join(data, "shell.vtp"))

    # Ten touching plates, one block each, from the OBJ sample.
    vertices, groups = [], []
    with open(os.path.join(samples, "plates.obj")) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                vertices.append(tuple(float(x) for x in w[1:4]))
            elif w[0] == "o":
                groups.append((w[1], []))
            elif w[0] == "f":
                groups[-1][1].append([int(x.split("/")[0]) - 1 for x in w[1:]])
    blocks = []
    for name, faces in groups:
        used = sorted({i for f in faces for i in f})
        local = {v: k for k, v in enumerate(used)}
        pts = vtkPoints()
        pts.SetDataTypeToDouble()
        for v in used:
            pts.InsertNextPoint(vertices[v])
        cells = vtkCellArray()
        for f in faces:
            cells.InsertNextCell(len(f), [local[i] for i in f])
        poly = vtkPolyData()
        poly.SetPoints(pts)
        poly.SetPolys(cells)
        blocks.append((name, poly))
    write_vtm(blocks, os.path.join(data, "plates.vtm"))

    # Two overlapping spheres and two pieces of line rays through them.
    write_vtm([("left", sphere(1.0, (-0.5, 0, 0), 32)), ("right", sphere(1.0, (0.5, 0, 0), 32))],
              os.path.join(data, "csg.vtm"))
    pieces = []
    for piece in range(2):
        pts = vtkPoints()
        pts.SetDataTypeToDouble()
        lines = vtkCellArray()
        for k in range(64):
            y = -0.95 + 1.9 * (piece * 64 + k) / 127.0
            a = pts.InsertNextPoint(-3.0, y, 0.01 * k)
            b = pts.InsertNextPoint(3.0, y, 0.01 * k)
            lines.InsertNextCell(2, [a, b])
        poly = vtkPolyData()
        poly.SetPoints(pts)
        poly.SetLines(lines)
        name = "rays_%d.vtp" % piece
        write_vtp(poly, os.path.join(data, name))
        pieces.append(name)
    with open(os.path.join(data, "rays.pvtp"), "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="PPolyData" version="1.0" byte_order="LittleEndian">\n'
                '<PPolyData GhostLevel="0">\n<PPoints><PDataArray type="Float64" NumberOfComponents="3"/>'
                '</PPoints>\n')
        for name in pieces:
            f.write('<Piece Source="%s"/>\n' % name)
        f.write('</PPolyData>\n</VTKFile>\n')


def bits(x):
    return struct.unpack("<q", struct.pack("<d", float(x)))[0]


def leaves(data):
    """(block name, polydata) of every leaf, or ("", data) for a data set."""
    if not data.IsA("vtkMultiBlockDataSet"):
        return [("", data)]
    out = []
    it = data.NewIterator()
    it.UnRegister(None)
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        name = it.GetCurrentMetaData().Get(data.NAME()) if it.HasCurrentMetaData() else ""
        out.append((name or "block %d" % it.GetCurrentFlatIndex(), it.GetCurrentDataObject()))
        it.GoToNextItem()
    return out


def records(data, arrays, per_cell):
    """Every point (keyed by its coordinates) or cell (keyed by its original id and its rank
    within that id) with the arrays' values as IEEE bit patterns."""
    out = []
    for name, piece in leaves(data):
        attributes = piece.GetCellData() if per_cell else piece.GetPointData()
        n = piece.GetNumberOfCells() if per_cell else piece.GetNumberOfPoints()
        original = piece.GetCellData().GetArray("vtkOriginalCellIds")
        seen = {}
        for e in range(n):
            if per_cell:
                oid = int(original.GetTuple1(e)) if original else e
                seq = seen.get(oid, 0)
                seen[oid] = seq + 1
                key = [name, oid, seq]
            else:  # every point, ghost points and points no cell of this rank uses included
                key = [name] + [bits(x) for x in piece.GetPoint(e)]
            values = []
            for a in arrays:
                array = attributes.GetArray(a)
                values.append(None if array is None else bits(array.GetTuple1(e)))
            out.append([key, values])
    return out


def table_rows(table):
    rows = []
    for r in range(table.GetNumberOfRows()):
        row = []
        for c in range(table.GetNumberOfColumns()):
            column = table.GetColumn(c)
            if column.IsA("vtkStringArray"):
                row.append(column.GetValue(r))
            else:
                row.append([bits(column.GetComponent(r, k)) for k in range(column.GetNumberOfComponents())])
        rows.append(row)
    return rows


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--plugin", required=True)
    p.add_argument("--cases", default="sphere,step,brep,plates,csg,limit,lines,volume")
    p.add_argument("--data", required=True)
    p.add_argument("--samples")
    p.add_argument("--models")
    p.add_argument("--out")
    p.add_argument("--make-inputs", action="store_true")
    args = p.parse_args()
    if args.make_inputs:
        make_inputs(args.data, args.samples)
        return
    LoadPlugin(args.plugin, ns=globals())
    controller = vtkMultiProcessController.GetGlobalController()
    rank = controller.GetLocalProcessId() if controller else 0
    for case in args.cases.split(","):
        out = os.path.join(args.out, case)
        os.makedirs(out, exist_ok=True)
        with open(os.path.join(out, "rank%d.json" % rank), "w") as f:
            json.dump(run_case(case, args, rank), f)


def run_case(case, args, rank):
    runs = []
    if case in ("lines", "volume"):  # bad input: a clear error on every rank, no hang
        if case == "lines":  # line cells only
            model = D3(Input=XMLPolyDataReader(FileName=[os.path.join(args.data, "rays_0.vtp")]))
        else:  # a volume split between the ranks: its pieces' boundaries include the cut
            model = D3(Input=Wavelet(WholeExtent=[0, 10, 0, 10, 0, 10]))
        proxy = PierceThickness(Input=model)
        proxy.UpdatePipeline()
        output = proxy.GetClientSideObject().GetOutputDataObject(0)
        return {"rank": rank, "cells": output.GetNumberOfCells()}
    if case == "limit":  # 1.7 MB replicated, limit 0.5 MB: refused under MPI, ignored in serial
        model = D3(Input=XMLPolyDataReader(FileName=[os.path.join(args.data, "shell.vtp")]))
        proxy = PierceThickness(Input=model, MaxReplicatedMB=0.5)
        proxy.UpdatePipeline()
        output = proxy.GetClientSideObject().GetOutputDataObject(0)
        return {"rank": rank, "cells": output.GetNumberOfCells()}
    if case == "sphere":
        model = D3(Input=XMLPolyDataReader(FileName=[os.path.join(args.data, "shell.vtp")]))
        for at in ("Points", "Cells"):
            # Near the shell's wall of 0.1: about 30 % of the samples are thin, in many regions.
            runs.append((at, PierceThickness(Input=model, SampleAt=at, MinThickness=SPHERE_THIN[at]),
                         ["Thickness", "ThicknessStatus", "Thin", "SolidId", "Region"], at == "Cells"))
        # With a layer of ghost cells on each piece: the filter leaves the ghost cells out, and
        # the points only they use carry the serial values too (a no-op in serial).
        ghosts = GhostCellsGenerator(Input=model, BuildIfRequired=0)
        runs.append(("ghost points", PierceThickness(Input=ghosts, MinThickness=SPHERE_THIN["Points"]),
                     ["Thickness", "ThicknessStatus", "Thin", "SolidId", "Region"], False))
    elif case == "step":
        model = D3(Input=PierceCADReader(FileName=os.path.join(args.samples, "plate_assembly.step")))
        runs.append(("cells", PierceThickness(Input=model, SampleAt="Cells", MinThickness=3.0),
                     ["Thickness", "ThicknessStatus", "Thin", "SolidId", "Region"], True))
    elif case == "brep":
        model = D3(Input=PierceCADReader(FileName=os.path.join(args.models, "thin_plate.brep")))
        for at in ("Points", "Cells"):
            runs.append((at, PierceThickness(Input=model, SampleAt=at),
                         ["Thickness", "ThicknessStatus", "Thin", "SolidId", "BRepFaces"], at == "Cells"))
    elif case == "plates":
        model = D3(Input=XMLMultiBlockDataReader(FileName=[os.path.join(args.data, "plates.vtm")]))
        runs.append(("overlaps", PierceOverlaps(Input=model, RaysPerAxis=24),
                     ["OverlapCount", "CoplanarCount", "CoplanarPartner", "CoplanarHits", "InterferenceHits",
                      "SolidId"], True))
    else:
        model = D3(Input=XMLMultiBlockDataReader(FileName=[os.path.join(args.data, "csg.vtm")]))
        rays = XMLPartitionedPolydataReader(FileName=[os.path.join(args.data, "rays.pvtp")])
        runs.append(("classify", PierceRayClassify(Input=model, Rays=rays, IncludeGaps=1), None, True))
    result = {"rank": rank, "runs": {}}
    for label, proxy, arrays, per_cell in runs:
        proxy.UpdatePipeline()
        algorithm = proxy.GetClientSideObject()
        surfaces = algorithm.GetOutputDataObject(0)
        table = algorithm.GetOutputDataObject(1)
        if arrays is None:  # partitions: one cell per partition, keyed by ray and entry
            keyed = []
            cd = surfaces.GetCellData()
            names = [cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())]
            for c in range(surfaces.GetNumberOfCells()):
                key = [int(cd.GetArray("RayId").GetTuple1(c)), bits(cd.GetArray("TIn").GetTuple1(c))]
                keyed.append([key, [bits(cd.GetArray(n).GetTuple1(c)) for n in names]])
            items = keyed
        else:
            items = records(surfaces, arrays, per_cell)
        result["runs"][label] = {"items": items, "table": table_rows(table), "per_cell": per_cell,
                                 "columns": {table.GetColumnName(c): [table.GetColumn(c).GetTuple1(r)
                                                                     for r in range(table.GetNumberOfRows())]
                                             for c in range(table.GetNumberOfColumns())
                                             if table.GetColumn(c).IsA("vtkDataArray")}}
    return result


if __name__ == "__main__":
    main()
