"""pierce_vtk.report: the HTML report of `pierce report` (docs/REPORT.md) from ParaView (pvpython,
the Python shell) or from VTK data.

    from pierce_vtk import report
    report("part.html", min_thickness=1.0)               # the active pipeline object (pvpython)
    report("part.html", source=polydata, clearance=0.5)  # a vtkPolyData or multiblock of them
"""


def report(path, source=None, **options):
    """Writes the report to `path` and returns it. `source`: a ParaView pipeline object (default:
    the active one), or a vtkDataObject. For a pipeline object, the files its readers upstream
    read are reported (so CAD files keep their exact B-rep); a pipeline without a reader is
    reported from the surface the object outputs, one solid per block. `options`: the keyword
    arguments of pierce.report (min_thickness, max_thickness, clearance, method, per, kernel,
    title, force)."""
    import pierce
    if source is None or _is_proxy(source):
        from paraview import simple
        proxy = source if source is not None else simple.GetActiveSource()
        if proxy is None:
            raise ValueError("no active pipeline object: select one, or pass source=")
        files = _reader_files(proxy)
        if files:
            return pierce.report(files, path, **options)
        source = simple.servermanager.Fetch(proxy)
    return pierce.report(_scene_of(source), path, **options)


def _is_proxy(obj):
    return hasattr(obj, "ListProperties") and hasattr(obj, "SMProxy")


def _reader_files(proxy):
    """The files read by the readers upstream of `proxy` (itself included), each once, in order."""
    files, seen, todo = [], set(), [proxy]
    while todo:
        p = todo.pop(0)
        if id(p) in seen:
            continue
        seen.add(id(p))
        props = p.ListProperties()
        for name in ("FileName", "FileNames"):
            if name in props:
                value = p.GetPropertyValue(name)
                for f in [value] if isinstance(value, str) else list(value or []):
                    if f and f not in files:
                        files.append(f)
        if "Input" in props:
            inputs = p.Input  # a proxy, or for filters taking several an InputProperty listing them
            if _is_proxy(inputs):
                todo.append(inputs)
            elif inputs is not None:
                todo += [inputs[i] for i in range(len(inputs))]
    return files


def _scene_of(data):
    """A pierce.Scene with one geometry per surface block of `data` (triangulated), named after
    the block where the multiblock names it."""
    import numpy as np
    import pierce
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkDataObjectTree
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter
    from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter

    blocks = []
    if isinstance(data, vtkDataObjectTree):
        it = data.NewTreeIterator()
        it.VisitOnlyLeavesOn()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            meta = it.GetCurrentMetaData()
            name = meta.Get(vtkCompositeDataSet.NAME()) if meta is not None and meta.Has(vtkCompositeDataSet.NAME()) else ""
            blocks.append((name or "block%d" % len(blocks), it.GetCurrentDataObject()))
            it.GoToNextItem()
    else:
        blocks.append(("", data))
    scene = pierce.Scene()
    for name, block in blocks:
        surface = vtkDataSetSurfaceFilter()
        surface.SetInputData(block)
        triangles = vtkTriangleFilter()
        triangles.SetInputConnection(surface.GetOutputPort())
        triangles.PassLinesOff()
        triangles.PassVertsOff()
        triangles.Update()
        out = triangles.GetOutput()
        if out.GetNumberOfPolys() == 0:
            continue
        points = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)
        polys = vtk_to_numpy(out.GetPolys().GetConnectivityArray()).reshape(-1, 3)
        scene.add_mesh(points, polys, name=name)
    if len(scene) == 0:
        raise ValueError("the data has no surface to report on")
    return scene
