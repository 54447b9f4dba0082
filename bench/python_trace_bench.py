"""pierce.trace on NumPy arrays beside the C++ batch (trace_batch) on the same scene and rays.

Writes gen.blob(subdivisions) as an OBJ file, loads it in Python with pierce.load and in
pierce_bench_batch with --mesh (the same reader), and takes the same rays on both sides from the
generator 'random:n=N,seed=1' (pierce.load_rays, --ray-spec). Per repetition it runs
pierce_bench_batch once (--reps 1, on all cores, like pierce.trace) and then times pierce.trace on
(N, 3) float64 arrays for the same rows: the default kernel, first hit and all hits. Prints the
medians and pierce.trace / C++ batch: what the Python call adds (validation, the hits copied into
a structured array, the GIL released and re-taken). A bench, not a test.

    /usr/bin/python3 bench/python_trace_bench.py --bench build/bin/pierce_bench_batch
    (with PYTHONPATH=build/python)
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import pierce


def write_obj(mesh, path):
    with open(path, "w") as f:
        for v in mesh.vertices:
            f.write("v %r %r %r\n" % tuple(float(x) for x in v))
        for t in mesh.triangles:
            f.write("f %d %d %d\n" % tuple(int(i) + 1 for i in t))


def batch_ms(bench, obj, spec, threads, kernel):
    """{max_hits: ms} of the C++ batch rows of `kernel` in one pierce_bench_batch run."""
    out = subprocess.run([bench, "--mesh", obj, "--ray-spec", spec, "--reps", "1", "--threads", str(threads)],
                         check=True, capture_output=True, text=True).stdout
    rows = {}
    for line in out.splitlines():
        m = re.match(r"(\S+)\s+(1|all)\s+([0-9.]+)\s", line)
        if m and m.group(1) == kernel:
            rows[1 if m.group(2) == "1" else 0] = float(m.group(3))
    if len(rows) != 2:
        sys.exit("no rows for kernel %s in the output of %s:\n%s" % (kernel, bench, out))
    return rows


def cpu_times():
    """(steal, total) jiffies from the first line of /proc/stat (cpu user nice system idle iowait irq softirq steal)."""
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:9]]
    return v[7], sum(v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bench", required=True, help="path of pierce_bench_batch")
    ap.add_argument("--rays", type=int, default=200000)
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--subdivisions", type=int, default=6, help="gen.blob subdivisions")
    args = ap.parse_args()
    threads = os.cpu_count() or 1
    kernel = pierce.DEFAULT_KERNEL
    spec = "random:n=%d,seed=1" % args.rays
    load = "%.2f %.2f %.2f" % os.getloadavg()
    steal0, total0 = cpu_times()
    with tempfile.TemporaryDirectory() as tmp:
        obj = os.path.join(tmp, "blob.obj")
        write_obj(pierce.gen.blob(args.subdivisions), obj)
        scene = pierce.load(obj)
        org, d, tmin, tmax = pierce.load_rays(spec, scene)
        assert org.dtype == np.float64 and org.flags.c_contiguous
        pierce.trace(scene, org, d, tmin=tmin, tmax=tmax, kernel=kernel)  # builds the BVH, warms up
        cpp = {1: [], 0: []}
        py = {1: [], 0: []}
        for _ in range(args.reps):
            for n, ms in batch_ms(args.bench, obj, spec, threads, kernel).items():
                cpp[n].append(ms)
            for n in (1, 0):
                t0 = time.perf_counter()
                h = pierce.trace(scene, org, d, tmin=tmin, tmax=tmax, kernel=kernel, max_hits=n)
                py[n].append(1e3 * (time.perf_counter() - t0))
                assert len(h) == len(org)
    steal1, total1 = cpu_times()
    print("python_trace_bench: gen.blob(%d), %d triangles, %d rays (%s), kernel %s, %d thread(s), %d reps, load %s"
          % (args.subdivisions, scene.triangle_count, len(org), spec, kernel, threads, args.reps, load))
    print("%-6s %14s %16s %8s" % ("N", "C++ batch ms", "pierce.trace ms", "ratio"))
    for n in (1, 0):
        c, p = statistics.median(cpp[n]), statistics.median(py[n])
        print("%-6s %14.2f %16.2f %8.2f" % ("1" if n == 1 else "all", c, p, p / c))
    print("stolen by the hypervisor during the run: %.0f %%" % (100.0 * (steal1 - steal0) / max(1, total1 - total0)))


if __name__ == "__main__":
    main()
