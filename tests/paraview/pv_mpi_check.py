"""ctest driver: the Pierce filters under `mpiexec -n 2 pvbatch` give exactly the serial arrays.

`--stage run` runs pv_mpi_case.py (all cases in one process, to pay pvbatch's start-up once)
serially, on 2 MPI ranks, and on 2 ranks with PIERCE_VTK_NO_GATHER=1 (each rank alone: the
behaviour before the fix). `--stage compare --case C` then compares every sample of case C:
the same set of samples (none missing; a cell on exactly one rank; a point shared by two ranks'
pieces with the same values), bit-identical values, rank 0's table equal to the serial table
and the other ranks' tables empty; and it requires the same comparison to fail for the run
without gathering, so that the check is known to be able to fail.

    python3 pv_mpi_check.py --stage run --pvbatch pvbatch --mpiexec mpiexec --plugin P.so \
        --samples samples --work DIR
    python3 pv_mpi_check.py --stage compare --case sphere --work DIR
"""
import argparse
import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
MPI_FLAGS = ["--allow-run-as-root", "--oversubscribe", "-n", "2"]


def run(cmd, env=None, timeout=240):
    print("+ " + " ".join(cmd), flush=True)
    r = subprocess.run(cmd, env=env, timeout=timeout, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(r.stdout[-4000:])
    if r.returncode != 0:
        sys.exit("FAIL: command exited with %d" % r.returncode)
    return r.stdout


def load(directory, ranks):
    return [json.load(open(os.path.join(directory, "rank%d.json" % r))) for r in range(ranks)]


def compare(serial, parallel):
    """Differences between the serial run and the ranks' runs (empty list: identical)."""
    problems = []
    for label, s in serial[0]["runs"].items():
        reference = {}
        for key, values in s["items"]:
            reference[json.dumps(key)] = values
        got = {}
        duplicates = 0
        for rank in parallel:
            for key, values in rank["runs"][label]["items"]:
                k = json.dumps(key)
                if k in got:
                    if s["per_cell"] or got[k] != values:
                        duplicates += 1
                    continue
                got[k] = values
        missing = [k for k in reference if k not in got]
        extra = [k for k in got if k not in reference]
        differ = [k for k in reference if k in got and got[k] != reference[k]]
        print("%s: %d serial samples, %d on the ranks (%s); %d missing, %d extra, %d repeated, %d differ" %
              (label, len(reference), len(got), "+".join(str(len(r["runs"][label]["items"])) for r in parallel),
               len(missing), len(extra), duplicates, len(differ)))
        if missing or extra or duplicates or differ:
            problems.append("%s: %d missing, %d extra, %d repeated, %d values differ" %
                            (label, len(missing), len(extra), duplicates, len(differ)))
        if parallel[0]["runs"][label]["table"] != s["table"]:
            problems.append("%s: rank 0's table differs from the serial table (%d vs %d rows)" %
                            (label, len(parallel[0]["runs"][label]["table"]), len(s["table"])))
        for rank in parallel[1:]:
            if rank["runs"][label]["table"]:
                problems.append("%s: rank %d's table is not empty" % (label, rank["rank"]))
        if not reference:
            problems.append("%s: the serial run has no samples" % label)
    return problems


FILTER = {"lines": "", "volume": "", "limit": "", "sphere": "Pierce Thickness", "step": "Pierce Thickness", "brep": "Pierce Thickness",
          "plates": "Pierce Overlaps",
          "csg": "Pierce Ray Classify"}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--stage", required=True, choices=["run", "compare"])
    p.add_argument("--pvbatch")
    p.add_argument("--mpiexec")
    p.add_argument("--plugin")
    p.add_argument("--case")
    p.add_argument("--samples")
    p.add_argument("--models")
    p.add_argument("--work", required=True)
    args = p.parse_args()
    dirs = {name: os.path.join(args.work, name) for name in ("data", "serial", "mpi", "no_gather")}
    if args.stage == "run":
        script = os.path.join(HERE, "pv_mpi_case.py")
        for d in dirs.values():
            os.makedirs(d, exist_ok=True)
        common = ["--plugin", args.plugin, "--data", dirs["data"], "--samples", args.samples, "--models", args.models]
        env = dict(os.environ)
        env.pop("PIERCE_VTK_NO_GATHER", None)
        run([args.pvbatch, script, "--make-inputs"] + common, env)
        run([args.pvbatch, script, "--out", dirs["serial"]] + common, env)
        log = run([args.mpiexec] + MPI_FLAGS + [args.pvbatch, "--symmetric", script, "--out", dirs["mpi"]] + common, env)
        with open(os.path.join(args.work, "mpi.log"), "w") as f:
            f.write(log)
        env["PIERCE_VTK_NO_GATHER"] = "1"
        run([args.mpiexec] + MPI_FLAGS + [args.pvbatch, "--symmetric", script, "--out", dirs["no_gather"]] + common,
            env)
        print("MPI runs done")
        return
    if args.case in ("lines", "volume"):
        with open(os.path.join(args.work, "mpi.log")) as f:
            log = f.read()
        ranks = load(os.path.join(dirs["mpi"], args.case), 2)
        message = {"lines": "has no polygons", "volume": "is a volume (3D cells) split between 2 ranks"}[args.case]
        print("2 ranks: %s cells; message %s" % ("+".join(str(r["cells"]) for r in ranks),
                                                 "found" if message in log else "missing"))
        if any(r["cells"] for r in ranks) or message not in log:
            sys.exit("FAIL: bad input was not refused with a message")
        print("MPI run matches serial: bad input refused on every rank")
        return
    if args.case == "limit":
        with open(os.path.join(args.work, "mpi.log")) as f:
            log = f.read()
        serial = load(os.path.join(dirs["serial"], "limit"), 1)
        ranks = load(os.path.join(dirs["mpi"], "limit"), 2)
        message = "takes about 1.7 MB on every rank, more than the limit of 0.5 MB (MaxReplicatedMB)"
        print("serial output: %d cells; 2 ranks: %s cells; message %s" %
              (serial[0]["cells"], "+".join(str(r["cells"]) for r in ranks), "found" if message in log else "missing"))
        if serial[0]["cells"] == 0 or any(r["cells"] for r in ranks) or message not in log:
            sys.exit("FAIL: the replication limit was not applied as it should")
        print("MPI run matches serial: limit refused with a message")
        return
    with open(os.path.join(args.work, "mpi.log")) as f:
        if FILTER[args.case] + " on 2 ranks: the replicated surface" not in f.read():
            sys.exit("FAIL: %s did not report a distributed run" % FILTER[args.case])
    serial = load(os.path.join(dirs["serial"], args.case), 1)
    problems = compare(serial, load(os.path.join(dirs["mpi"], args.case), 2))
    # Nothing measured twice: the thickness runs report how many samples each rank measured;
    # their sum is the number of distinct samples (run order of pv_mpi_case.py: sphere Points,
    # sphere Cells, sphere ghost points, step, brep Points, brep Cells).
    with open(os.path.join(args.work, "mpi.log")) as f:
        measured = [int(n) for n in re.findall(r"samples measured per rank: [0-9 +]+ = ([0-9]+)", f.read())]
    first = {"sphere": 0, "step": 3, "brep": 4}.get(args.case)
    if first is not None:
        for k, (label, serial_run) in enumerate(serial[0]["runs"].items()):
            n = measured[first + k] if first + k < len(measured) else None
            print("%s: %s samples measured by the ranks in all, %d distinct samples" %
                  (label, n, len(serial_run["items"])))
            if n != len(serial_run["items"]):
                problems.append("%s: the ranks measured %s samples, not %d: some twice or none" %
                                (label, n, len(serial_run["items"])))
    if args.case == "brep":  # on the exact B-rep: the sheet's 0.3, not the mesh's 0.07
        for label, serial_run in serial[0]["runs"].items():
            columns = serial_run["columns"]
            print("%s: OnBRep %s, min %s" % (label, columns.get("OnBRep"), columns.get("Min")))
            if columns.get("OnBRep") != [1.0] or not columns.get("Min") or abs(columns["Min"][0] - 0.3) > 1e-6:
                problems.append("%s: not measured on the exact B-rep (OnBRep %s, min %s, expected 0.3)" %
                                (label, columns.get("OnBRep"), columns.get("Min")))
    for problem in problems:
        print("FAIL: " + problem)
    if problems:
        sys.exit(1)
    if not compare(serial, load(os.path.join(dirs["no_gather"], args.case), 2)):
        sys.exit("FAIL: the check cannot fail: without gathering it still reports no difference")
    print("negative check: without gathering the comparison fails, as it must")
    print("MPI run matches serial: " + args.case)


main()
