"""ParaView's messages: plain text when stderr is not a terminal, one warning per problem.

- pvbatch loads the plugin and opens a file that is not STEP, with TERM naming a colour terminal
  and stderr a pipe: the error must be there, without ANSI colour codes;
- it opens a solid whose first tessellation folds (pierce_make_test_models' folded.brep), runs
  Pierce Thickness, then makes the reader read the file again: the fold warning appears once.

    python3 check_plain_log.py --pvbatch pvbatch --plugin PierceParaView.so --make-models BIN --out DIR
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

FOLD_SCRIPT = """
import sys
from paraview.simple import LoadPlugin, OpenDataFile
LoadPlugin(sys.argv[1], ns=globals())
reader = OpenDataFile(sys.argv[2])
thickness = PierceThickness(Input=reader)
thickness.UpdatePipeline()
reader.GetClientSideObject().Modified()  # read again, same file and options
reader.SMProxy.MarkModified(reader.SMProxy)
thickness.UpdatePipeline()
"""


def main():
    p = argparse.ArgumentParser()
    for name in ("pvbatch", "plugin", "make-models", "out"):
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

    models = os.path.join(args.out, "models")
    os.makedirs(models, exist_ok=True)
    subprocess.run([args.make_models, models], check=True, capture_output=True)
    script = os.path.join(args.out, "fold_once.py")
    open(script, "w").write(FOLD_SCRIPT)
    run = subprocess.run([args.pvbatch, script, args.plugin, os.path.join(models, "folded.brep")],
                         capture_output=True, text=True)
    text = run.stdout + run.stderr
    folds = text.count("folded triangles on")
    print("fold warnings: %d" % folds)
    if run.returncode != 0 or folds != 1:
        print(text[-2000:])
        return 1
    print("plain log ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
