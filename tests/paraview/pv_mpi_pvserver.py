"""pvpython test: the way the GUI runs Pierce in parallel. Starts `mpiexec -n 2 pvserver` on a
free port, connects to it, loads the plugin on the server, runs reader -> D3 -> Pierce Thickness
(per cell) on the hollow sphere of pv_mpi_case.py, fetches the result (all ranks' pieces) and
compares it with the serial run that `pv_mpi_check.py --stage run` stored in WORK: every
triangle once, bit-identical values, the same statistics table. The server is killed at the end
whatever happens.

    pvpython pv_mpi_pvserver.py --mpiexec mpiexec --pvserver pvserver --plugin P.so --work WORK
"""
import json
import os
import signal
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pvbatch_main  # noqa: E402
from pv_mpi_case import SPHERE_THIN, records, table_rows  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import D3, Connect, Disconnect, LoadPlugin, XMLPolyDataReader  # noqa: E402


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def main():
    args = pvbatch_main.required_options("mpiexec", "pvserver", "plugin", "work")
    port = free_port()
    log_path = os.path.join(args.work, "pvserver.log")
    log = open(log_path, "w")
    # pvpython may itself run as an MPI singleton: its OpenMPI variables would confuse mpiexec.
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "PRTE_", "OPAL_"))}
    server = subprocess.Popen([args.mpiexec, "--allow-run-as-root", "--oversubscribe", "-n", "2", args.pvserver,
                               "--server-port=%d" % port, "--force-offscreen-rendering"],
                              stdout=log, stderr=subprocess.STDOUT, start_new_session=True, env=env)
    failures = []
    try:
        deadline = time.time() + 90
        while "Accepting connection" not in open(log_path).read():
            if server.poll() is not None or time.time() > deadline:
                sys.exit("FAIL: pvserver did not start:\n" + open(log_path).read())
            time.sleep(0.2)
        Connect("localhost", port)
        LoadPlugin(args.plugin, remote=True, ns=globals())
        model = D3(Input=XMLPolyDataReader(FileName=[os.path.join(args.work, "data", "shell.vtp")]))
        # As pv_mpi_case.py's sphere run per cell.
        thickness = PierceThickness(Input=model, SampleAt="Cells", MinThickness=SPHERE_THIN["Cells"])  # noqa: F821 (the plugin's)
        thickness.UpdatePipeline()
        surfaces = servermanager.Fetch(thickness, None, None)
        got = records(surfaces, ["Thickness", "ThicknessStatus", "Thin", "SolidId", "Region"], True)
        serial = json.load(open(os.path.join(args.work, "serial", "sphere", "rank0.json")))["runs"]["Cells"]
        reference = {json.dumps(k): v for k, v in serial["items"]}
        seen = {}
        repeated = 0
        for k, v in got:
            k = json.dumps(k)
            repeated += k in seen
            seen[k] = v
        missing = sum(1 for k in reference if k not in seen)
        differ = sum(1 for k in reference if k in seen and seen[k] != reference[k])
        print("pvserver: %d serial triangles, %d fetched; %d missing, %d repeated, %d differ" %
              (len(reference), len(got), missing, repeated, differ))
        if missing or repeated or differ or len(got) != len(reference):
            failures.append("fetched thickness differs from the serial run")
        statistics = table_rows(servermanager.Fetch(thickness, None, None, 1))
        print("pvserver: statistics table %s the serial one" % ("equals" if statistics == serial["table"] else "differs from"))
        if statistics != serial["table"]:
            failures.append("fetched statistics table differs from the serial run")
        Disconnect()
        time.sleep(0.5)
        text = open(log_path).read()
        if "Pierce Thickness on 2 ranks: the replicated surface" not in text:
            failures.append("the server did not report a distributed run:\n" + text)
    finally:
        if server.poll() is None:
            os.killpg(server.pid, signal.SIGTERM)
            try:
                server.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(server.pid, signal.SIGKILL)
    for f in failures:
        print("FAIL: " + f)
    if failures:
        sys.exit(1)
    print("pvserver run matches serial")


main()
