"""ctest driver: the Pierce filters under `mpiexec -n 2 pvbatch` give exactly the serial arrays.

Runs pv_mpi_case.py serially and on 2 MPI ranks, then compares every sample: the same set of
samples (none missing; a cell on exactly one rank; a point shared by two ranks' pieces with the
same values), bit-identical values, and rank 0's table equal to the serial table (the other
ranks' tables empty). With --negative it also runs the MPI pipeline with PIERCE_VTK_NO_GATHER=1
(each rank alone, the behaviour before the fix) and requires the comparison to fail there.

    python3 pv_mpi_check.py --pvbatch pvbatch --mpiexec mpiexec --plugin P.so --case sphere \
        --samples samples --work DIR [--negative]
"""
import argparse
import json
import os
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


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--pvbatch", required=True)
    p.add_argument("--mpiexec", required=True)
    p.add_argument("--plugin", required=True)
    p.add_argument("--case", required=True)
    p.add_argument("--samples", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--negative", action="store_true")
    args = p.parse_args()
    script = os.path.join(HERE, "pv_mpi_case.py")
    data = os.path.join(args.work, "data")
    dirs = {name: os.path.join(args.work, args.case, name) for name in ("serial", "mpi", "no_gather")}
    for d in [data] + list(dirs.values()):
        os.makedirs(d, exist_ok=True)
    common = ["--plugin", args.plugin, "--case", args.case, "--data", data, "--samples", args.samples]
    env = dict(os.environ)
    env.pop("PIERCE_VTK_NO_GATHER", None)
    env["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    run([args.pvbatch, script, "--make-inputs"] + common, env)
    run([args.pvbatch, script, "--out", dirs["serial"]] + common, env)
    out = run([args.mpiexec] + MPI_FLAGS + [args.pvbatch, "--symmetric", script, "--out", dirs["mpi"]] + common, env)
    if "on 2 ranks: the replicated surface" not in out:
        sys.exit("FAIL: the filter did not report a distributed run")
    problems = compare(load(dirs["serial"], 1), load(dirs["mpi"], 2))
    for problem in problems:
        print("FAIL: " + problem)
    if problems:
        sys.exit(1)
    if args.negative:
        env["PIERCE_VTK_NO_GATHER"] = "1"
        run([args.mpiexec] + MPI_FLAGS + [args.pvbatch, "--symmetric", script, "--out", dirs["no_gather"]] + common,
            env)
        if not compare(load(dirs["serial"], 1), load(dirs["no_gather"], 2)):
            sys.exit("FAIL: the check cannot fail: without gathering it still reports no difference")
        print("negative check: without gathering the comparison fails, as it must")
    print("MPI run matches serial: " + args.case)


main()
