"""pvbatch test: load the built plugin, open the STEP assembly through the plugin's CAD reader and
check each filter's arrays against the assembly's known geometry (tests/vtk/step_assembly.h):

    plate  [0,10] x [0,10] x [0,2]     block, block#2: 2 x 2 x 2 on the plate's top
    clash  [6,8] x [6,8] x [1.5,3.5]   sunk 0.5 into the plate

    pvbatch test_pv_filters.py --plugin PierceParaView.so --step assembly.step
"""
import os
import sys

from paraview.simple import LoadPlugin, Line, OpenDataFile, Plane, UpdatePipeline
from paraview import servermanager

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pvbatch_main
from pvbatch_main import check  # noqa: E402

def near(a, b, tol=1e-6):
    return abs(a - b) <= tol


def blocks_by_name(multiblock):
    out = {}
    for i in range(multiblock.GetNumberOfBlocks()):
        out[multiblock.GetMetaData(i).Get(multiblock.NAME())] = multiblock.GetBlock(i)
    return out


def cell_values(polydata, name):
    array = polydata.GetCellData().GetArray(name)
    check(array is not None, "missing cell array " + name)
    return [array.GetTuple1(i) for i in range(array.GetNumberOfTuples())] if array else []


def column(table, name):
    array = table.GetColumnByName(name)
    check(array is not None, "missing table column " + name)
    return [array.GetVariantValue(i).ToString() for i in range(table.GetNumberOfRows())] if array else []


def main():
    args = pvbatch_main.required_options("plugin", "step")

    LoadPlugin(args.plugin, ns=globals())

    # Reader chosen by extension through the plugin's ReaderFactory hint.
    reader = OpenDataFile(args.step)
    check(reader is not None and reader.GetXMLName() == "PierceCADReader",
          "STEP file not opened by PierceCADReader: %r" % (reader and reader.GetXMLName()))
    UpdatePipeline(proxy=reader)
    solids = blocks_by_name(servermanager.Fetch(reader))
    check(sorted(solids) == ["plate_assy/block", "plate_assy/block#2", "plate_assy/clash", "plate_assy/plate"],
          "solid names: %s" % sorted(solids))

    # Thickness per triangle: each part's own width whatever touches or pierces it.
    thickness = PierceThickness(Input=reader, SampleAt="Cells", MinThickness=3.0)  # noqa: F821
    result = blocks_by_name(servermanager.Fetch(thickness))
    plate = cell_values(result["plate_assy/plate"], "Thickness")
    check(len(plate) > 0 and all(near(v, 2.0) or near(v, 10.0) for v in plate), "plate thickness %s" % plate)
    check(any(near(v, 2.0) for v in plate) and any(near(v, 10.0) for v in plate), "plate has both widths")
    thin = cell_values(result["plate_assy/plate"], "Thin")
    check([t == 1.0 for t in thin] == [near(v, 2.0) for v in plate], "Thin flags where thickness < 3")
    for name in ("plate_assy/block", "plate_assy/block#2", "plate_assy/clash"):
        values = cell_values(result[name], "Thickness")
        check(all(near(v, 2.0) for v in values), "%s thickness %s" % (name, values))
    stats = servermanager.Fetch(thickness, None, None, 1)
    check(stats.GetNumberOfRows() == 4, "statistics rows %d" % stats.GetNumberOfRows())

    # Overlaps: plate/clash interfere by 0.5; plate/block touch (contact + coplanar, no interference).
    overlaps = PierceOverlaps(Input=reader, RaysPerAxis=24)  # noqa: F821
    UpdatePipeline(proxy=overlaps)
    pairs = servermanager.Fetch(overlaps, None, None, 1)
    kinds = column(pairs, "Kind")
    a_names, b_names = column(pairs, "NameA"), column(pairs, "NameB")
    rows = {(k, a, b): i for i, (k, a, b) in enumerate(zip(kinds, a_names, b_names))}
    key = ("interference", "plate_assy/plate", "plate_assy/clash")
    check(key in rows, "plate/clash interference reported: %s" % sorted(rows))
    if key in rows:
        penetration = pairs.GetValueByName(rows[key], "Penetration").ToDouble()
        check(near(penetration, 0.5), "plate/clash penetration %g" % penetration)
    check(("interference", "plate_assy/plate", "plate_assy/block") not in rows, "touching is not interference")
    check(("contact", "plate_assy/plate", "plate_assy/block") in rows, "plate/block contact")
    check(("coplanar", "plate_assy/plate", "plate_assy/block#2") in rows, "plate/block#2 coplanar faces")
    surfaces = blocks_by_name(servermanager.Fetch(overlaps))
    check(max(cell_values(surfaces["plate_assy/clash"], "InterferenceHits")) > 0, "clash interference hits")
    partners = cell_values(surfaces["plate_assy/block"], "CoplanarPartner")
    check(partners.count(0.0) >= 1, "block's bottom has the plate as coplanar partner: %s" % partners)

    # Ray classification: a vertical line through plate and clash, one through plate and block.
    through_clash = Line(Point1=[7, 7, -1], Point2=[7, 7, 5])
    classify = PierceRayClassify(Input=reader, Rays=through_clash)  # noqa: F821
    segments = servermanager.Fetch(classify)
    depth = cell_values(segments, "Depth")
    count = cell_values(segments, "SolidCount")
    check(len(depth) == 3, "3 partitions through plate and clash, got %d" % len(depth))
    if len(depth) == 3:
        check(near(depth[0], 1.5) and near(depth[1], 0.5) and near(depth[2], 1.5), "depths %s" % depth)
        check(count == [1.0, 2.0, 1.0], "solid counts %s" % count)
    through_block = Line(Point1=[2, 2, -1], Point2=[2, 2, 5])
    classify.Rays = through_block
    segments = servermanager.Fetch(classify)
    t_in, t_out = cell_values(segments, "TIn"), cell_values(segments, "TOut")
    check(len(t_in) == 2 and t_out[0] == t_in[1], "plate and block adjacent: %s %s" % (t_in, t_out))
    table = servermanager.Fetch(classify, None, None, 1)
    check(column(table, "Names") == ["plate_assy/plate", "plate_assy/block"], "partition names")

    # Array selection: a plane's Normals as ray directions (the plane faces -z, above the plate).
    plane = Plane(Origin=[0.5, 0.5, 8], Point1=[0.5, 9.5, 8], Point2=[9.5, 0.5, 8], XResolution=3, YResolution=3)
    UpdatePipeline(proxy=plane)  # as in the GUI: the domain lists the arrays of an updated input
    classify.Rays = plane
    classify.UseDirectionArray = 1
    available = list(classify.GetProperty("DirectionArrayName").Available)
    check("Normals" in available, "direction array choices %s" % available)
    classify.DirectionArray = "Normals"
    segments = servermanager.Fetch(classify)
    # Along the default +z nothing lies above z = 8: every one of the 16 rays hitting the plate
    # proves the Normals were used.
    rays = set(cell_values(segments, "RayId"))
    check(len(rays) == 16, "rays along the plane's normals that hit: %d" % len(rays))

    return pvbatch_main.status()


if __name__ == "__main__":
    pvbatch_main.run(main)
