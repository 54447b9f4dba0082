"""ParaView's messages read as plain text when stderr is not a terminal: pvbatch loads the plugin
and opens a file that is not STEP, with TERM naming a colour terminal and stderr a pipe; the error
must be there, without ANSI colour codes.

    python3 check_plain_log.py --pvbatch pvbatch --plugin PierceParaView.so --out DIR
"""
import argparse
import os
import subprocess
import sys

SCRIPT = """
import sys
from paraview.simple import LoadPlugin, OpenDataFile
LoadPlugin(sys.argv[1], ns=globals())
OpenDataFile(sys.argv[2]).UpdatePipeline()
"""


def main():
    p = argparse.ArgumentParser()
    for name in ("pvbatch", "plugin", "out"):
        p.add_argument("--" + name, required=True)
    args = p.parse_args()
    script = os.path.join(args.out, "plain_log.py")
    bad = os.path.join(args.out, "not_a_step_file.step")
    open(script, "w").write(SCRIPT)
    open(bad, "w").write("ISO-10303-21; this is not STEP\n")
    env = dict(os.environ, TERM="xterm-256color")
    run = subprocess.run([args.pvbatch, script, args.plugin, bad], capture_output=True, text=True, env=env)
    text = run.stdout + run.stderr
    found = "not a readable STEP file" in text
    plain = "\x1b[" not in text
    print("error reported: %s; ANSI codes: %s" % (found, not plain))
    if not (found and plain):
        print(text[-2000:])
        return 1
    print("plain log ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
