"""Strong scaling of Pierce Thickness under MPI (a bench, not a test; docs/BENCHMARKS.md).

Writes a closed shell of two concentric UV spheres (radius 1 and 0.95, wound outward and inward;
2 x 2 x N x (N - 2) triangles, 1.63 M for the default N = 640) as a .vtp, then runs
reader -> D3 -> Pierce Thickness (per triangle) with pvbatch on 1 and 2 ranks, each rank bound
to one core (so one TBB thread per rank: the 2-rank run uses the cores the 1-rank run leaves
idle), `--repeat` times each, interleaved, and prints the filter's own stage times (slowest rank): gather
(surface extraction and, on 2 ranks, the exchange), BVH build, trace (wall clock, and the CPU
time of the busiest rank: the work split, whatever the load); median of the runs. The
machine's load (uptime) is printed before and after.

    /usr/bin/python3 bench/paraview_scaling.py --plugin build/lib/paraview-plugins/PierceParaView/PierceParaView.so
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

PIPELINE = r'''
import sys
from paraview.simple import D3, LoadPlugin, XMLPolyDataReader
LoadPlugin(sys.argv[1], ns=globals())
t = PierceThickness(Input=D3(Input=XMLPolyDataReader(FileName=[sys.argv[2]])), SampleAt="Cells")
t.UpdatePipeline()
for line in open("/proc/self/status"):
    if line.startswith("VmHWM"):
        print("peak memory " + line.split(":")[1].strip())
'''

MAKE = r'''
import sys
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkReverseSense
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
n = int(sys.argv[2])
def sphere(r):
    s = vtkSphereSource(); s.SetRadius(r); s.SetThetaResolution(n); s.SetPhiResolution(n); s.Update()
    return s.GetOutput()
inner = vtkReverseSense(); inner.SetInputData(sphere(0.95)); inner.Update()
a = vtkAppendPolyData(); a.AddInputData(sphere(1.0)); a.AddInputData(inner.GetOutput()); a.Update()
print("triangles", a.GetOutput().GetNumberOfCells())
w = vtkXMLPolyDataWriter(); w.SetInputData(a.GetOutput()); w.SetDataModeToBinary(); w.SetFileName(sys.argv[1]); w.Write()
'''

STAGE = re.compile(r"(gather|BVH build|trace) ([0-9.e+-]+) s \(CPU ([0-9.e+-]+) s\)")


def uptime():
    return subprocess.run(["uptime"], stdout=subprocess.PIPE, text=True).stdout.strip()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--plugin", required=True)
    p.add_argument("--pvbatch", default="pvbatch")
    p.add_argument("--mpiexec", default="mpiexec")
    p.add_argument("--resolution", type=int, default=640)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--work", default=tempfile.gettempdir())
    args = p.parse_args()
    model = os.path.join(args.work, "pierce_scaling_shell_%d.vtp" % args.resolution)
    script = os.path.join(args.work, "pierce_scaling_pipeline.py")
    with open(script, "w") as f:
        f.write(PIPELINE)
    if not os.path.exists(model):
        make = os.path.join(args.work, "pierce_scaling_make.py")
        with open(make, "w") as f:
            f.write(MAKE)
        subprocess.run([args.pvbatch, make, model, str(args.resolution)], check=True)
    print("model: %s" % model)
    print("load before: " + uptime())
    env = dict(os.environ, PIERCE_VTK_TIMING="1")
    runs_of = {1: [], 2: []}
    for _ in range(args.repeat):  # interleaved, so that a change of load falls on both alike
        for ranks in (1, 2):
            runs = runs_of[ranks]
            cmd = [args.mpiexec, "--allow-run-as-root", "--oversubscribe", "--bind-to", "core", "-n", str(ranks),
                   args.pvbatch, script, args.plugin, model]
            out = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
            found = STAGE.findall(out)
            stages = {name: float(v) for name, v, _ in found}
            stages.update({name + " CPU": float(c) for name, _, c in found})
            if len(stages) != 6:
                sys.exit("no stage times in the output of %s:\n%s" % (" ".join(cmd), out[-3000:]))
            runs.append(stages)
            peaks = re.findall(r"peak memory ([0-9]+) kB", out)
            print("  %d rank(s): gather %.3f s, BVH build %.3f s, trace %.3f s (CPU of the busiest rank %.3f s); peak "
                  "memory of rank 0 (pvbatch with D3 and the reader) %s MB" %
                  (ranks, stages["gather"], stages["BVH build"], stages["trace"], stages["trace CPU"],
                   int(peaks[0]) // 1024 if peaks else "?"), flush=True)
    results = {r: {k: statistics.median(x[k] for x in runs_of[r]) for k in ("gather", "BVH build", "trace", "trace CPU")}
               for r in (1, 2)}
    print("load after: " + uptime())
    print("| ranks | gather (s) | BVH build (s) | trace (s) | trace speed-up | trace CPU of the busiest rank (s) |")
    print("|---|---|---|---|---|---|")
    for ranks in (1, 2):
        r = results[ranks]
        print("| %d | %.3f | %.3f | %.3f | %.2f× | %.3f |" %
              (ranks, r["gather"], r["BVH build"], r["trace"], results[1]["trace"] / r["trace"], r["trace CPU"]))


main()
